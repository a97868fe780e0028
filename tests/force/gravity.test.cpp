// Tests of tumble::UniformGravity (include/tumble/force/gravity.hpp): the force m g at the
// centroid. Its generalized force is L_r(r_g)^T m g (Eq. 1.28), the gradient of the potential
// energy -m g . r_og(q), and equals a PointForce at the centroid; a body under gravity alone has
// its centroid falling with g and turns torque-free.

#include "tumble/force/gravity.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "support/body_fixtures.hpp"
#include "support/catch.hpp"
#include "support/parameterizations.hpp"
#include "tumble/force/loads.hpp"
#include "tumble/force/point_force.hpp"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using tumble::ReferencePoint;
using tumble::UniformGravity;
using tumble::test::AD;
using tumble::test::rel_error;

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kTol = 256 * kEps;

template <class P, ReferencePoint Ref> using Body = tumble::RigidBody<P, Ref, double>;
template <class P> using Coords = typename tumble::test::State<P>::Coords;

static_assert(tumble::ForceElement<UniformGravity>);
static_assert(!UniformGravity::needs_rotation(ReferencePoint::centroid));
static_assert(UniformGravity::needs_rotation(ReferencePoint::offset));

template <class P, ReferencePoint Ref> void check_gravity() {
  constexpr int nq = 3 + P::size;
  tumble::test::Random rng(301);
  const Vector3d g(0.3, -0.2, -9.81);
  const UniformGravity gravity(g);
  for (int b = 0; b < 3; ++b) {
    const auto model = tumble::test::random_body(rng, Ref == ReferencePoint::offset);
    const Body<P, Ref> body(tumble::test::mass_properties(model));
    const Vector3d weight = model.mass * g;
    const tumble::PointForce at_centroid(model.centroid, weight, tumble::Components::inertial);
    for (int i = 0; i < 10; ++i) {
      const auto s = tumble::test::random_state<P>(rng);
      INFO(P::name << " " << tumble::test::ref_name(Ref) << " body " << b << " state " << i);
      const auto w = tumble::total_wrench(body, 0.0, s.q, s.qdot, gravity);
      const Coords<P> q = tumble::generalized_force(body, 0.0, s.q, s.qdot, gravity);

      // Eq. (1.28) with L_r of the centroid from the library's point Jacobian.
      const Coords<P> expected =
          Body<P, Ref>::point_jacobian(s.q, model.centroid).transpose() * weight;
      CHECK(rel_error(q, expected) < kTol);
      CHECK(rel_error(w.force, weight) < kTol);

      // The same as a force m g at the centroid.
      const auto wp = tumble::total_wrench(body, 0.0, s.q, s.qdot, at_centroid);
      CHECK(rel_error(w.force, wp.force) < kTol);
      CHECK((w.moment - wp.moment).norm() <= kTol * weight.norm() * (1 + model.centroid.norm()));

      if constexpr (Ref == ReferencePoint::centroid) {
        // A pure force through the reference point: no moment, no generalized attitude force.
        CHECK(w.moment.isZero(0));
        CHECK(q.template tail<P::size>().isZero(0));
      }

      // Q = -dV/dq with V = -m g . r_og(q): the gradient by AD, on the tangent space of the
      // constraint for Euler parameters.
      const auto q_ad = tumble::test::seeded(s.q, nq);
      const auto rg_ad = tumble::RigidBody<P, Ref, AD>::point_position(
          q_ad, tumble::test::constant(model.centroid));
      const AD potential = -(tumble::test::constant(weight).dot(rg_ad));
      const Coords<P> grad = potential.derivatives();
      const auto t = tumble::test::tangent_projector(s);
      CHECK(rel_error(Coords<P>(t * q), Coords<P>(-(t * grad))) < kTol);
    }
  }
}

template <class P, ReferencePoint Ref> void check_free_fall() {
  // Gravity alone: the centroid accelerates with g, and the rotation is torque-free about the
  // centroid (Euler's equations I_g alpha = -omega x I_g omega).
  tumble::test::Random rng(302);
  const Vector3d g(0.0, 0.0, -9.81);
  const UniformGravity gravity(g);
  for (int i = 0; i < 10; ++i) {
    const auto model = tumble::test::random_body(rng, Ref == ReferencePoint::offset);
    const Body<P, Ref> body(tumble::test::mass_properties(model));
    const auto s = tumble::test::random_state<P>(rng);
    INFO(P::name << " " << tumble::test::ref_name(Ref) << " case " << i);
    const Coords<P> qdd = tumble::accelerations(body, 0.0, s.q, s.qdot, gravity);
    const auto th = s.theta();
    const Vector3d alpha =
        P::G(th) * qdd.template tail<P::size>() + P::Gdot_thetadot(th, s.thetadot());
    const Vector3d rg = model.centroid;
    const Vector3d ag =
        qdd.template head<3>() + s.R * (alpha.cross(rg) + s.omega.cross(s.omega.cross(rg)));
    const Matrix3d& ig = model.inertia_centroid;
    const Vector3d gyro = s.omega.cross(ig * s.omega);
    const double smallest = Eigen::SelfAdjointEigenSolver<Matrix3d>(ig).eigenvalues()(0);
    CHECK((ig * alpha + gyro).norm() < kTol * (gyro.norm() + ig.norm() * alpha.norm()));
    CHECK((ag - g).norm() <
          kTol * (g.norm() + (gyro.norm() / smallest + s.omega.squaredNorm()) * rg.norm()));
  }
}

}  // namespace

TEMPLATE_LIST_TEST_CASE("gravity is m g at the centroid: Q = L_r^T m g = -grad V",
                        "[force][gravity]", tumble::test::AllParameterizations) {
  check_gravity<TestType, ReferencePoint::centroid>();
  check_gravity<TestType, ReferencePoint::offset>();
}

TEMPLATE_LIST_TEST_CASE("under gravity alone the centroid falls with g, the rotation is free",
                        "[force][gravity]", tumble::test::AllParameterizations) {
  check_free_fall<TestType, ReferencePoint::centroid>();
  check_free_fall<TestType, ReferencePoint::offset>();
}

TEST_CASE("gravity on a centroidal body needs no rotation matrix", "[force][gravity]") {
  using Centroidal = Body<tumble::EulerParameters, ReferencePoint::centroid>;
  using Offset = Body<tumble::EulerParameters, ReferencePoint::offset>;
  static_assert(!tumble::loads_need_rotation<Centroidal, UniformGravity>);
  static_assert(tumble::loads_need_rotation<Offset, UniformGravity>);
  // The rotation-free path gives the hand result m g, no moment.
  const Centroidal body(tumble::MassProperties<double>::about_centroid(2.0, Matrix3d::Identity()));
  Coords<tumble::EulerParameters> q, qdot;
  q << 1.0, 2.0, 3.0, 0.5, 0.5, 0.5, 0.5;
  qdot << 0.1, 0.2, 0.3, 0.0, 0.1, -0.1, 0.0;
  const auto w = tumble::total_wrench(body, 0.0, q, qdot, UniformGravity(Vector3d(0, 0, -9.81)));
  CHECK(w.force == Vector3d(0.0, 0.0, -19.62));
  CHECK(w.moment.isZero(0));
}

TEST_CASE("gravity rejects a non-finite g", "[force][gravity]") {
  for (const double bad :
       {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    REQUIRE_THROWS_AS(UniformGravity(Vector3d(0.0, bad, -9.81)), std::invalid_argument);
    REQUIRE_THROWS_WITH(UniformGravity(Vector3d(0.0, bad, -9.81)),
                        TUMBLE_CONTAINS("g has a non-finite entry"));
  }
  CHECK(UniformGravity(Vector3d(0.0, 0.0, -9.81)).g() == Vector3d(0.0, 0.0, -9.81));
}
