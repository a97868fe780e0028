// Physics of tumble::RigidBody (include/tumble/body/rigid_body.hpp), checked against laws that do
// not depend on the parameterization:
//   - every parameterization gives the same angular acceleration alpha = G thetaddot +
//     Gdot thetadot (Eq. 1.10) and the same centroid acceleration (Eq. 1.9) for the same physical
//     state and loads, equal to the Newton-Euler equations written in the test;
//   - the energy balance dT/dt = qdot^T Q (dT/dt by forward AD along the motion: exact);
//   - linear and angular momentum balance, d(m v_g)/dt = sum F and dH_O/dt = sum r x F + R M;
//   - M symmetric positive definite (three parameters) or semidefinite with null vector [0; p]
//     (Euler parameters);
//   - momenta and kinetic energy against the sums over the point-mass model.
// Reference: the reference chapter, Chapter 1, "Rigid body".

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include "support/body_fixtures.hpp"
#include "support/catch.hpp"
#include "support/parameterizations.hpp"
#include "tumble/body/rigid_body.hpp"
#include "tumble/force/loads.hpp"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using tumble::ReferencePoint;
using tumble::test::AD;
using tumble::test::record_error;
using tumble::test::rel_error;

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kTol = 256 * kEps;

template <class P, ReferencePoint Ref> using Body = tumble::RigidBody<P, Ref, double>;
template <class P, ReferencePoint Ref> using BodyAD = tumble::RigidBody<P, Ref, AD>;
template <class P> using Coords = typename tumble::test::State<P>::Coords;

constexpr bool offset(ReferencePoint r) { return r == ReferencePoint::offset; }

template <class P, ReferencePoint Ref, class Body>
Coords<P> accelerations(const Body& body, const tumble::test::State<P>& s,
                        const tumble::test::LoadSet& loads) {
  return tumble::test::with_elements(
      loads, [&](const auto&... e) { return tumble::accelerations(body, 0.0, s.q, s.qdot, e...); });
}

// --- one physics, every parameterization ---------------------------------------------------------

template <class P, ReferencePoint Ref> void check_newton_euler() {
  // The seed does not depend on P: every parameterization sees the same bodies, states and loads.
  tumble::test::Random rng(201);
  double worst_alpha = 0, worst_ag = 0;
  int used = 0, skipped = 0;
  for (int b = 0; b < 4; ++b) {
    const auto model = tumble::test::random_body(rng, offset(Ref));
    const Body<P, Ref> body(tumble::test::mass_properties(model));
    const Matrix3d& ig = model.inertia_centroid;
    const Vector3d& rg = model.centroid;
    const Eigen::SelfAdjointEigenSolver<Matrix3d> eig(ig);
    for (int i = 0; i < 10; ++i) {
      const auto ps = tumble::test::random_physical_state(rng);
      const auto loads = tumble::test::random_loads(rng);
      if (!tumble::test::usable<P>(ps)) {
        ++skipped;
        continue;
      }
      ++used;
      INFO(P::name << " " << tumble::test::ref_name(Ref) << " body " << b << " state " << i);
      const auto s = tumble::test::make_state<P>(ps);
      const Coords<P> qdd = accelerations<P, Ref>(body, s, loads);

      // alpha = G thetaddot + Gdot thetadot (Eq. 1.10); the centroid by Eq. (1.9).
      const auto th = s.theta();
      const Vector3d alpha =
          P::G(th) * qdd.template tail<P::size>() + P::Gdot_thetadot(th, s.thetadot());
      const Vector3d ag =
          qdd.template head<3>() + s.R * (alpha.cross(rg) + s.omega.cross(s.omega.cross(rg)));

      // Newton-Euler in the test, from the physical state itself: m a_g = sum F and
      // I_g alpha + omega x I_g omega = M_g (body components, about the centroid).
      const auto applied = tumble::test::applied_forces(model, ps, loads);
      Vector3d force = Vector3d::Zero(), moment_g = applied.moment;
      double force_scale = 0, moment_scale = applied.moment.norm();
      for (const auto& [rho, f] : applied.forces) {
        force += f;
        moment_g += (rho - rg).cross(ps.rotation.transpose() * f);
        force_scale += f.norm();
        moment_scale += (rho - rg).norm() * f.norm();
      }
      const Vector3d gyro = ps.omega.cross(ig * ps.omega);
      moment_scale += gyro.norm();
      const Vector3d alpha_ne = ig.ldlt().solve(moment_g - gyro);
      const Vector3d ag_ne = force / model.mass;

      // Errors relative to the magnitudes that enter, without cancellation: a rounding error of
      // the moments is amplified by I_g^{-1}, at most by 1 / (smallest principal moment).
      const double alpha_scale = moment_scale / eig.eigenvalues()(0);
      const double e_alpha = (alpha - alpha_ne).norm() / alpha_scale;
      const double e_ag =
          (ag - ag_ne).norm() /
          (force_scale / model.mass + alpha_scale * rg.norm() + ps.omega.squaredNorm() * rg.norm());
      CHECK(e_alpha < kTol);
      CHECK(e_ag < kTol);
      worst_alpha = std::max(worst_alpha, e_alpha);
      worst_ag = std::max(worst_ag, e_ag);
    }
  }
  // Only states within kMinSingularityDistance of a singular attitude are skipped.
  CHECK(used >= 30);
  record_error("alpha vs Newton-Euler", P::name, Ref, worst_alpha);
  record_error("centroid acceleration vs Newton-Euler", P::name, Ref, worst_ag);
  (void)skipped;
}

}  // namespace

TEMPLATE_LIST_TEST_CASE("every parameterization gives the Newton-Euler accelerations",
                        "[body][physics]", tumble::test::AllParameterizations) {
  check_newton_euler<TestType, ReferencePoint::centroid>();
  check_newton_euler<TestType, ReferencePoint::offset>();
}

// --- energy and momentum balance -----------------------------------------------------------------

namespace {

template <class P, ReferencePoint Ref> void check_balance_laws() {
  tumble::test::Random rng(202);
  double worst_energy = 0, worst_p = 0, worst_h = 0;
  for (int b = 0; b < 4; ++b) {
    const auto model = tumble::test::random_body(rng, offset(Ref));
    const Body<P, Ref> body(tumble::test::mass_properties(model));
    const BodyAD<P, Ref> body_ad(tumble::test::mass_properties<AD>(model));
    const double cond_ig = tumble::test::inertia_condition(model);
    for (int i = 0; i < 10; ++i) {
      const auto s = tumble::test::random_state<P>(rng);
      const auto loads = tumble::test::random_loads(rng);
      INFO(P::name << " " << tumble::test::ref_name(Ref) << " body " << b << " state " << i);
      const Coords<P> qdd = accelerations<P, Ref>(body, s, loads);
      const Coords<P> q_gen = tumble::test::with_elements(loads, [&](const auto&... e) {
        return tumble::generalized_force(body, 0.0, s.q, s.qdot, e...);
      });
      // Along the motion: q + t qdot, qdot + t qddot; derivatives at t = 0 are exact.
      const auto q_ad = tumble::test::along(s.q, s.qdot);
      const auto qd_ad = tumble::test::along(s.qdot, qdd);

      // Magnitudes without cancellation. The body solves I_g alpha = b with the stored inverse
      // of I_g, whose residual is bounded by eps cond(I_g) |b| (not eps |b|): the tolerances of
      // the balance laws carry that factor.
      const double tol = kTol * cond_ig;
      const auto m = body.mass_matrix(s.q);
      const Vector3d alpha = P::G(s.theta()) * qdd.template tail<P::size>() +
                             P::Gdot_thetadot(s.theta(), s.thetadot());
      const Vector3d rg = model.centroid;
      const double ig_norm = model.inertia_centroid.norm();

      // dT/dt = qdot^T M qddot + 1/2 qdot^T Mdot qdot = qdot^T Q, because qdot^T f_v =
      // -1/2 qdot^T Mdot qdot (the inertial forces do no work).
      const AD t_ad = body_ad.kinetic_energy(q_ad, qd_ad);
      const double dt_dt = t_ad.derivatives()(0);
      const double power = s.qdot.dot(q_gen);
      const double power_scale = s.qdot.cwiseAbs().dot(q_gen.cwiseAbs()) +
                                 s.qdot.cwiseAbs().dot(m.cwiseAbs() * qdd.cwiseAbs());
      const double ee = std::abs(dt_dt - power) / power_scale;
      CHECK(ee < tol);
      worst_energy = std::max(worst_energy, ee);

      // d(m v_g)/dt = sum F; dH_O/dt = sum r_j x F_j + R M (inertial components, about O).
      const auto applied = tumble::test::applied_forces(model, s, loads);
      Vector3d force = Vector3d::Zero(), moment_o = s.R * applied.moment;
      double f_scale = 0, m_scale = applied.moment.norm();
      for (const auto& [rho, f] : applied.forces) {
        const Vector3d r = tumble::test::point_position(s, rho);
        force += f;
        moment_o += r.cross(f);
        f_scale += f.norm();
        m_scale += r.norm() * f.norm();
      }
      const Vector3d dp = tumble::test::derivative(body_ad.linear_momentum(q_ad, qd_ad));
      const Vector3d dh = tumble::test::derivative(body_ad.angular_momentum(q_ad, qd_ad));
      const double ag_scale =
          f_scale + model.mass * (alpha.norm() + s.omega.squaredNorm()) * rg.norm();
      const double ep = (dp - force).norm() / ag_scale;
      // dH_O/dt = r_og x m a_g + R (omega x I_g omega + I_g alpha).
      const double h_scale = m_scale + ig_norm * (s.omega.squaredNorm() + alpha.norm()) +
                             body.centroid_position(s.q).norm() * ag_scale;
      const double eh = (dh - moment_o).norm() / h_scale;
      CHECK(ep < tol);
      CHECK(eh < tol);
      worst_p = std::max(worst_p, ep);
      worst_h = std::max(worst_h, eh);
    }
  }
  record_error("energy balance dT/dt = qdot.Q", P::name, Ref, worst_energy);
  record_error("linear momentum balance", P::name, Ref, worst_p);
  record_error("angular momentum balance", P::name, Ref, worst_h);
}

}  // namespace

TEMPLATE_LIST_TEST_CASE("energy balance dT/dt = qdot^T Q and momentum balance along the motion",
                        "[body][physics]", tumble::test::AllParameterizations) {
  check_balance_laws<TestType, ReferencePoint::centroid>();
  check_balance_laws<TestType, ReferencePoint::offset>();
}

// --- the mass matrix -----------------------------------------------------------------------------

namespace {

template <class P, ReferencePoint Ref> void check_definiteness() {
  constexpr int nq = 3 + P::size;
  tumble::test::Random rng(203);
  for (int b = 0; b < 4; ++b) {
    const auto model = tumble::test::random_body(rng, offset(Ref));
    const Body<P, Ref> body(tumble::test::mass_properties(model));
    for (int i = 0; i < 10; ++i) {
      const auto s = tumble::test::random_state<P>(rng);
      INFO(P::name << " " << tumble::test::ref_name(Ref) << " body " << b << " state " << i);
      const Eigen::Matrix<double, nq, nq> m = body.mass_matrix(s.q);
      CHECK(rel_error(m, m.transpose().eval()) < kTol);
      const Eigen::Matrix<double, nq, nq> ms = 0.5 * (m + m.transpose());
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, nq, nq>> eig(ms);
      const auto& ev = eig.eigenvalues();
      const double largest = ev(nq - 1);
      if constexpr (P::has_constraint) {
        // Positive semidefinite with the null vector [0; p]: |p|^2 = 1 is not a direction of
        // motion, and G p = 0.
        Coords<P> n = Coords<P>::Zero();
        n.template tail<P::size>() = s.theta();
        CHECK((m * n).norm() < kTol * largest);
        CHECK(std::abs(ev(0)) < kTol * largest);
        CHECK(ev(1) > 0);
        // Positive definite on the tangent space: adding the null direction makes M invertible.
        const Eigen::LLT<Eigen::Matrix<double, nq, nq>> llt(
            Eigen::Matrix<double, nq, nq>(ms + largest * n * n.transpose()));
        CHECK(llt.info() == Eigen::Success);
      } else {
        const Eigen::LLT<Eigen::Matrix<double, nq, nq>> llt(ms);
        CHECK(llt.info() == Eigen::Success);
        CHECK(ev(0) > 0);
      }
    }
  }
}

}  // namespace

TEMPLATE_LIST_TEST_CASE("M is symmetric, positive definite (semidefinite with [0; p] for EP)",
                        "[body][physics]", tumble::test::AllParameterizations) {
  check_definiteness<TestType, ReferencePoint::centroid>();
  check_definiteness<TestType, ReferencePoint::offset>();
}

// --- momenta and kinetic energy ------------------------------------------------------------------

namespace {

template <class P, ReferencePoint Ref> void check_momenta() {
  tumble::test::Random rng(204);
  double worst = 0;
  for (int b = 0; b < 4; ++b) {
    const auto model = tumble::test::random_body(rng, offset(Ref));
    const Body<P, Ref> body(tumble::test::mass_properties(model));
    for (int i = 0; i < 10; ++i) {
      const auto s = tumble::test::random_state<P>(rng);
      INFO(P::name << " " << tumble::test::ref_name(Ref) << " body " << b << " state " << i);
      // Sums over the point masses (inertial positions and velocities by Eqs. 1.1, 1.4).
      Vector3d p = Vector3d::Zero(), h = Vector3d::Zero(), hg = Vector3d::Zero();
      Vector3d rg = Vector3d::Zero();
      double t = 0, h_scale = 0, hg_scale = 0;
      for (const auto& pm : model.cloud) {
        const Vector3d r = tumble::test::point_position(s, pm.rho);
        const Vector3d v = tumble::test::point_velocity(s, pm.rho);
        const Vector3d d = pm.rho - model.centroid;  // body components, from the centroid
        p += pm.mass * v;
        h += r.cross(pm.mass * v);
        hg += d.cross(pm.mass * s.omega.cross(d));
        rg += pm.mass * r;
        t += 0.5 * pm.mass * v.squaredNorm();
        h_scale += pm.mass * r.norm() * v.norm();
        hg_scale += pm.mass * d.squaredNorm() * s.omega.norm();
      }
      rg /= model.mass;
      const double e_p = rel_error(body.linear_momentum(s.q, s.qdot), p);
      const double e_h = (body.angular_momentum(s.q, s.qdot) - h).norm() / h_scale;
      const double e_hg = (body.angular_momentum_centroid(s.q, s.qdot) - hg).norm() / hg_scale;
      const double e_rg = rel_error(body.centroid_position(s.q), rg);
      const double e_vg = rel_error(body.centroid_velocity(s.q, s.qdot), Vector3d(p / model.mass));
      const double e_t = std::abs(body.kinetic_energy(s.q, s.qdot) - t) / t;
      const double e_tm =
          std::abs(0.5 * s.qdot.dot(tumble::test::cloud_mass_matrix(model, s) * s.qdot) - t) / t;
      CHECK(e_p < kTol);
      CHECK(e_h < kTol);
      CHECK(e_hg < kTol);
      CHECK(e_rg < kTol);
      CHECK(e_vg < kTol);
      CHECK(e_t < kTol);
      CHECK(e_tm < kTol);
      worst = std::max({worst, e_p, e_h, e_hg, e_rg, e_vg, e_t, e_tm});
    }
  }
  record_error("momenta and T vs point masses", P::name, Ref, worst);
}

}  // namespace

TEMPLATE_LIST_TEST_CASE("momenta and kinetic energy equal the sums over point masses",
                        "[body][physics]", tumble::test::AllParameterizations) {
  check_momenta<TestType, ReferencePoint::centroid>();
  check_momenta<TestType, ReferencePoint::offset>();
}
