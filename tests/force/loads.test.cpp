// Tests of include/tumble/force/loads.hpp: loads_need_rotation decides at compile time whether R
// is computed; total_wrench and generalized_force are the sums over the elements (Eq. 1.31); the
// accelerations through the loads equal those through the wrench and through Q (Eq. 1.32), also
// on the path that does not compute R, and with no loads at all (torque-free).

#include "tumble/force/loads.hpp"

#include <limits>

#include "support/body_fixtures.hpp"
#include "support/catch.hpp"
#include "support/parameterizations.hpp"
#include "tumble/force/gravity.hpp"
#include "tumble/force/point_force.hpp"
#include "tumble/force/spring_damper.hpp"
#include "tumble/force/user_force.hpp"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using tumble::BodyMoment;
using tumble::loads_need_rotation;
using tumble::PointForce;
using tumble::ReferencePoint;
using tumble::SpringDamper;
using tumble::UniformGravity;
using tumble::test::rel_error;

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kTol = 256 * kEps;

template <class P, ReferencePoint Ref> using Body = tumble::RigidBody<P, Ref, double>;
template <class P> using Coords = typename tumble::test::State<P>::Coords;
using EP = tumble::EulerParameters;
using Centroidal = Body<EP, ReferencePoint::centroid>;
using Offset = Body<EP, ReferencePoint::offset>;
using Drag = tumble::UserForce<tumble::test::Drag, false>;

// A body framed at its centroid under gravity and moments needs no R ...
static_assert(!loads_need_rotation<Centroidal>);
static_assert(!loads_need_rotation<Centroidal, UniformGravity>);
static_assert(!loads_need_rotation<Centroidal, BodyMoment>);
static_assert(!loads_need_rotation<Centroidal, UniformGravity, BodyMoment, Drag>);
// ... one force at a point, a spring or a user force that reads R makes it needed ...
static_assert(loads_need_rotation<Centroidal, UniformGravity, BodyMoment, PointForce>);
static_assert(loads_need_rotation<Centroidal, SpringDamper>);
static_assert(loads_need_rotation<Centroidal, tumble::UserForce<tumble::test::Drag, true>>);
// ... and off the centroid gravity has a moment, which needs R.
static_assert(loads_need_rotation<Offset, UniformGravity>);
static_assert(!loads_need_rotation<Offset, BodyMoment>);

template <class P, ReferencePoint Ref> void check_sums() {
  tumble::test::Random rng(701);
  for (int b = 0; b < 3; ++b) {
    const auto model = tumble::test::random_body(rng, Ref == ReferencePoint::offset);
    const Body<P, Ref> body(tumble::test::mass_properties(model));
    for (int i = 0; i < 8; ++i) {
      const auto s = tumble::test::random_state<P>(rng);
      const auto loads = tumble::test::random_loads(rng);
      INFO(P::name << " " << tumble::test::ref_name(Ref) << " body " << b << " state " << i);
      tumble::test::with_elements(loads, [&](const auto&... e) {
        // The wrench and Q of all elements are the sums of each element's.
        const auto w = tumble::total_wrench(body, 0.0, s.q, s.qdot, e...);
        tumble::Wrench<double> sum;
        (sum += ... += tumble::total_wrench(body, 0.0, s.q, s.qdot, e));
        CHECK(rel_error(w.force, sum.force) < kTol);
        CHECK(rel_error(w.moment, sum.moment) < kTol);
        const Coords<P> q = tumble::generalized_force(body, 0.0, s.q, s.qdot, e...);
        const Coords<P> q_sum =
            (Coords<P>::Zero() + ... + tumble::generalized_force(body, 0.0, s.q, s.qdot, e));
        CHECK(rel_error(q, q_sum) < kTol);
        CHECK(rel_error(q, Body<P, Ref>::generalized_force(s.q, w)) < kTol);
        // Three routes to qddot.
        const Coords<P> a = tumble::accelerations(body, 0.0, s.q, s.qdot, e...);
        CHECK(rel_error(body.accelerations(s.q, s.qdot, w), a) < kTol);
        const auto k = body.kinematics(s.q, s.qdot);
        CHECK(rel_error(body.accelerations(s.q, s.qdot, k, w), a) < kTol);
        return 0;
      });
    }
  }
}

template <class P> void check_rotation_free_path() {
  // Centroidal body, gravity + moment + drag: R is not computed, and the result equals the path
  // with R and the Newton-Euler solution by hand: a = F / m, I alpha = M - omega x I omega.
  tumble::test::Random rng(702);
  const auto model = tumble::test::random_body(rng, false);
  const Body<P, ReferencePoint::centroid> body(tumble::test::mass_properties(model));
  const UniformGravity gravity(Vector3d(0, 0, -9.81));
  const BodyMoment moment(rng.vector(2.0));
  const auto drag = tumble::make_user_force<false>(tumble::test::Drag{0.3, 0.2});
  static_assert(!loads_need_rotation<Body<P, ReferencePoint::centroid>, UniformGravity, BodyMoment,
                                     decltype(drag)>);
  for (int i = 0; i < 10; ++i) {
    const auto s = tumble::test::random_state<P>(rng);
    INFO(P::name << " state " << i);
    const Coords<P> a = tumble::accelerations(body, 0.0, s.q, s.qdot, gravity, moment, drag);
    const auto k = body.template kinematics<true>(s.q, s.qdot);
    tumble::Wrench<double> w;
    gravity.apply(0.0, k, w);
    moment.apply(0.0, k, w);
    drag.apply(0.0, k, w);
    CHECK(rel_error(body.accelerations(s.q, s.qdot, k, w), a) < kTol);
    const Vector3d force = model.mass * Vector3d(0, 0, -9.81) - 0.3 * s.qdot.template head<3>();
    CHECK(rel_error(Vector3d(a.template head<3>()), Vector3d(force / model.mass)) < kTol);
  }
}

template <class P, ReferencePoint Ref> void check_no_loads() {
  tumble::test::Random rng(703);
  const auto model = tumble::test::random_body(rng, Ref == ReferencePoint::offset);
  const Body<P, Ref> body(tumble::test::mass_properties(model));
  for (int i = 0; i < 5; ++i) {
    const auto s = tumble::test::random_state<P>(rng);
    const Coords<P> a = tumble::accelerations(body, 0.0, s.q, s.qdot);
    CHECK(rel_error(a, body.accelerations(s.q, s.qdot, tumble::Wrench<double>{})) < kTol);
    CHECK(tumble::generalized_force(body, 0.0, s.q, s.qdot).isZero(0));
    // Torque-free: the centroid does not accelerate (Eq. 1.9 with the library's alpha).
    const Vector3d alpha =
        P::G(s.theta()) * a.template tail<P::size>() + P::Gdot_thetadot(s.theta(), s.thetadot());
    const Vector3d rg = model.centroid;
    const Vector3d ag =
        a.template head<3>() + s.R * (alpha.cross(rg) + s.omega.cross(s.omega.cross(rg)));
    CHECK(ag.norm() < kTol * (alpha.norm() + s.omega.squaredNorm()) * (1.0 + rg.norm()));
  }
}

}  // namespace

TEMPLATE_LIST_TEST_CASE("loads: wrench, Q and accelerations are the sums over the elements",
                        "[force][loads]", tumble::test::AllParameterizations) {
  check_sums<TestType, ReferencePoint::centroid>();
  check_sums<TestType, ReferencePoint::offset>();
}

TEMPLATE_LIST_TEST_CASE("loads: the path without R equals the path with R", "[force][loads]",
                        tumble::test::AllParameterizations) {
  check_rotation_free_path<TestType>();
}

TEMPLATE_LIST_TEST_CASE("loads: no elements is the torque-free body", "[force][loads]",
                        tumble::test::AllParameterizations) {
  check_no_loads<TestType, ReferencePoint::centroid>();
  check_no_loads<TestType, ReferencePoint::offset>();
}
