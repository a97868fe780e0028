// Tests of tumble::RigidBody (include/tumble/body/rigid_body.hpp) against the reference chapter
// evaluated independently in the test (tests/support/body_fixtures.hpp):
//   - M (Eq. 1.23) and f_v (Eqs. 1.26, 1.27) against the sums over point masses of Eqs. (1.18),
//     (1.19), with L_i and a_v,i built from P::rotation, P::G, P::Gdot_thetadot (Eqs. 1.8, 1.11);
//   - the point Jacobian against AD of the point position (Eq. 1.14), the velocity and
//     acceleration of a point against AD along the motion (Eqs. 1.7, 1.12);
//   - the accelerations (closed-form Newton-Euler) against the residual of Eq. (1.32) and a dense
//     LU of M (of the constrained system [M, C^T; C, 0] for Euler parameters), with every kind of
//     load, and with a generalized force given directly;
//   - non-finite states and loads, and the centroid check.
// The float, long double and AD bodies are tested in rigid_body_scalar_types.test.cpp.
// Every parameterization in tests/support/parameterizations.hpp, both reference points.

#include "tumble/body/rigid_body.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Dense>

#include "support/body_fixtures.hpp"
#include "support/catch.hpp"
#include "support/parameterizations.hpp"
#include "tumble/force/loads.hpp"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using tumble::ReferencePoint;
using tumble::test::AD;
using tumble::test::record_error;
using tumble::test::rel_error;

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// M, f_v and Q are sums of a few products of up to five 3 x 3 factors (R, S, G, I): a few hundred
// roundings of relative size eps at most, relative to the largest entry.
constexpr double kTol = 256 * kEps;

template <class P, ReferencePoint Ref> using Body = tumble::RigidBody<P, Ref, double>;
template <class P, ReferencePoint Ref> using BodyAD = tumble::RigidBody<P, Ref, AD>;
template <class P> using Coords = typename tumble::test::State<P>::Coords;

constexpr bool offset(ReferencePoint r) { return r == ReferencePoint::offset; }

/// Condition number of a square matrix (2-norm), for forward-error bounds of a linear solve.
template <class M> double condition(const M& m) {
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd{Eigen::MatrixXd(m)};
  const auto& sv = svd.singularValues();
  return sv(0) / sv(sv.size() - 1);
}

// --- M and f_v against the point-mass sums -------------------------------------------------------

template <class P, ReferencePoint Ref> void check_mass_matrix_and_fv() {
  tumble::test::Random rng(101);
  double worst_m = 0, worst_f = 0, worst_gd = 0;
  for (int b = 0; b < 4; ++b) {
    const auto model = tumble::test::random_body(rng, offset(Ref));
    for (const bool via_reference : {false, true}) {
      const Body<P, Ref> body(tumble::test::mass_properties(model, via_reference));
      for (int i = 0; i < 8; ++i) {
        const auto s = tumble::test::random_state<P>(rng);
        INFO(P::name << " " << tumble::test::ref_name(Ref) << " body " << b << " via_reference "
                     << via_reference << " state " << i);

        // Gdot thetadot, which the test's f_v takes from P, checked first by AD:
        // d/dt [G(theta + t thetadot) thetadot] at t = 0 (Eq. 1.10).
        const auto g_ad = P::G(tumble::test::along(s.theta(), s.thetadot()));
        const Eigen::Matrix<AD, 3, 1> w_ad = g_ad * tumble::test::constant(s.thetadot());
        const Vector3d gd_expected = tumble::test::derivative(w_ad);
        const Vector3d gd = P::Gdot_thetadot(s.theta(), s.thetadot());
        const double gd_scale = std::max(gd_expected.norm(), s.omega.squaredNorm());
        const double egd = (gd - gd_expected).norm() / gd_scale;
        CHECK(egd < kTol);
        worst_gd = std::max(worst_gd, egd);

        const auto m = body.mass_matrix(s.q);
        const auto m_cloud = tumble::test::cloud_mass_matrix(model, s);
        const double em =
            tumble::test::scaled_error(m, m_cloud, tumble::test::cloud_mass_matrix_scale(model, s));
        CHECK(em < kTol);
        CHECK(rel_error(m, m.transpose().eval()) < kTol);
        worst_m = std::max(worst_m, em);

        const auto f = body.centrifugal_coriolis(s.q, s.qdot);
        const auto f_cloud = tumble::test::cloud_centrifugal_coriolis(model, s);
        const double ef = tumble::test::scaled_error(
            f, f_cloud, tumble::test::cloud_centrifugal_coriolis_scale(model, s));
        CHECK(ef < kTol);
        worst_f = std::max(worst_f, ef);
        if constexpr (!offset(Ref)) {
          // Eq. (1.33): no translational part at the centroid, exactly.
          CHECK(f.template head<3>().isZero(0));
          CHECK(m.template topRightCorner<3, P::size>().isZero(0));
        }
      }
    }
  }
  record_error("M vs point masses", P::name, Ref, worst_m);
  record_error("f_v vs point masses", P::name, Ref, worst_f);
  record_error("Gdot thetadot vs AD", P::name, Ref, worst_gd);
}

}  // namespace

TEMPLATE_LIST_TEST_CASE("mass matrix and f_v equal the sums over point masses (Eqs. 1.18, 1.19)",
                        "[body][rigid_body]", TUMBLE_TEST_PARAMETERIZATIONS) {
  check_mass_matrix_and_fv<TestType, ReferencePoint::centroid>();
  check_mass_matrix_and_fv<TestType, ReferencePoint::offset>();
}

// --- point kinematics ----------------------------------------------------------------------------

namespace {

template <class P, ReferencePoint Ref> void check_point_kinematics() {
  constexpr int nq = 3 + P::size;
  tumble::test::Random rng(102);
  double worst_l = 0, worst_a = 0;
  for (int i = 0; i < 20; ++i) {
    const auto s = tumble::test::random_state<P>(rng);
    const Vector3d rho = rng.vector(0.8);
    INFO(P::name << " " << tumble::test::ref_name(Ref) << " state " << i);

    // Eq. (1.14): L_r = d r_op / d q, the Jacobian by AD of Eq. (1.1). For Euler parameters only
    // on the tangent space of |p| = 1: R(p) r is quadratic in p, and L_r p = 0 by construction.
    const auto q_ad = tumble::test::seeded(s.q, nq);
    const auto r_ad = BodyAD<P, Ref>::point_position(q_ad, tumble::test::constant(rho));
    Eigen::Matrix<double, 3, nq> jac;
    for (int k = 0; k < 3; ++k) {
      jac.row(k) = r_ad(k).derivatives().transpose();
    }
    const auto l = Body<P, Ref>::point_jacobian(s.q, rho);
    const auto t = tumble::test::tangent_projector(s);
    const double el = rel_error((l * t).eval(), (jac * t).eval());
    CHECK(el < kTol);
    CHECK(rel_error(l, tumble::test::jacobian(s, rho)) < kTol);
    worst_l = std::max(worst_l, el);

    // Eq. (1.7): rdot_op = L_r qdot.
    CHECK(rel_error(Body<P, Ref>::point_velocity(s.q, s.qdot, rho), (l * s.qdot).eval()) < kTol);

    // Eq. (1.12): d/dt rdot_op = L_r qddot + a_v for any qddot, the derivative by AD along
    // q + t qdot, qdot + t qddot.
    const Coords<P> qdd = tumble::test::random_vector<3 + P::size>(rng, 3.0);
    const auto v_ad = BodyAD<P, Ref>::point_velocity(tumble::test::along(s.q, s.qdot),
                                                     tumble::test::along(s.qdot, qdd),
                                                     tumble::test::constant(rho));
    const Vector3d a_expected = tumble::test::derivative(v_ad);
    const Vector3d av = Body<P, Ref>::point_velocity_acceleration(s.q, s.qdot, rho);
    const double ea = rel_error(Vector3d(l * qdd + av), a_expected);
    CHECK(ea < kTol);
    CHECK(rel_error(Body<P, Ref>::point_acceleration(s.q, s.qdot, qdd, rho), a_expected) < kTol);
    CHECK(rel_error(av, tumble::test::velocity_acceleration(s, rho)) < kTol);
    worst_a = std::max(worst_a, ea);
  }
  record_error("L_r vs AD", P::name, Ref, worst_l);
  record_error("point acceleration vs AD", P::name, Ref, worst_a);
}

}  // namespace

TEMPLATE_LIST_TEST_CASE("point Jacobian, velocity and acceleration against AD (Eqs. 1.7-1.14)",
                        "[body][rigid_body]", TUMBLE_TEST_PARAMETERIZATIONS) {
  check_point_kinematics<TestType, ReferencePoint::centroid>();
  check_point_kinematics<TestType, ReferencePoint::offset>();
}

// --- equations of motion -------------------------------------------------------------------------

namespace {

/// Dense solution of Eq. (1.32) in the test: LU of M for three-parameter sets; for Euler
/// parameters, LU of [M, C^T; C, 0] [qddot; lambda] = [f_v + Q; -2 |pdot|^2] with C = [0, 2 p^T]
/// (the second derivative of |p|^2 = 1). Returns [qddot; lambda] (lambda only for EP).
template <class P>
Eigen::VectorXd dense_solve(const tumble::test::State<P>& s,
                            const Eigen::Matrix<double, 3 + P::size, 3 + P::size>& m,
                            const Coords<P>& rhs, double* cond) {
  constexpr int nq = 3 + P::size;
  if constexpr (P::has_constraint) {
    Eigen::MatrixXd a = Eigen::MatrixXd::Zero(nq + 1, nq + 1);
    a.topLeftCorner(nq, nq) = m;
    a.block(nq, 3, 1, P::size) = 2.0 * s.theta().transpose();
    a.block(3, nq, P::size, 1) = 2.0 * s.theta();
    Eigen::VectorXd b(nq + 1);
    b << rhs, -2.0 * s.thetadot().squaredNorm();
    *cond = condition(a);
    return a.fullPivLu().solve(b);
  } else {
    *cond = condition(m);
    return Eigen::VectorXd(m.fullPivLu().solve(rhs));
  }
}

/// The residual of Eq. (1.32), max |M qddot - f_v - Q| relative to max(|M| |qddot| + |f_v| + |Q|).
template <class MM, class V> double residual(const MM& m, const V& qdd, const V& f, const V& q) {
  const V r = m * qdd - f - q;
  const V scale = m.cwiseAbs() * qdd.cwiseAbs() + f.cwiseAbs() + q.cwiseAbs();
  return r.cwiseAbs().maxCoeff() / scale.maxCoeff();
}

template <class P, ReferencePoint Ref> void check_equations_of_motion() {
  tumble::test::Random rng(103);
  double worst_res = 0, worst_q = 0, worst_lu = 0, worst_routes = 0;
  for (int b = 0; b < 4; ++b) {
    const auto model = tumble::test::random_body(rng, offset(Ref));
    const Body<P, Ref> body(tumble::test::mass_properties(model));
    for (int i = 0; i < 10; ++i) {
      const auto s = tumble::test::random_state<P>(rng);
      const auto loads = tumble::test::random_loads(rng);
      INFO(P::name << " " << tumble::test::ref_name(Ref) << " body " << b << " state " << i);

      const Coords<P> qdd = tumble::test::with_elements(loads, [&](const auto&... e) {
        return tumble::accelerations(body, 0.0, s.q, s.qdot, e...);
      });
      const Coords<P> q_code = tumble::test::with_elements(loads, [&](const auto&... e) {
        return tumble::generalized_force(body, 0.0, s.q, s.qdot, e...);
      });

      // Independent: Q = sum L_r^T F + [0; G^T M] (Eqs. 1.28, 1.31), M and f_v as point sums.
      const Coords<P> q_test =
          tumble::test::generalized_force(s, tumble::test::applied_forces(model, s, loads));
      const double eq = rel_error(q_code, q_test);
      CHECK(eq < kTol);
      worst_q = std::max(worst_q, eq);

      const auto m = tumble::test::cloud_mass_matrix(model, s);
      const Coords<P> f = tumble::test::cloud_centrifugal_coriolis(model, s);
      const double er = residual(m, qdd, f, q_test);
      CHECK(er < kTol);
      worst_res = std::max(worst_res, er);

      // Forward error against a dense LU: bounded by the condition number times the backward
      // error.
      double cond = 0;
      const Eigen::VectorXd sol = dense_solve<P>(s, m, Coords<P>(f + q_test), &cond);
      const double elu = rel_error(qdd, Coords<P>(sol.head(3 + P::size)));
      CHECK(elu < kTol * cond);
      worst_lu = std::max(worst_lu, elu / cond);
      if constexpr (P::has_constraint) {
        // The loads do no work against |p| = 1: the multiplier vanishes, and p.pddot = -|pdot|^2.
        CHECK(std::abs(sol(3 + P::size)) < kTol * cond * std::max(1.0, q_test.norm()));
        CHECK(std::abs(s.theta().dot(qdd.template tail<P::size>()) + s.thetadot().squaredNorm()) <
              kTol * (1.0 + s.thetadot().squaredNorm()));
      }

      // The three routes to qddot agree: loads, the wrench, the generalized force (wrench_from).
      const auto w = tumble::test::with_elements(loads, [&](const auto&... e) {
        return tumble::total_wrench(body, 0.0, s.q, s.qdot, e...);
      });
      const double e_routes = std::max(rel_error(body.accelerations(s.q, s.qdot, w), qdd),
                                       rel_error(body.accelerations(s.q, s.qdot, q_test), qdd));
      CHECK(e_routes < kTol * cond);
      worst_routes = std::max(worst_routes, e_routes / cond);
    }
  }
  record_error("Q (loads) vs L^T F", P::name, Ref, worst_q);
  record_error("residual of Eq. 1.32 (loads)", P::name, Ref, worst_res);
  record_error("qddot vs dense LU / cond", P::name, Ref, worst_lu);
  record_error("qddot routes (wrench, Q) / cond", P::name, Ref, worst_routes);
}

template <class P, ReferencePoint Ref> void check_generalized_force_given() {
  tumble::test::Random rng(104);
  double worst_res = 0, worst_lu = 0, worst_p = 0;
  for (int b = 0; b < 4; ++b) {
    const auto model = tumble::test::random_body(rng, offset(Ref));
    const Body<P, Ref> body(tumble::test::mass_properties(model));
    for (int i = 0; i < 10; ++i) {
      const auto s = tumble::test::random_state<P>(rng);
      const Coords<P> q = tumble::test::random_vector<3 + P::size>(rng, 5.0);
      INFO(P::name << " " << tumble::test::ref_name(Ref) << " body " << b << " state " << i);

      const Coords<P> qdd = body.accelerations(s.q, s.qdot, q);
      const auto m = tumble::test::cloud_mass_matrix(model, s);
      const Coords<P> f = tumble::test::cloud_centrifugal_coriolis(model, s);
      double cond = 0;
      const Eigen::VectorXd sol = dense_solve<P>(s, m, Coords<P>(f + q), &cond);
      const double elu = rel_error(qdd, Coords<P>(sol.head(3 + P::size)));
      CHECK(elu < kTol * cond);
      worst_lu = std::max(worst_lu, elu / cond);

      if constexpr (P::has_constraint) {
        // Q has a component along [0; p]: it is a constraint force, balanced by the multiplier
        // lambda of C = [0, 2 p^T]: M qddot - f_v - Q + C^T lambda = 0.
        Coords<P> ct = Coords<P>::Zero();
        ct.template tail<P::size>() = 2.0 * s.theta();
        const double lambda = sol(3 + P::size);
        const double er = residual(m, qdd, f, Coords<P>(q - lambda * ct));
        CHECK(er < kTol * cond);
        worst_res = std::max(worst_res, er);
        // Adding any multiple of [0; p] to Q does not change qddot.
        const Coords<P> qdd2 = body.accelerations(s.q, s.qdot, Coords<P>(q + 7.5 * ct));
        const double ep = rel_error(qdd2, qdd);
        CHECK(ep < kTol);
        worst_p = std::max(worst_p, ep);
      } else {
        const double er = residual(m, qdd, f, q);
        CHECK(er < kTol);
        worst_res = std::max(worst_res, er);
      }
    }
  }
  record_error("residual of Eq. 1.32 (Q given)", P::name, Ref, worst_res);
  record_error("qddot (Q given) vs dense LU / cond", P::name, Ref, worst_lu);
  if constexpr (P::has_constraint) {
    record_error("qddot change for Q + c [0; p]", P::name, Ref, worst_p);
  }
}

}  // namespace

TEMPLATE_LIST_TEST_CASE("accelerations solve M qddot = f_v + Q with every kind of load (Eq. 1.32)",
                        "[body][rigid_body]", TUMBLE_TEST_PARAMETERIZATIONS) {
  check_equations_of_motion<TestType, ReferencePoint::centroid>();
  check_equations_of_motion<TestType, ReferencePoint::offset>();
}

TEMPLATE_LIST_TEST_CASE("accelerations for a generalized force given directly (Eq. 1.32)",
                        "[body][rigid_body]", TUMBLE_TEST_PARAMETERIZATIONS) {
  check_generalized_force_given<TestType, ReferencePoint::centroid>();
  check_generalized_force_given<TestType, ReferencePoint::offset>();
}

TEMPLATE_LIST_TEST_CASE("an offset body with a zero offset equals the centroidal body",
                        "[body][rigid_body]", TUMBLE_TEST_PARAMETERIZATIONS) {
  using P = TestType;
  tumble::test::Random rng(105);
  const auto model = tumble::test::random_body(rng, false);
  const Body<P, ReferencePoint::centroid> at_g(tumble::test::mass_properties(model));
  const Body<P, ReferencePoint::offset> at_c(tumble::test::mass_properties(model));
  for (int i = 0; i < 10; ++i) {
    const auto s = tumble::test::random_state<P>(rng);
    const auto loads = tumble::test::random_loads(rng);
    const auto run = [&](const auto& body) {
      return tumble::test::with_elements(loads, [&](const auto&... e) {
        return tumble::accelerations(body, 0.0, s.q, s.qdot, e...);
      });
    };
    CHECK(rel_error(at_c.mass_matrix(s.q), at_g.mass_matrix(s.q)) < kTol);
    CHECK(rel_error(at_c.centrifugal_coriolis(s.q, s.qdot),
                    at_g.centrifugal_coriolis(s.q, s.qdot)) < kTol);
    CHECK(rel_error(run(at_c), run(at_g)) < kTol);
  }
}

// --- rejections and non-finite input -------------------------------------------------------------

#if TUMBLE_TEST_PRIMARY_SLICE
TEST_CASE("a centroidal RigidBody rejects a centroid away from the reference point",
          "[body][rigid_body]") {
  using MP = tumble::MassProperties<double>;
  const MP mp = MP::about_centroid(2.0, Matrix3d::Identity(), Vector3d(0.0, 0.1, 0.0));
  using Centroidal = Body<tumble::EulerParameters, ReferencePoint::centroid>;
  using Offset = Body<tumble::EulerParameters, ReferencePoint::offset>;
  REQUIRE_THROWS_AS(Centroidal(mp), std::invalid_argument);
  REQUIRE_THROWS_WITH(Centroidal(mp), TUMBLE_CONTAINS("needs a zero centroid offset"));
  REQUIRE_NOTHROW(Offset(mp));
  REQUIRE_NOTHROW(Centroidal(MP::about_centroid(2.0, Matrix3d::Identity())));
}
#endif  // TUMBLE_TEST_PRIMARY_SLICE

namespace {

template <class P, ReferencePoint Ref> void check_non_finite() {
  tumble::test::Random rng(106);
  const auto model = tumble::test::random_body(rng, offset(Ref));
  const Body<P, Ref> body(tumble::test::mass_properties(model));
  const auto s = tumble::test::random_state<P>(rng);
  tumble::Wrench<double> w;
  w.force = rng.vector(3.0);
  w.moment = rng.vector(3.0);
  INFO(P::name << " " << tumble::test::ref_name(Ref));
  REQUIRE_NOTHROW(body.accelerations(s.q, s.qdot, w));

  // A NaN anywhere in q or qdot either reaches the result, and then throws NonFiniteError
  // naming the state, or provably does not (the accelerations for a given wrench do not depend
  // on r_oc and rdot_oc, nor, for Euler angles framed at the centroid, on the first angle): never
  // a silent NaN. Each attitude coordinate reaches it in at least one of the two.
  constexpr int nq = 3 + P::size;
  int q_thrown = 0, qdot_thrown = 0;
  for (int k = 0; k < nq; ++k) {
    INFO("NaN in entry " << k);
    Coords<P> q = s.q;
    q(k) = kNaN;
    try {
      const Coords<P> r = body.accelerations(q, s.qdot, w);
      CHECK(r.allFinite());
    } catch (const tumble::NonFiniteError& e) {
      CHECK_THAT(std::string(e.what()), TUMBLE_CONTAINS("the state q has a non-finite entry"));
      q_thrown += k >= 3 ? 1 : 0;
    }
    Coords<P> qd = s.qdot;
    qd(k) = kNaN;
    try {
      const Coords<P> r = body.accelerations(s.q, qd, w);
      CHECK(r.allFinite());
    } catch (const tumble::NonFiniteError& e) {
      CHECK_THAT(std::string(e.what()), TUMBLE_CONTAINS("the rates qdot have a non-finite entry"));
      qdot_thrown += k >= 3 ? 1 : 0;
    }
  }
  if constexpr (P::has_constraint) {
    CHECK(q_thrown == P::size);
    CHECK(qdot_thrown == P::size);
  } else {
    CHECK(q_thrown >= P::size - 1);
    CHECK(qdot_thrown == P::size);
  }
  for (int k = 0; k < 6; ++k) {
    tumble::Wrench<double> bad = w;
    (k < 3 ? bad.force(k) : bad.moment(k - 3)) = kNaN;
    REQUIRE_THROWS_AS(body.accelerations(s.q, s.qdot, bad), tumble::NonFiniteError);
    REQUIRE_THROWS_WITH(body.accelerations(s.q, s.qdot, bad),
                        TUMBLE_CONTAINS("the applied load has a non-finite entry"));
  }
  Coords<P> q_bad = Coords<P>::Ones();
  q_bad(3 + P::size - 1) = std::numeric_limits<double>::infinity();
  REQUIRE_THROWS_WITH(body.accelerations(s.q, s.qdot, q_bad),
                      TUMBLE_CONTAINS("the applied load has a non-finite entry"));
}

}  // namespace

TEMPLATE_LIST_TEST_CASE("non-finite states and loads throw NonFiniteError naming the cause",
                        "[body][rigid_body]", TUMBLE_TEST_PARAMETERIZATIONS) {
  check_non_finite<TestType, ReferencePoint::centroid>();
  check_non_finite<TestType, ReferencePoint::offset>();
}

// Not per parameterization: compiled once, in the primary slice (tests/CMakeLists.txt compiles
// this file in slices of the parameterizations).
#if TUMBLE_TEST_PRIMARY_SLICE

#ifdef TUMBLE_TEST_HAVE_EULER_ANGLES
TEST_CASE("Euler angles exactly at gimbal lock throw NonFiniteError naming the singularity",
          "[body][rigid_body]") {
  // Proper Euler angles lock at t2 = 0, where sin(t2) is exactly 0 in floating point (unlike
  // cos(pi/2) for Tait-Bryan sequences): G is exactly singular.
  tumble::test::Random rng(107);
  const auto model = tumble::test::random_body(rng, true);
  const Body<tumble::EulerZXZ, ReferencePoint::offset> body(tumble::test::mass_properties(model));
  Coords<tumble::EulerZXZ> q, qdot;
  q << 0.1, 0.2, 0.3, 0.4, 0.0, -0.7;
  qdot << 0.5, -0.2, 0.1, 0.3, -0.6, 0.9;
  tumble::Wrench<double> w;
  w.force = Vector3d(1.0, 2.0, 3.0);
  w.moment = Vector3d(-0.5, 0.25, 1.0);
  REQUIRE_THROWS_AS(body.accelerations(q, qdot, w), tumble::NonFiniteError);
  REQUIRE_THROWS_WITH(body.accelerations(q, qdot, w),
                      TUMBLE_CONTAINS("at a singularity of EulerZXZ"));
}
#endif

TEST_CASE("a NaN position read by a spring throws NonFiniteError naming a non-finite value",
          "[body][rigid_body]") {
  // The spring-damper meets the NaN first: it must say that a value is non-finite, not that
  // the two ends coincide.
  const auto model = tumble::test::BodyModel{};
  const Body<tumble::EulerParameters, ReferencePoint::centroid> body(
      tumble::test::mass_properties(model));
  Coords<tumble::EulerParameters> q, qdot;
  q << kNaN, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0;
  qdot.setZero();
  const tumble::SpringDamper spring(Vector3d(0.1, 0.0, 0.0), Vector3d(0.0, 0.0, 2.0),
                                    {10.0, 1.0, 1.0});
  REQUIRE_THROWS_AS(tumble::accelerations(body, 0.0, q, qdot, spring), tumble::NonFiniteError);
  REQUIRE_THROWS_WITH(tumble::accelerations(body, 0.0, q, qdot, spring),
                      TUMBLE_CONTAINS("non-finite"));
}

#endif  // TUMBLE_TEST_PRIMARY_SLICE
