// Tests of tumble::UserForce (include/tumble/force/user_force.hpp): the callable sees the time and
// the body's kinematics, its wrench is added as returned, a force placed with Wrench::add_force
// equals a PointForce, NeedsRotation is declared at compile time, and a non-finite wrench throws
// NonFiniteError.

#include "tumble/force/user_force.hpp"

#include <cmath>
#include <limits>
#include <type_traits>

#include "support/body_fixtures.hpp"
#include "support/catch.hpp"
#include "support/parameterizations.hpp"
#include "tumble/force/loads.hpp"
#include "tumble/force/point_force.hpp"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using tumble::ReferencePoint;
using tumble::test::rel_error;

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kTol = 256 * kEps;

template <class P, ReferencePoint Ref> using Body = tumble::RigidBody<P, Ref, double>;
template <class P> using Coords = typename tumble::test::State<P>::Coords;
using EP = tumble::EulerParameters;

/// A force F(t) = t f0 at the body point rho, inertial components (reads R).
struct RampAtPoint {
  Vector3d rho;
  Vector3d f0;
  template <class S, ReferencePoint Ref>
  tumble::Wrench<S> operator()(const S& t, const tumble::BodyKinematics<S, Ref>& k) const {
    tumble::Wrench<S> w;
    w.add_force(k.rotation, rho.cast<S>(), Vector3d(f0).cast<S>() * t);
    return w;
  }
};

/// Returns a wrench with one entry set to `bad`.
struct Broken {
  int entry;
  double bad;
  template <class S, ReferencePoint Ref>
  tumble::Wrench<S> operator()(const S& /*t*/, const tumble::BodyKinematics<S, Ref>& /*k*/) const {
    tumble::Wrench<S> w;
    (entry < 3 ? w.force(entry) : w.moment(entry - 3)) = S(bad);
    return w;
  }
};

static_assert(tumble::ForceElement<tumble::UserForce<RampAtPoint>>);
static_assert(tumble::ForceElement<tumble::UserForce<tumble::test::Drag, false>>);
static_assert(
    decltype(tumble::make_user_force(RampAtPoint{}))::needs_rotation(ReferencePoint::centroid));
static_assert(!decltype(tumble::make_user_force<false>(tumble::test::Drag{}))::needs_rotation(
    ReferencePoint::centroid));
static_assert(!tumble::loads_need_rotation<Body<EP, ReferencePoint::centroid>,
                                           tumble::UserForce<tumble::test::Drag, false>>);
static_assert(tumble::loads_need_rotation<Body<EP, ReferencePoint::centroid>,
                                          tumble::UserForce<RampAtPoint>>);

template <class P, ReferencePoint Ref> void check_user_force() {
  tumble::test::Random rng(601);
  const auto model = tumble::test::random_body(rng, Ref == ReferencePoint::offset);
  const Body<P, Ref> body(tumble::test::mass_properties(model));
  for (int i = 0; i < 10; ++i) {
    const auto s = tumble::test::random_state<P>(rng);
    const Vector3d rho = rng.vector(0.8), f0 = rng.vector(3.0);
    const double t = rng.uniform(0.0, 5.0);
    INFO(P::name << " " << tumble::test::ref_name(Ref) << " state " << i);

    // A force at a body point through Wrench::add_force is a PointForce (here of size t f0).
    const auto ramp = tumble::make_user_force(RampAtPoint{rho, f0});
    const tumble::PointForce point(rho, t * f0);
    const Coords<P> qu = tumble::generalized_force(body, t, s.q, s.qdot, ramp);
    const Coords<P> qp = tumble::generalized_force(body, 0.0, s.q, s.qdot, point);
    CHECK(rel_error(qu, qp) < kTol);

    // The callable sees the state: a drag -d v_c, -e omega computed here by hand.
    const tumble::test::Drag drag{0.7, 0.4};
    const auto w = tumble::total_wrench(body, t, s.q, s.qdot, tumble::make_user_force<false>(drag));
    CHECK(rel_error(w.force, Vector3d(-0.7 * s.qdot.template head<3>())) < kTol);
    CHECK(rel_error(w.moment, Vector3d(-0.4 * s.omega)) < kTol);

    // A lambda that records what it was given.
    Vector3d seen_position, seen_velocity, seen_omega;
    Matrix3d seen_rotation;
    double seen_t = -1;
    const auto spy = tumble::make_user_force([&](const double& tt, const auto& k) {
      seen_t = tt;
      seen_position = k.position;
      seen_velocity = k.velocity;
      seen_omega = k.omega;
      seen_rotation = k.rotation;
      CHECK(k.mass_properties == &body.mass_properties());
      return tumble::Wrench<double>{};
    });
    const auto w0 = tumble::total_wrench(body, t, s.q, s.qdot, spy);
    CHECK(seen_t == t);
    CHECK(seen_position == s.q.template head<3>());
    CHECK(seen_velocity == s.qdot.template head<3>());
    CHECK(rel_error(seen_omega, s.omega) < kTol);
    CHECK(rel_error(seen_rotation, s.R) < kTol);
    CHECK(w0.force.isZero(0));
    CHECK(w0.moment.isZero(0));
  }
}

}  // namespace

TEMPLATE_LIST_TEST_CASE("a user force sees the kinematics and adds its wrench",
                        "[force][user_force]", tumble::test::AllParameterizations) {
  check_user_force<TestType, ReferencePoint::centroid>();
  check_user_force<TestType, ReferencePoint::offset>();
}

TEST_CASE("a user force returning a non-finite wrench throws NonFiniteError",
          "[force][user_force]") {
  using B = Body<EP, ReferencePoint::offset>;
  const B body(tumble::MassProperties<double>::about_centroid(1.0, Matrix3d::Identity(),
                                                              Vector3d(0.1, 0, 0)));
  Coords<EP> q, qdot;
  q << 0, 0, 0, 1, 0, 0, 0;
  qdot << 1, 0, 0, 0, 0.1, 0, 0;
  for (const double bad :
       {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    for (int entry = 0; entry < 6; ++entry) {
      INFO("entry " << entry << " value " << bad);
      const auto user = tumble::make_user_force(Broken{entry, bad});
      REQUIRE_THROWS_AS(tumble::accelerations(body, 0.0, q, qdot, user), tumble::NonFiniteError);
      REQUIRE_THROWS_WITH(tumble::accelerations(body, 0.0, q, qdot, user),
                          TUMBLE_CONTAINS("the user force returned a non-finite wrench"));
      REQUIRE_THROWS_AS(tumble::generalized_force(body, 0.0, q, qdot, user),
                        tumble::NonFiniteError);
    }
  }
}
