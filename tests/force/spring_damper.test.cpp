// Tests of tumble::SpringDamper (include/tumble/force/spring_damper.hpp): the force by hand for a
// stretched and a compressed spring, the sign of the damping, the isotropic spring (L0 = 0), the
// conservative part as the gradient of 1/2 k (L - L0)^2 and the dissipation rate -c Ldot^2 (both
// by AD along the motion), Q = L_r^T F (Eq. 1.28), and every rejection.

#include "tumble/force/spring_damper.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "support/body_fixtures.hpp"
#include "support/catch.hpp"
#include "support/parameterizations.hpp"
#include "tumble/force/loads.hpp"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using tumble::ReferencePoint;
using tumble::SpringDamper;
using tumble::SpringDamperParameters;
using tumble::test::AD;
using tumble::test::rel_error;

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kTol = 256 * kEps;

template <class P, ReferencePoint Ref> using Body = tumble::RigidBody<P, Ref, double>;
template <class P> using Coords = typename tumble::test::State<P>::Coords;
using EP = tumble::EulerParameters;
using Centroidal = Body<EP, ReferencePoint::centroid>;

static_assert(tumble::ForceElement<SpringDamper>);
static_assert(SpringDamper::needs_rotation(ReferencePoint::centroid));

/// The wrench of `spring` on a unit body at the origin, not rotated, with velocity v and
/// angular velocity w (body = inertial components here).
tumble::Wrench<double> wrench(const SpringDamper& spring, const Vector3d& v = Vector3d::Zero(),
                              const Vector3d& w = Vector3d::Zero()) {
  const Centroidal body(tumble::MassProperties<double>::about_centroid(1.0, Matrix3d::Identity()));
  Coords<EP> q, qdot;
  q << 0, 0, 0, 1, 0, 0, 0;
  qdot << v, EP::thetadot(Eigen::Vector4d(1, 0, 0, 0), w);
  return tumble::total_wrench(body, 0.0, q, qdot, spring);
}

}  // namespace

TEST_CASE("spring-damper force by hand", "[force][spring_damper]") {
  const Vector3d tip(1, 0, 0);  // the body point, at (1, 0, 0) in both frames

  SECTION("stretched: pulls the point towards the anchor") {
    // L = 3, L0 = 1, k = 10: tension 20 along +y; moment (1, 0, 0) x (0, 20, 0) = (0, 0, 20).
    const auto w = wrench(SpringDamper(tip, Vector3d(1, 3, 0), {10.0, 0.0, 1.0}));
    CHECK((w.force - Vector3d(0, 20, 0)).norm() < kTol * 20);
    CHECK((w.moment - Vector3d(0, 0, 20)).norm() < kTol * 20);
  }
  SECTION("compressed: pushes the point away from the anchor") {
    // L = 0.5, L0 = 1, k = 10: tension -5, force (0, -5, 0).
    const auto w = wrench(SpringDamper(tip, Vector3d(1, 0.5, 0), {10.0, 0.0, 1.0}));
    CHECK((w.force - Vector3d(0, -5, 0)).norm() < kTol * 5);
    CHECK((w.moment - Vector3d(0, 0, -5)).norm() < kTol * 5);
  }
  SECTION("at rest length: no force") {
    const auto w = wrench(SpringDamper(tip, Vector3d(1, 2, 0), {10.0, 0.0, 2.0}));
    CHECK(w.force.norm() < kTol * 10);
  }
  SECTION("damping opposes the approach, by translation or by rotation") {
    // The point moves towards the anchor at 1 m/s: Ldot = -1, tension c Ldot = -4, force -4 y.
    const SpringDamper damper(tip, Vector3d(1, 3, 0), {0.0, 4.0, 1.0});
    const auto wv = wrench(damper, Vector3d(0, 1, 0));
    CHECK((wv.force - Vector3d(0, -4, 0)).norm() < kTol * 4);
    // The same point velocity from omega = (0, 0, 1): omega x (1, 0, 0) = (0, 1, 0).
    const auto ww = wrench(damper, Vector3d::Zero(), Vector3d(0, 0, 1));
    CHECK((ww.force - Vector3d(0, -4, 0)).norm() < kTol * 4);
    // Moving away, the damper pulls back.
    const auto wa = wrench(damper, Vector3d(0, -0.5, 0));
    CHECK((wa.force - Vector3d(0, 2, 0)).norm() < kTol * 4);
    // A velocity across the spring does not change its length: no damping force.
    const auto wx = wrench(damper, Vector3d(0, 0, 1));
    CHECK(wx.force.norm() < kTol * 4);
  }
  SECTION("zero rest length: the isotropic spring k d - c v, also with coincident ends") {
    const SpringDamperParameters sd{10.0, 2.0, 0.0};
    const auto w = wrench(SpringDamper(tip, Vector3d(2, 2, -1), sd), Vector3d(0.5, 0, 0.25));
    // d = (1, 2, -1), v_p = (0.5, 0, 0.25): 10 d - 2 v_p.
    CHECK((w.force - Vector3d(9, 20, -10.5)).norm() < kTol * 25);
    const auto w0 = wrench(SpringDamper(tip, tip, sd), Vector3d(0.5, 0, 0.25));
    CHECK((w0.force - Vector3d(-1, 0, -0.5)).norm() < kTol);
  }
}

TEST_CASE("coincident ends of a spring with a rest length throw NonFiniteError",
          "[force][spring_damper]") {
  const SpringDamper spring(Vector3d(1, 0, 0), Vector3d(1, 0, 0), {10.0, 1.0, 0.5});
  REQUIRE_THROWS_AS(wrench(spring), tumble::NonFiniteError);
  REQUIRE_THROWS_WITH(wrench(spring), TUMBLE_CONTAINS("the two ends coincide"));
}

TEST_CASE("invalid spring-damper parameters throw std::invalid_argument",
          "[force][spring_damper]") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const Vector3d p(1, 0, 0), a(0, 0, 1);
  for (const SpringDamperParameters& sd :
       {SpringDamperParameters{-1.0, 0.0, 0.0}, SpringDamperParameters{1.0, -0.1, 0.0},
        SpringDamperParameters{1.0, 0.0, -1.0}, SpringDamperParameters{nan, 0.0, 0.0},
        SpringDamperParameters{1.0, nan, 0.0}, SpringDamperParameters{1.0, 0.0, nan},
        SpringDamperParameters{inf, 0.0, 0.0}}) {
    INFO("k " << sd.stiffness << " c " << sd.damping << " L0 " << sd.rest_length);
    REQUIRE_THROWS_AS(SpringDamper(p, a, sd), std::invalid_argument);
    REQUIRE_THROWS_WITH(SpringDamper(p, a, sd),
                        TUMBLE_CONTAINS("stiffness, damping and rest length must be finite"));
  }
  REQUIRE_THROWS_WITH(SpringDamper(Vector3d(nan, 0, 0), a, {1.0, 0.0, 0.0}),
                      TUMBLE_CONTAINS("the point or the anchor is not finite"));
  REQUIRE_THROWS_WITH(SpringDamper(p, Vector3d(0, inf, 0), {1.0, 0.0, 0.0}),
                      TUMBLE_CONTAINS("the point or the anchor is not finite"));
  const SpringDamper ok(p, a, {1.0, 2.0, 3.0});
  CHECK(ok.parameters().stiffness == 1.0);
  CHECK(ok.parameters().damping == 2.0);
  CHECK(ok.parameters().rest_length == 3.0);
}

namespace {

template <class P, ReferencePoint Ref> void check_spring_energy() {
  constexpr int nq = 3 + P::size;
  tumble::test::Random rng(501);
  double worst = 0;
  for (int b = 0; b < 3; ++b) {
    const auto model = tumble::test::random_body(rng, Ref == ReferencePoint::offset);
    const Body<P, Ref> body(tumble::test::mass_properties(model));
    for (int i = 0; i < 10; ++i) {
      const auto s = tumble::test::random_state<P>(rng);
      const Vector3d rho = rng.vector(0.8);
      const Vector3d anchor = rng.vector(2.0);
      const double k = rng.uniform(1.0, 50.0), c = rng.uniform(0.1, 5.0);
      const double l0 = i % 3 == 0 ? 0.0 : rng.uniform(0.2, 2.0);
      INFO(P::name << " " << tumble::test::ref_name(Ref) << " body " << b << " state " << i
                   << " L0 " << l0);
      const auto l = Body<P, Ref>::point_jacobian(s.q, rho);
      const Vector3d p = tumble::test::point_position(s, rho);
      const Vector3d vp = tumble::test::point_velocity(s, rho);

      // Eq. (1.28) with the force computed by hand.
      const SpringDamper both(rho, anchor, {k, c, l0});
      const Vector3d f = tumble::test::spring_force({k, c, l0}, p, vp, anchor);
      const Coords<P> q = tumble::generalized_force(body, 0.0, s.q, s.qdot, both);
      const double eq = rel_error(q, Coords<P>(l.transpose() * f));
      CHECK(eq < kTol);

      // The spring alone is conservative: Q = -dV/dq, V = 1/2 k (L - L0)^2 with
      // L = |anchor - r_op(q)| (gradient by AD; tangent space for Euler parameters).
      const SpringDamper spring(rho, anchor, {k, 0.0, l0});
      const Coords<P> qs = tumble::generalized_force(body, 0.0, s.q, s.qdot, spring);
      const auto r_ad = tumble::RigidBody<P, Ref, AD>::point_position(tumble::test::seeded(s.q, nq),
                                                                      tumble::test::constant(rho));
      const Eigen::Matrix<AD, 3, 1> d_ad = tumble::test::constant(anchor) - r_ad;
      const AD len = sqrt(d_ad.squaredNorm());
      const AD v = AD(0.5 * k) * (len - AD(l0)) * (len - AD(l0));
      const Coords<P> grad = v.derivatives();
      const auto t = tumble::test::tangent_projector(s);
      const double ev = rel_error(Coords<P>(t * qs), Coords<P>(-(t * grad)));
      CHECK(ev < kTol);

      // The damper alone dissipates: its power F . v_p = qdot^T Q equals -c Ldot^2 <= 0, with
      // Ldot by AD along the motion.
      const SpringDamper damper(rho, anchor, {0.0, c, l0});
      const Coords<P> qd = tumble::generalized_force(body, 0.0, s.q, s.qdot, damper);
      const auto r_t = tumble::RigidBody<P, Ref, AD>::point_position(
          tumble::test::along(s.q, s.qdot), tumble::test::constant(rho));
      const Eigen::Matrix<AD, 3, 1> d_t = tumble::test::constant(anchor) - r_t;
      const double power = s.qdot.dot(qd);
      double expected = 0;
      if (l0 == 0) {
        expected = -c * vp.squaredNorm();  // F = -c v_p
      } else {
        const double len_dot = sqrt(d_t.squaredNorm()).derivatives()(0);
        expected = -c * len_dot * len_dot;
      }
      CHECK(power <= 0);
      const double ep = std::abs(power - expected) / (c * vp.squaredNorm());
      CHECK(ep < kTol);
      worst = std::max({worst, eq, ev, ep});
    }
  }
  tumble::test::record_error("spring Q, potential, dissipation", P::name, Ref, worst);
}

}  // namespace

TEMPLATE_LIST_TEST_CASE("spring-damper: Q = L_r^T F, conservative spring, dissipative damper",
                        "[force][spring_damper]", tumble::test::AllParameterizations) {
  check_spring_energy<TestType, ReferencePoint::centroid>();
  check_spring_energy<TestType, ReferencePoint::offset>();
}
