// Tests of tumble::PointForce and tumble::BodyMoment (include/tumble/force/point_force.hpp):
// wrenches by hand, the generalized force of a force at a point Q = L_r^T F (Eq. 1.28) in both
// components, its virtual work F . delta r_p against AD of the point position (Eqs. 1.13-1.15),
// the generalized force of a moment [0; G^T M] (Eq. 1.31), and the validation of the inputs.

#include "tumble/force/point_force.hpp"

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
using tumble::BodyMoment;
using tumble::Components;
using tumble::PointForce;
using tumble::ReferencePoint;
using tumble::test::AD;
using tumble::test::rel_error;

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kTol = 256 * kEps;

template <class P, ReferencePoint Ref> using Body = tumble::RigidBody<P, Ref, double>;
template <class P> using Coords = typename tumble::test::State<P>::Coords;

static_assert(tumble::ForceElement<PointForce>);
static_assert(tumble::ForceElement<BodyMoment>);
static_assert(PointForce::needs_rotation(ReferencePoint::centroid));
static_assert(!BodyMoment::needs_rotation(ReferencePoint::centroid));
static_assert(!BodyMoment::needs_rotation(ReferencePoint::offset));

}  // namespace

TEST_CASE("point force and moment wrenches by hand", "[force][point_force]") {
  // A body turned by 90 degrees about z (R maps body x to inertial y), at the origin.
  using B = Body<tumble::EulerParameters, ReferencePoint::centroid>;
  const B body(tumble::MassProperties<double>::about_centroid(1.0, Matrix3d::Identity()));
  const double h = std::sqrt(0.5);
  Coords<tumble::EulerParameters> q, qdot;
  q << 0.0, 0.0, 0.0, h, 0.0, 0.0, h;
  qdot.setZero();
  const Vector3d rho(1.0, 0.0, 0.0);  // body x, inertial y

  // Inertial force (0, 2, 0) at body x: in body components (2, 0, 0), parallel to rho: no moment.
  const auto w1 = tumble::total_wrench(body, 0.0, q, qdot,
                                       PointForce(rho, Vector3d(0, 2, 0), Components::inertial));
  CHECK((w1.force - Vector3d(0, 2, 0)).norm() < kTol);
  CHECK(w1.moment.norm() < 2 * kTol);

  // Body force (0, 2, 0) at body x: inertial (-2, 0, 0); moment (1, 0, 0) x (0, 2, 0) = (0, 0, 2).
  const auto w2 = tumble::total_wrench(body, 0.0, q, qdot,
                                       PointForce(rho, Vector3d(0, 2, 0), Components::body));
  CHECK((w2.force - Vector3d(-2, 0, 0)).norm() < 2 * kTol);
  CHECK((w2.moment - Vector3d(0, 0, 2)).norm() < kTol);

  // Inertial force (2, 0, 0) at body x: body components (0, -2, 0); moment (0, 0, -2).
  const auto w3 = tumble::total_wrench(body, 0.0, q, qdot,
                                       PointForce(rho, Vector3d(2, 0, 0), Components::inertial));
  CHECK((w3.moment - Vector3d(0, 0, -2)).norm() < 2 * kTol);

  // A moment is passed through in body components, no force.
  const auto w4 = tumble::total_wrench(body, 0.0, q, qdot, BodyMoment(Vector3d(1, -2, 3)));
  CHECK(w4.force.isZero(0));
  CHECK(w4.moment == Vector3d(1, -2, 3));

  // The default components are inertial.
  const auto w5 = tumble::total_wrench(body, 0.0, q, qdot, PointForce(rho, Vector3d(2, 0, 0)));
  CHECK((w5.moment - w3.moment).norm() == 0);
}

namespace {

template <class P, ReferencePoint Ref> void check_point_force() {
  constexpr int nq = 3 + P::size;
  tumble::test::Random rng(401);
  double worst = 0;
  for (int b = 0; b < 3; ++b) {
    const auto model = tumble::test::random_body(rng, Ref == ReferencePoint::offset);
    const Body<P, Ref> body(tumble::test::mass_properties(model));
    for (int i = 0; i < 10; ++i) {
      const auto s = tumble::test::random_state<P>(rng);
      const Vector3d rho = rng.vector(0.8);
      const Vector3d f = rng.vector(4.0);
      const Vector3d m = rng.vector(2.0);
      INFO(P::name << " " << tumble::test::ref_name(Ref) << " body " << b << " state " << i);
      const auto l = Body<P, Ref>::point_jacobian(s.q, rho);

      // Eq. (1.28): Q = L_r^T F, F inertial; a body-fixed force has inertial components R F.
      const Coords<P> qi = tumble::generalized_force(body, 0.0, s.q, s.qdot,
                                                     PointForce(rho, f, Components::inertial));
      const Coords<P> qb =
          tumble::generalized_force(body, 0.0, s.q, s.qdot, PointForce(rho, f, Components::body));
      const double ei = rel_error(qi, Coords<P>(l.transpose() * f));
      const double eb = rel_error(qb, Coords<P>(l.transpose() * (s.R * f)));
      CHECK(ei < kTol);
      CHECK(eb < kTol);

      // Virtual work (Eqs. 1.13, 1.29): Q . dq = F . dr_p for every admissible dq, with dr_p by
      // AD of the point position (Eq. 1.1) along dq.
      Coords<P> dq = tumble::test::random_vector<nq>(rng);
      dq = tumble::test::tangent_projector(s) * dq;
      const auto r_ad = tumble::RigidBody<P, Ref, AD>::point_position(tumble::test::along(s.q, dq),
                                                                      tumble::test::constant(rho));
      const Vector3d dr = tumble::test::derivative(r_ad);
      const double ew = std::abs(qi.dot(dq) - f.dot(dr)) / (qi.cwiseAbs().dot(dq.cwiseAbs()));
      CHECK(ew < kTol);

      // Eq. (1.31): a moment M (body) has Q = [0; G^T M], and virtual work M . G dtheta.
      const Coords<P> qm = tumble::generalized_force(body, 0.0, s.q, s.qdot, BodyMoment(m));
      Coords<P> expected = Coords<P>::Zero();
      expected.template tail<P::size>() = P::G(s.theta()).transpose() * m;
      const double em = rel_error(qm, expected);
      CHECK(em < kTol);
      CHECK(qm.template head<3>().isZero(0));
      worst = std::max({worst, ei, eb, ew, em});
    }
  }
  tumble::test::record_error("point force / moment Q vs L^T F", P::name, Ref, worst);
}

}  // namespace

TEMPLATE_LIST_TEST_CASE("generalized force of a point force is L_r^T F (Eq. 1.28)",
                        "[force][point_force]", tumble::test::AllParameterizations) {
  check_point_force<TestType, ReferencePoint::centroid>();
  check_point_force<TestType, ReferencePoint::offset>();
}

TEST_CASE("point forces and moments reject non-finite input", "[force][point_force]") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const double bad : {nan, inf}) {
    REQUIRE_THROWS_AS(PointForce(Vector3d(bad, 0, 0), Vector3d(1, 0, 0)), std::invalid_argument);
    REQUIRE_THROWS_WITH(PointForce(Vector3d(bad, 0, 0), Vector3d(1, 0, 0)),
                        TUMBLE_CONTAINS("the point or the force is not finite"));
    REQUIRE_THROWS_WITH(PointForce(Vector3d(0, 0, 0), Vector3d(1, bad, 0), Components::body),
                        TUMBLE_CONTAINS("the point or the force is not finite"));
    REQUIRE_THROWS_AS(BodyMoment(Vector3d(0, 0, bad)), std::invalid_argument);
    REQUIRE_THROWS_WITH(BodyMoment(Vector3d(0, 0, bad)),
                        TUMBLE_CONTAINS("the moment is not finite"));
  }
}
