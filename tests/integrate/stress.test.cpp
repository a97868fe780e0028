// Numerical stability of tumble under stress: scenes where simulations usually break,
// each with a pass criterion taken from physics, for every parameterization it concerns.
//  - long runs of the tumbling asymmetric body (I = diag(1, 2, 3), omega0 = (0.1, 2.0, 0.05)):
//    energy and inertial angular momentum drift bounded by a multiple of tol x flips, and the
//    flip interval (sign changes of omega_2, located by a root function) equal to the Jacobi
//    elliptic one of tests/support/torque_free.hpp; 500 s in CI, 10,000 s behind [.long];
//  - singular attitudes: every Euler sequence spun straight through its singular middle angle,
//    Gibbs through 180 deg, MRP and the rotation vector through many full turns, against the
//    Euler-parameter run and the analytic solution, switches counted;
//  - fast spin (|omega| = 1e3 rad/s): the flip interval scales as 1/|omega| (the Euler equations
//    are homogeneous of degree 2 in omega: omega_k(t) = k omega(k t));
//  - a thin rod (1e-6 : 1 : 1) and nearly symmetric bodies against the closed form;
//  - masses 1e-6 .. 1e6 kg, lengths 1e-3 .. 1e3 m: a body on a spring under gravity with k/m and
//    g/L held fixed moves identically in dimensionless terms (r/L, R(t));
//  - quaternion norm drift with Adams (Baumgarte) and BDF (projection);
//  - stiff spring-dampers k/m up to 1e8 s^-2: BDF succeeds, Adams reports the stiffness.
//  - the core (RigidBody<P, Ref, S>::accelerations) in float and long double against the
//    Newton-Euler equations evaluated in long double, at tolerances that fit the type. The
//    integrator is double-only: CVODE's sunrealtype is double in the installed SUNDIALS, and
//    Scene static_asserts double bodies.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>
#include <tuple>
#include <type_traits>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "support/catch.hpp"
#include "support/parameterizations.hpp"
#include "support/random.hpp"
#include "support/scene_fixtures.hpp"
#include "support/torque_free.hpp"
#include "tumble/body/rigid_body.hpp"
#include "tumble/force/gravity.hpp"
#include "tumble/force/spring_damper.hpp"
#include "tumble/integrate/scene_integrator.hpp"
#include "tumble/scene/observables.hpp"
#include "tumble/scene/scene.hpp"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using Eigen::VectorXd;
using tumble::Bodies;
using tumble::CvodeError;
using tumble::CvodeMethod;
using tumble::EulerParameters;
using tumble::Event;
using tumble::IntegrationError;
using tumble::Loads;
using tumble::MassProperties;
using tumble::ReferencePoint;
using tumble::RigidBody;
using tumble::Scene;
using tumble::SceneIntegrator;
using tumble::SceneIntegratorOptions;
using tumble::test::rotation_angle_between;
using tumble::test::TorqueFreeBody;

constexpr double pi = std::numbers::pi;

using tumble::test::method_name;
SceneIntegratorOptions options(CvodeMethod method, double tol, long max_steps = 1000000) {
  return tumble::test::integrator_options(method, tol, max_steps);
}

using tumble::test::global_error_bound;

// ---- the tumbling body: long runs --------------------------------------------------------------

const Vector3d kInertia = tumble::test::kTumblingInertia;
const Vector3d kOmega = tumble::test::kTumblingOmega;
const Matrix3d kR0 = Eigen::AngleAxisd(0.5, Vector3d(1, -1, 2).normalized()).toRotationMatrix();

struct LongRun {
  double energy_drift = 0;    ///< max |T - T0| / T0 over the outputs
  double momentum_drift = 0;  ///< max |h - h0| / |h0|, inertial
  double quaternion_drift = 0;
  double flip_interval = 0;  ///< measured: (last - first sign change) / (changes - 1)
  double flip_error = 0;     ///< |measured / reference - 1|
  /// max |P(omega(t_i)) / P(omega0) - 1| over sampled outputs: how far the elliptic flip interval
  /// of the invariants the integrator carries strays from the initial one (TorqueFreeBody).
  double period_spread = 0;
  int flips = 0;
  long steps = 0;
  long switches = 0;
};

/// The tumbling body with omega0 = k kOmega (k scales the spin; t_end is in units of 1/k).
template <class P>
LongRun long_tumble(CvodeMethod method, double tol, double t_end, double k = 1.0) {
  using Body = RigidBody<P>;
  const TorqueFreeBody ref(kInertia, Vector3d(k * kOmega), kR0);
  Scene<Bodies<Body>> scene;
  const auto id = scene.add(Body(MassProperties<>::about_centroid(1.0, kInertia.asDiagonal())),
                            {.rotation = kR0, .omega = k * kOmega});
  std::vector<double> crossings;
  // The flips are the zeros of omega_2 (the intermediate axis): CVODE locates them.
  scene.add_event(Event{[&scene, id](double, const tumble::SceneStateView& y) {
                          return tumble::omega(scene, id, y)(1);
                        },
                        0,
                        [&crossings](double t, tumble::SceneState&) { crossings.push_back(t); }});
  const double e0 = tumble::kinetic_energy(scene, scene.initial_state());
  const Vector3d h0 = tumble::angular_momentum(scene, scene.initial_state());
  SceneIntegrator integrator(scene, 0.0, options(method, tol));
  LongRun r;
  const int outputs = 200;
  for (int i = 1; i <= outputs; ++i) {
    integrator.advance(t_end * i / outputs);
    const tumble::SceneState& y = integrator.state();
    r.energy_drift = std::max(r.energy_drift, std::abs(tumble::kinetic_energy(scene, y) - e0) / e0);
    r.momentum_drift =
        std::max(r.momentum_drift, (tumble::angular_momentum(scene, y) - h0).norm() / h0.norm());
    r.quaternion_drift = std::max(r.quaternion_drift, tumble::constraint_drift(scene, y));
    if (i % 10 == 0) {
      const double p = TorqueFreeBody(kInertia, tumble::omega(scene, id, y)).flip_interval();
      r.period_spread = std::max(r.period_spread, std::abs(p / ref.flip_interval() - 1.0));
    }
  }
  r.flips = static_cast<int>(crossings.size());
  if (r.flips >= 2) {
    r.flip_interval = (crossings.back() - crossings.front()) / (r.flips - 1);
    r.flip_error = std::abs(r.flip_interval / ref.flip_interval() - 1.0);
  }
  const auto s = integrator.statistics();
  r.steps = s.steps;
  r.switches = s.chart_switches;
  return r;
}

void print_long(const char* name, CvodeMethod m, double tol, double t_end, const LongRun& r) {
  std::printf("%-28s %-5s tol %.0e T %8.3g s: flips %4d  dE/E %.2e (%.1f tol/flip)  |dh|/|h| "
              "%.2e (%.1f tol/flip)  flip err %.2e (spread %.2e)  |p|-1 %.1e  steps %ld  "
              "switches %ld\n",
              name, method_name(m), tol, t_end, r.flips, r.energy_drift,
              r.energy_drift / (tol * std::max(r.flips, 1)), r.momentum_drift,
              r.momentum_drift / (tol * std::max(r.flips, 1)), r.flip_error, r.period_spread,
              r.quaternion_drift, r.steps, r.switches);
}

/// Invariant drift allowed per flip, in units of tol. Each flip takes a roughly fixed number of
/// steps (a few hundred to a few thousand, set by the flip's time scale and the chart switches),
/// each committing a local error of about tol (CVODE's weighted norm), so the drift of T and h
/// grows like tol x flips. The constant is measured, worst case over every parameterization and
/// both methods, 500 s at 1e-9 and 10,000 s at 1e-10 (GCC 12 Release, SUNDIALS 6.4): 264 tol per
/// flip (RotationVector, BDF, 10,000 s), so 1e3 leaves a margin of 3.8. Gibbs drifts about 20
/// times more than the other sets (5,608 tol per flip, BDF, 10,000 s; margin 3.6). Not the
/// switches (several Euler sequences switch more often) but, most likely, the coordinates
/// themselves: between switches a Gibbs vector moves like tan(phi/2), whose higher derivatives
/// are large, so every step commits its full local error; the rotation vector (phi) and Euler
/// angles in a spin move almost linearly and commit little. The "[.report]" table shows the same
/// order in a steady spin through the singular attitudes: Gibbs > MRP (tan(phi/4)) >> rotation
/// vector ~ Euler angles.
template <class P> double drift_per_flip() {
  return std::is_same_v<P, tumble::RodriguesParameters> ? 2e4 : 1e3;
}

/// The flip interval checks. Near the separatrix (here 1 - m ~ 6e-4) the elliptic period is very
/// sensitive to the invariants: dP/P ~ d(1-m) / (2 (1-m) K), about 100 x their relative drift.
/// So the measured mean interval is compared with the elliptic one of omega0 within the spread of
/// the elliptic intervals of the invariants the integrator carried (the mean of a quantity lies
/// within its range; factor 2 for the sampling of that range every 10 outputs), plus 100 tol for
/// locating the first and last crossing.
void check_flip_interval(const LongRun& r, double reference, double tol) {
  CHECK(std::abs(r.flip_interval / reference - 1.0) <= 2 * r.period_spread + 100 * tol);
}

template <class P> void check_long(CvodeMethod m, double tol, double t_end) {
  const LongRun r = long_tumble<P>(m, tol, t_end);
  print_long(std::string(P::name).c_str(), m, tol, t_end, r);
  INFO(P::name << " with " << method_name(m) << " over " << t_end << " s");
  const double flip_interval = TorqueFreeBody(kInertia, kOmega, kR0).flip_interval();
  // The count of the elliptic intervals of omega0, give or take one for the phase at t_end and
  // those the drift of the flip interval (at most the spread) adds or removes over the run.
  const double expected_flips = t_end / flip_interval;
  CHECK(std::abs(r.flips - expected_flips) <= 1.0 + r.period_spread * expected_flips);
  CHECK(r.energy_drift < drift_per_flip<P>() * tol * r.flips);
  CHECK(r.momentum_drift < drift_per_flip<P>() * tol * r.flips);
  check_flip_interval(r, flip_interval, tol);
  if constexpr (P::has_constraint) {
    CHECK(r.quaternion_drift < (m == CvodeMethod::bdf ? 10 : 100) * tol);
    CHECK(r.switches == 0);
  } else {
    CHECK(r.quaternion_drift == 0);
  }
}

}  // namespace

TEMPLATE_LIST_TEST_CASE("stress: the tumbling body for 500 s", "[integrate][stress]",
                        TUMBLE_TEST_PARAMETERIZATIONS) {
  for (const CvodeMethod m : {CvodeMethod::adams, CvodeMethod::bdf}) {
    check_long<TestType>(m, 1e-9, 500.0);
  }
}

TEMPLATE_LIST_TEST_CASE("stress: the tumbling body for 10,000 s", "[integrate][stress][.long]",
                        TUMBLE_TEST_PARAMETERIZATIONS) {
  for (const CvodeMethod m : {CvodeMethod::adams, CvodeMethod::bdf}) {
    check_long<TestType>(m, 1e-10, 10000.0);
  }
}

// ---- fast spin: |omega| = 1e3 rad/s -------------------------------------------------------------

TEMPLATE_LIST_TEST_CASE("stress: fast spin, |omega| = 1e3 rad/s", "[integrate][stress]",
                        TUMBLE_TEST_PARAMETERIZATIONS) {
  using P = TestType;
  const double k = 1e3 / kOmega.norm();
  const double tol = 1e-9;
  const double base = TorqueFreeBody(kInertia, kOmega, kR0).flip_interval();
  for (const CvodeMethod m : {CvodeMethod::adams, CvodeMethod::bdf}) {
    // 100 s of the slow body: the same 11 flips.
    const LongRun r = long_tumble<P>(m, tol, 100.0 / k, k);
    print_long(std::string(P::name).c_str(), m, tol, 100.0 / k, r);
    INFO(P::name << " with " << method_name(m));
    CHECK(r.flips == 11);
    // Scaling: the flip interval of the fast body times k is the slow body's one (base / k is
    // the reference), within the spread of the carried invariants (see check_flip_interval).
    check_flip_interval(r, base / k, tol);
    CHECK(r.energy_drift < drift_per_flip<P>() * tol * r.flips);
    CHECK(r.momentum_drift < drift_per_flip<P>() * tol * r.flips);
  }
}

// ---- singular attitudes
// ---------------------------------------------------------------------------

namespace {

/// The spin axis that drives P straight through its singular attitudes: the middle axis of an
/// Euler sequence (theta2 then runs through +-pi/2, or 0 and pi), any axis for the vector sets
/// (the angle runs through 180 and 360 deg every turn).
template <class P> int spin_axis() {
  if constexpr (requires { P::axis2; }) {
    return P::axis2;
  } else {
    return 2;
  }
}

struct SingularRun {
  double attitude = 0;   ///< max angle between R and the Euler-parameter R, rad
  double omega = 0;      ///< max |omega - omega_EP|
  double reference = 0;  ///< max angle between R and the analytic R
  long switches = 0;
  long steps = 0;
  double energy = 0;    ///< max |T - T0| / T0 of the three-parameter body (for the report)
  double momentum = 0;  ///< max |h - h0| / |h0|, inertial, of the three-parameter body
};

template <class P> SingularRun singular_run(CvodeMethod m, double tol, int turns) {
  const int a = spin_axis<P>();
  // The spin axis is the major axis, so the spin is stable; a small transverse rate adds a
  // nutation of about 0.02 rad.
  // Moments 3 (spin axis), 2, 1.5: distinct, and a possible mass distribution (2 + 1.5 > 3).
  Vector3d inertia;
  inertia(a) = 3.0;
  inertia((a + 1) % 3) = 2.0;
  inertia((a + 2) % 3) = 1.5;
  Vector3d omega = Vector3d::Zero();
  omega(a) = pi;  // half a turn per second
  omega((a + 1) % 3) = 0.05;
  const TorqueFreeBody ref(inertia, omega);
  using B = RigidBody<P>;
  using E = RigidBody<EulerParameters>;
  Scene<Bodies<B, E>> scene;
  const auto mp = MassProperties<>::about_centroid(1.0, inertia.asDiagonal());
  const auto ib = scene.add(B(mp), {.omega = omega});
  const auto ie = scene.add(E(mp), {.omega = omega});
  SceneIntegrator integrator(scene, 0.0, options(m, tol));
  SingularRun r;
  const double t_end = 2.0 * turns;
  for (int i = 1; i <= 40 * turns; ++i) {
    const double t = t_end * i / (40 * turns);
    integrator.advance(t);
    const tumble::SceneState& y = integrator.state();
    r.attitude = std::max(r.attitude, rotation_angle_between(tumble::rotation(scene, ib, y),
                                                             tumble::rotation(scene, ie, y)));
    r.omega = std::max(r.omega, (tumble::omega(scene, ib, y) - tumble::omega(scene, ie, y)).norm());
    r.reference = std::max(r.reference,
                           rotation_angle_between(tumble::rotation(scene, ib, y), ref.rotation(t)));
    // T = 1/2 omega . I omega and h = R I omega of the three-parameter body, from its state.
    const Vector3d w = tumble::omega(scene, ib, y);
    const Vector3d h = tumble::rotation(scene, ib, y) * inertia.cwiseProduct(w);
    r.energy = std::max(r.energy, std::abs(0.5 * w.dot(inertia.cwiseProduct(w)) /
                                               static_cast<double>(ref.kinetic_energy_ld()) -
                                           1.0));
    r.momentum =
        std::max(r.momentum, (h - ref.angular_momentum()).norm() / ref.angular_momentum().norm());
  }
  r.switches = integrator.chart_switches(ib);
  r.steps = integrator.statistics().steps;
  return r;
}

}  // namespace

TEMPLATE_LIST_TEST_CASE("stress: straight through the singular attitudes, many turns",
                        "[integrate][stress]", TUMBLE_TEST_PARAMETERIZATIONS) {
  using P = TestType;
  if constexpr (!P::has_constraint) {
    const int turns = 20;
    const double tol = 1e-10;
    for (const CvodeMethod m : {CvodeMethod::adams, CvodeMethod::bdf}) {
      const SingularRun r = singular_run<P>(m, tol, turns);
      std::printf("%-28s %-5s %d turns: |R - R_EP| %.2e rad (%.0f tol), |w - w_EP| %.2e, "
                  "|R - R_ref| %.2e, switches %ld, steps %ld\n",
                  std::string(P::name).c_str(), method_name(m), turns, r.attitude, r.attitude / tol,
                  r.omega, r.reference, r.switches, r.steps);
      INFO(P::name << " with " << method_name(m) << ": " << r.steps << " steps");
      // The steps are those of the scene (both bodies share them; the switches dominate).
      const double bound = global_error_bound(tol, r.steps, pi, 2.0 * turns);
      CHECK(r.attitude < bound);
      CHECK(r.omega < bound);
      CHECK(r.reference < bound);
      // Every turn passes each singular attitude of the original chart once (Euler: both
      // +-pi/2, or 0 and pi; vector sets: 180 or 360 deg): at least one switch per turn.
      CHECK(r.switches >= turns);
    }
  }
}

// ---- extreme inertia: a thin rod and nearly symmetric bodies ------------------------------------

namespace {

struct ClosedFormRun {
  double error = 0;   ///< max over outputs of the attitude angle error and |domega| / |omega0|
  double energy = 0;  ///< max |T - T0| / T0
  long steps = 0;
  long switches = 0;
};

template <class P>
ClosedFormRun closed_form_error(const Vector3d& inertia, const Vector3d& omega, CvodeMethod m,
                                double tol, double t_end) {
  using B = RigidBody<P>;
  const TorqueFreeBody ref(inertia, omega, kR0);
  Scene<Bodies<B>> scene;
  const auto id = scene.add(B(MassProperties<>::about_centroid(1.0, inertia.asDiagonal())),
                            {.rotation = kR0, .omega = omega});
  const double e0 = tumble::kinetic_energy(scene, scene.initial_state());
  SceneIntegrator integrator(scene, 0.0, options(m, tol));
  double err = 0, de = 0;
  for (int i = 1; i <= 100; ++i) {
    const double t = t_end * i / 100;
    integrator.advance(t);
    const tumble::SceneState& y = integrator.state();
    err = std::max(err, rotation_angle_between(tumble::rotation(scene, id, y), ref.rotation(t)));
    err = std::max(err, (tumble::omega(scene, id, y) - ref.omega(t)).norm() / omega.norm());
    de = std::max(de, std::abs(tumble::kinetic_energy(scene, y) - e0) / e0);
  }
  return {err, de, integrator.statistics().steps, integrator.chart_switches(id)};
}

}  // namespace

TEMPLATE_LIST_TEST_CASE("stress: a thin rod (1e-6 : 1 : 1) and nearly symmetric bodies",
                        "[integrate][stress]", TUMBLE_TEST_PARAMETERIZATIONS) {
  using P = TestType;
  const double tol = 1e-10;
  struct Case {
    const char* name;
    Vector3d inertia;
    Vector3d omega;
  };
  const Case cases[] = {
      {"thin rod", {1e-6, 1.0, 1.0}, {3.0, 1.0, 0.5}},
      {"nearly symmetric, 1e-6", {1.0, 1.0 + 1e-6, 2.0}, {0.4, 0.3, 1.0}},
      {"nearly symmetric, 1e-10", {2.0, 2.0, 2.0 + 2e-10}, {0.4, 0.3, 1.0}},
  };
  for (const CvodeMethod m : {CvodeMethod::adams, CvodeMethod::bdf}) {
    for (const Case& c : cases) {
      const ClosedFormRun r = closed_form_error<P>(c.inertia, c.omega, m, tol, 20.0);
      const double ts = tol * static_cast<double>(r.steps);
      std::printf("%-28s %-5s %-24s max error vs closed form %.2e (%.3f tol x steps), dE/E %.1e "
                  "(%.3f tol x steps), steps %ld\n",
                  std::string(P::name).c_str(), method_name(m), c.name, r.error, r.error / ts,
                  r.energy, r.energy / ts, r.steps);
      INFO(P::name << " with " << method_name(m) << ": " << c.name << ", " << r.steps << " steps");
      CHECK(r.error < global_error_bound(tol, r.steps, c.omega.norm(), 20.0));
      // The energy is an invariant, with no phase growth: dE/E = 2 domega/omega, so about 2 tol
      // per step, times the margin 5 of global_error_bound (worst case measured 6.9 tol x steps).
      CHECK(r.energy < 10.0 * ts);
    }
  }
}

// ---- masses and lengths over 12 and 6 decades ---------------------------------------------------

namespace {

struct Scaled {
  std::vector<Matrix3d> rotation;
  std::vector<Vector3d> position;  ///< divided by L
  long steps = 0;
};

/// A body of mass m and size L, framed at a point off its centroid, hanging on a spring under
/// gravity. With k/m = 40 s^-2, g/L = 10 s^-2 and every length proportional to L, the motion in
/// r/L and R is the same for every m and L (the equations are invariant under m -> a m,
/// lengths -> b lengths at fixed time scale). Tolerances: atol per component scaled by L.
template <class P> Scaled scaled_run(double m, double l, CvodeMethod method, double tol) {
  using B = RigidBody<P, ReferencePoint::offset>;
  Scene<Bodies<B>, Loads<tumble::UniformGravity, tumble::SpringDamper>> scene;
  const Vector3d inertia = m * l * l * Vector3d(0.02, 0.03, 0.04);
  const auto id = scene.add(
      B(MassProperties<>::about_centroid(m, inertia.asDiagonal(), l * Vector3d(0.1, 0.05, 0.0))),
      {.position = l * Vector3d(0.1, 0.0, -0.5),
       .rotation = Eigen::AngleAxisd(0.3, Vector3d(1, 2, 3).normalized()).toRotationMatrix(),
       .velocity = l * Vector3d(0.2, -0.1, 0.3),
       .omega = {1.0, -2.0, 0.5}});
  scene.add_load(id, tumble::UniformGravity(Vector3d(0, 0, -10.0 * l)));
  scene.add_load(id, tumble::SpringDamper(
                         l * Vector3d(0.2, 0, 0), Vector3d::Zero(),
                         {.stiffness = 40.0 * m, .damping = 0.1 * m, .rest_length = 0.4 * l}));
  SceneIntegratorOptions o = options(method, tol);
  VectorXd atol = VectorXd::Constant(scene.size(), tol);
  const int nq = B::nq;
  atol.segment<3>(0).setConstant(tol * l);
  atol.segment<3>(nq).setConstant(tol * l);
  o.atol = atol;
  SceneIntegrator integrator(scene, 0.0, o);
  Scaled s;
  for (int i = 1; i <= 20; ++i) {
    integrator.advance(0.5 * i);
    const tumble::SceneState& y = integrator.state();
    s.rotation.push_back(tumble::rotation(scene, id, y));
    s.position.push_back(tumble::position(scene, id, y) / l);
  }
  s.steps = integrator.statistics().steps;
  return s;
}

template <class P> void check_scaling(CvodeMethod method) {
  const double tol = 1e-10;
  const Scaled base = scaled_run<P>(1.0, 1.0, method, tol);
  double worst = 0;
  for (const double m : {1e-6, 1.0, 1e6}) {
    for (const double l : {1e-3, 1.0, 1e3}) {
      const Scaled s = scaled_run<P>(m, l, method, tol);
      double err = 0;
      for (std::size_t i = 0; i < base.rotation.size(); ++i) {
        err = std::max(err, rotation_angle_between(s.rotation[i], base.rotation[i]));
        err = std::max(err, (s.position[i] - base.position[i]).norm());
      }
      INFO(P::name << " with " << method_name(method) << ": m = " << m << " kg, L = " << l
                   << " m, steps " << s.steps << " and " << base.steps);
      // The scaled problem is the same in r/L and R, and so is CVODE's weighted error norm (atol
      // of the positions and velocities scaled by L): the two runs differ only through rounding,
      // which can change step-size decisions (and, for Euler angles, the times of the chart
      // switches); then each run is within its global error of the exact solution, so they
      // differ by at most the sum (|omega0| = 2.3 rad/s, 10 s).
      const double bound = global_error_bound(tol, s.steps + base.steps, 2.3, 10.0);
      CHECK(err < bound);
      worst = std::max(worst, err / bound);
    }
  }
  std::printf("%-28s %-5s m in [1e-6, 1e6] kg, L in [1e-3, 1e3] m: max |R - R_1|, |r/L - r_1| "
              "= %.4f of the bound\n",
              std::string(P::name).c_str(), method_name(method), worst);
}

}  // namespace

#if TUMBLE_TEST_PRIMARY_SLICE  // not per parameterization: in one slice only
TEST_CASE("stress: masses 1e-6 .. 1e6 kg and lengths 1e-3 .. 1e3 m scale as physics says",
          "[integrate][stress]") {
  for (const CvodeMethod m : {CvodeMethod::adams, CvodeMethod::bdf}) {
    check_scaling<EulerParameters>(m);
    check_scaling<tumble::ModifiedRodriguesParameters>(m);
    check_scaling<tumble::EulerZXZ>(m);
  }
}

// ---- stiff spring-dampers -----------------------------------------------------------------------

namespace {

struct StiffRun {
  bool ok = false;
  long steps = 0;
  std::string message;
  double drift = 0;
};

/// A body on a spring-damper of stiffness k = ratio m at a point off its centroid (so the spring
/// also twists it), damping ratio 0.5 on the translational mode, for 1 s.
StiffRun stiff_run(double ratio, CvodeMethod method, long max_steps) {
  using B = RigidBody<EulerParameters>;
  Scene<Bodies<B>, Loads<tumble::SpringDamper>> scene;
  const double m = 2.0;
  const auto id =
      scene.add(B(MassProperties<>::about_centroid(m, Vector3d(0.02, 0.03, 0.04).asDiagonal())),
                {.position = {0.01, 0.0, 0.0}, .omega = {1.0, 2.0, 0.5}});
  scene.add_load(
      id, tumble::SpringDamper(
              Vector3d(0.05, 0, 0), Vector3d(0.05, 0, 0),
              {.stiffness = ratio * m, .damping = std::sqrt(ratio) * m, .rest_length = 0.0}));
  SceneIntegrator integrator(scene, 0.0, options(method, 1e-8, max_steps));
  StiffRun r;
  try {
    for (int i = 1; i <= 10; ++i) {
      integrator.advance(0.1 * i);
      const tumble::SceneState& y = integrator.state();
      r.drift = std::max(r.drift, tumble::constraint_drift(scene, y));
    }
    r.ok = true;
  } catch (const CvodeError& e) {
    r.message = e.what();
  }
  r.steps = integrator.statistics().steps;
  return r;
}

}  // namespace

TEST_CASE("stress: stiff spring-dampers, k/m up to 1e8 s^-2", "[integrate][stress]") {
  for (const double ratio : {1e4, 1e6, 1e8}) {
    const StiffRun bdf = stiff_run(ratio, CvodeMethod::bdf, 100000);
    std::printf("k/m = %.0e: BDF %s in %ld steps, quaternion drift %.1e\n", ratio,
                bdf.ok ? "succeeded" : "FAILED", bdf.steps, bdf.drift);
    INFO("k/m = " << ratio << ": " << bdf.message);
    CHECK(bdf.ok);
    CHECK(bdf.drift < 1e-6);
    // Adams with a budget of 500 steps per output interval: on a stiff problem it must report,
    // not hang.
    const StiffRun adams = stiff_run(ratio, CvodeMethod::adams, 500);
    std::printf("k/m = %.0e: Adams (max_steps 500) %s after %ld steps%s%s\n", ratio,
                adams.ok ? "succeeded" : "stopped", adams.steps, adams.ok ? "" : ": ",
                adams.message.c_str());
    // |lambda| = sqrt(k/m): at 1e8 the spring's 1e4 rad/s needs of the order of 1e4 steps per
    // second from Adams (bounded stability regions above order 2); at 1e6 (1e3 rad/s) it gets
    // through each 0.1 s output interval (max_steps counts per interval) in about 160
    // steps (measured), so only 1e8 is asserted.
    if (ratio >= 1e8) {
      CHECK_FALSE(adams.ok);
      CHECK(adams.message.find("CV_TOO_MUCH_WORK") != std::string::npos);
      CHECK(adams.message.find("max_steps = 500") != std::string::npos);
      // The statistics tell the stiffness: Adams took the whole budget for a fraction of what
      // BDF did in all.
      CHECK(adams.steps >= 500);
    }
  }
  // With an unlimited budget Adams succeeds at 1e8, with far more steps than BDF: |lambda| T =
  // 1e4 sets Adams' step count, BDF's is set by the accuracy of the slow motion (measured 16,336
  // against 1,487).
  const StiffRun adams = stiff_run(1e8, CvodeMethod::adams, 10000000);
  const StiffRun bdf = stiff_run(1e8, CvodeMethod::bdf, 100000);
  std::printf("k/m = 1e8: Adams %ld steps, BDF %ld steps\n", adams.steps, bdf.steps);
  CHECK(adams.ok);
  CHECK(adams.steps > 5 * bdf.steps);
}

#endif

// ---- the core in float, double and long double -------------------------------------------------

namespace {

/// The angular acceleration and the acceleration of the reference point that a body's qddot
/// encodes, recovered through the parameterization (alpha = G thetaddot + Gdot thetadot,
/// Eq. 1.10), against Newton-Euler in long double:
///   alpha = I_g^-1 (M_g - omega x I_g omega),  a_c = F/m - R (alpha x r_g + omega x (omega x
///   r_g)).
/// B::qdot_from behind a call GCC does not inline: when GCC 12 sees the 12-byte Vector3f
/// temporaries and Eigen's 16-byte packet copy (dead for size 3) in one function, it reports a
/// false -Warray-bounds (the same workaround as tests/support/body_fixtures.hpp).
template <class B>
[[gnu::noinline]] typename B::Coords qdot_of(const typename B::Coords& q,
                                             const tumble::Vector3<typename B::Scalar>& v,
                                             const tumble::Vector3<typename B::Scalar>& w) {
  return B::qdot_from(q, v, w);
}

template <class P, ReferencePoint Ref, class S> long double core_error() {
  using LD = long double;
  using B = RigidBody<P, Ref, S>;
  const Eigen::Matrix<LD, 3, 1> inertia(0.7L, 1.1L, 1.5L), omega(0.3L, -1.2L, 0.8L);
  const Eigen::Matrix<LD, 3, 1> rg = Ref == ReferencePoint::offset
                                         ? Eigen::Matrix<LD, 3, 1>(0.1L, -0.2L, 0.05L)
                                         : Eigen::Matrix<LD, 3, 1>::Zero();
  const Eigen::Matrix<LD, 3, 1> force(1.0L, -2.0L, 0.5L), moment(0.2L, 0.1L, -0.3L);
  const LD mass = 2.5L;
  const Eigen::Matrix<LD, 3, 3> r =
      Eigen::AngleAxis<LD>(0.9L, Eigen::Matrix<LD, 3, 1>(1, 2, -1).normalized()).toRotationMatrix();
  const B body(
      MassProperties<S>::about_centroid(S(mass), inertia.cast<S>().asDiagonal(), rg.cast<S>()));
  const typename P::template Coords<S> th = P::from_rotation(Eigen::Matrix<S, 3, 3>(r.cast<S>()));
  typename B::Coords q, qd;
  q << S(1), S(-2), S(3), th;
  qd = qdot_of<B>(q, tumble::Vector3<S>(S(0.5), S(0.1), S(-0.4)), omega.cast<S>());
  tumble::Wrench<S> w;
  w.force = force.cast<S>();
  w.moment = moment.cast<S>();
  const typename B::Coords qdd = body.accelerations(q, qd, w);
  // Recover alpha in long double from the type's own coordinates.
  using PL = typename P::template Coords<LD>;
  const PL thl = th.template cast<LD>();
  const PL thd = qd.template tail<P::size>().template cast<LD>();
  const PL thdd = qdd.template tail<P::size>().template cast<LD>();
  const Eigen::Matrix<LD, 3, 1> alpha = P::G(thl) * thdd + P::Gdot_thetadot(thl, thd);
  const Eigen::Matrix<LD, 3, 1> w_l = P::G(thl) * thd;
  const Eigen::Matrix<LD, 3, 3> rl = P::rotation(thl);
  const Eigen::Matrix<LD, 3, 1> ih = inertia.cwiseProduct(w_l);
  const Eigen::Matrix<LD, 3, 1> alpha_ne =
      (moment - rg.cross(rl.transpose() * force) - w_l.cross(ih)).cwiseQuotient(inertia);
  const Eigen::Matrix<LD, 3, 1> a_ne =
      force / mass - rl * (alpha_ne.cross(rg) + w_l.cross(w_l.cross(rg)));
  const Eigen::Matrix<LD, 3, 1> a = qdd.template head<3>().template cast<LD>();
  return std::max((alpha - alpha_ne).norm() / alpha_ne.norm(), (a - a_ne).norm() / a_ne.norm());
}

template <class P, class S> void check_core_type(const char* type) {
  const long double eps = std::numeric_limits<S>::epsilon();
  const long double e0 = core_error<P, ReferencePoint::centroid, S>();
  const long double e1 = core_error<P, ReferencePoint::offset, S>();
  INFO(P::name << " in " << type << ": relative errors " << static_cast<double>(e0) << ", "
               << static_cast<double>(e1) << " (eps " << static_cast<double>(eps) << ")");
  // The coordinates of the type are rounded once; the accelerations then carry a few eps times
  // the condition of G (at most about 10 away from the singular attitudes).
  CHECK(e0 < 200 * eps);
  CHECK(e1 < 200 * eps);
}

}  // namespace

TEMPLATE_LIST_TEST_CASE("stress: the core in float, double and long double", "[integrate][stress]",
                        TUMBLE_TEST_PARAMETERIZATIONS) {
  check_core_type<TestType, float>("float");
  check_core_type<TestType, double>("double");
  check_core_type<TestType, long double>("long double");
}

// ---- the report: the table of the stress scenes (hidden; run with "[.report]") ------------------

namespace {

/// One row; a negative value prints as "-" (not measured in that scene).
void report_row(const char* scene, const std::string& param, const char* method, double tol,
                double de, double dh, double dp, long switches, long steps) {
  static bool header = false;
  if (!header) {
    std::printf("| %-22s | %-27s | %-5s | %-5s | %-8s | %-8s | %-8s | %-8s | %-7s |\n", "scene",
                "parameterization", "meth.", "tol", "dE/E", "|dh|/|h|", "||p|-1|", "switches",
                "steps");
    std::printf("|%s|%s|%s|%s|%s|%s|%s|%s|%s|\n", std::string(24, '-').c_str(),
                std::string(29, '-').c_str(), std::string(7, '-').c_str(),
                std::string(7, '-').c_str(), std::string(10, '-').c_str(),
                std::string(10, '-').c_str(), std::string(10, '-').c_str(),
                std::string(10, '-').c_str(), std::string(9, '-').c_str());
    header = true;
  }
  const auto v = [](double x) {
    char b[16];
    if (x < 0) {
      std::snprintf(b, sizeof b, "%-8s", "-");
    } else {
      std::snprintf(b, sizeof b, "%.2e", x);
    }
    return std::string(b);
  };
  std::printf("| %-22s | %-27s | %-5s | %.0e | %s | %s | %s | %8ld | %7ld |\n", scene,
              param.c_str(), method, tol, v(de).c_str(), v(dh).c_str(), v(dp).c_str(), switches,
              steps);
}

}  // namespace

TEMPLATE_LIST_TEST_CASE("stress: report table", "[integrate][stress][.report]",
                        TUMBLE_TEST_PARAMETERIZATIONS) {
  using P = TestType;
  const std::string name(P::name);
  const double k = 1e3 / kOmega.norm();
  for (const CvodeMethod m : {CvodeMethod::adams, CvodeMethod::bdf}) {
    const LongRun r = long_tumble<P>(m, 1e-9, 500.0);
    report_row("tumbling 500 s", name, method_name(m), 1e-9, r.energy_drift, r.momentum_drift,
               P::has_constraint ? r.quaternion_drift : -1.0, r.switches, r.steps);
    const LongRun f = long_tumble<P>(m, 1e-9, 100.0 / k, k);
    report_row("fast spin 1e3 rad/s", name, method_name(m), 1e-9, f.energy_drift, f.momentum_drift,
               P::has_constraint ? f.quaternion_drift : -1.0, f.switches, f.steps);
    const ClosedFormRun c = closed_form_error<P>({1e-6, 1.0, 1.0}, {3.0, 1.0, 0.5}, m, 1e-10, 20.0);
    report_row("thin rod 20 s", name, method_name(m), 1e-10, c.energy, -1.0, -1.0, c.switches,
               c.steps);
    if constexpr (!P::has_constraint) {
      const SingularRun s = singular_run<P>(m, 1e-10, 20);
      report_row("singular, 20 turns", name, method_name(m), 1e-10, s.energy, s.momentum, -1.0,
                 s.switches, s.steps);
    }
  }
}

#if TUMBLE_TEST_PRIMARY_SLICE
TEST_CASE("stress: report table, stiff springs", "[integrate][stress][.report]") {
  for (const double ratio : {1e4, 1e6, 1e8}) {
    const StiffRun r = stiff_run(ratio, CvodeMethod::bdf, 100000);
    char scene[32];
    std::snprintf(scene, sizeof scene, "spring k/m = %.0e", ratio);
    report_row(scene, "EulerParameters", "BDF", 1e-8, -1.0, -1.0, r.drift, 0, r.steps);
  }
}
#endif
