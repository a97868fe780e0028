// The IFToMM multibody benchmark problems of group A that have an independent reference here:
// A01, the simple pendulum (a point mass on a massless 1 m bar, released horizontally: Jacobi's
// sn), and A02, the N-four-bar (N + 1 cranks and N couplers, all 1 m and 1 kg, B0 at 1 m/s),
// whose motion has one degree of freedom: the cranks stay parallel, and in the crank angle it is
// the rotating pendulum I theta'' = G sin theta, integrated as a second, minimal-coordinate
// model (both models in joint/n_four_bar_reference.hpp, shared with the main job's study (e)). The
// N-four-bar passes its singular position (all links on one line, where the loop momentarily gains
// N degrees of freedom) twice per turn. A03, Andrews' mechanism: andrews.test.cpp; A04, Bricard's
// mechanism: bricard.test.cpp; the slider-crank (revolute and prismatic joints) against its
// closed-form position: examples.test.cpp.

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include <Eigen/Geometry>

#include "joint/n_four_bar_reference.hpp"
#include "support/catch.hpp"
#include "support/pendulum.hpp"
#include "tumble/integrate.hpp"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using namespace tumble;

constexpr double g0 = 9.81;
using Ball = RigidBody<EulerParameters>;
// A02's models, tumble's (NFourBar) and the minimal-coordinate one (crank_angle), are shared
// with the main job's study (e): joint/n_four_bar_reference.hpp.
using n_four_bar_test::crank_angle;
using n_four_bar_test::NFourBar;

}  // namespace

TEST_CASE("IFToMM A01: the simple pendulum against Jacobi's sn", "[joint][iftomm]") {
  // The point mass: a small ball whose centre hangs on a Distance joint (a massless bar with
  // spherical ends) from the origin; the joint transmits no moment, so the ball's inertia does
  // not enter the motion of its centre. Gravity along -y, released at rest at x = +1 m.
  Mechanism<Bodies<Ball>, Joints<Distance>, Loads<UniformGravity>> scene;
  const auto ball =
      scene.add(Ball(MassProperties<>::about_centroid(1.0, Matrix3d::Identity() * 4e-5)),
                {.position = Vector3d(1, 0, 0)});
  scene.add_load(ball, UniformGravity(Vector3d(0, -g0, 0)));
  scene.add_joint(ball, ground, Distance(Vector3d::Zero(), Vector3d::Zero(), 1.0));
  // theta from straight down: theta0 = pi/2, w0 = sqrt(g / l).
  const double theta0 = std::numbers::pi / 2, w0 = std::sqrt(g0);
  std::vector<double> times;
  for (int i = 0; i <= 400; ++i) {
    times.push_back(0.025 * i);  // 10 s, 400 outputs
  }
  const double e0 = energy(scene, scene.initial_state());
  double err = 0.0, de = 0.0;
  integrate(scene, 0.0, times,
            [&](double t, const SceneState& s) {
              const double theta = tumble::test::pendulum_angle(theta0, w0, t);
              const Vector3d exact(std::sin(theta), -std::cos(theta), 0.0);
              err = std::max(err, (position(scene, ball, s) - exact).norm());
              de = std::max(de, std::abs(energy(scene, s) - e0));
            },
            {.rtol = 1e-11, .atol = 1e-11});
  INFO("largest position error " << err << " m, energy change " << de << " J");
  CHECK(err <= 1e-8);  // the benchmark's high precision asks for 1e-3
  CHECK(de <= 1e-8);
}

/// Runs the N-four-bar to t_end with integrator I at tol and returns the largest crank-angle
/// error against the minimal-coordinate model, with the energy and the closure checked; the
/// integrator's statistics into `stats` when given; `window` > 0: its stiffness window.
template <int N, class I>
double n_four_bar_error(bool hanging, double t_end, double tol,
                        typename I::Statistics* stats = nullptr, long window = 0) {
  NFourBar m(N, hanging);
  SceneState s = m.scene.initial_state();
  const AssemblyReport rep = assemble(m.scene, s);
  CHECK(rep.before.position <= 1e-15);  // placed exactly
  CHECK(rep.after.rank == 12 * N + 5);  // 6 (2N + 1) coordinates, 1 degree of freedom
  const double e0 = energy(m.scene, s);
  double err = 0.0, de = 0.0, drift = 0.0;
  std::vector<double> times;
  for (int i = 0; i <= 100; ++i) {
    times.push_back(t_end * i / 100.0);
  }
  typename I::Options opt;
  opt.rtol = tol;
  opt.atol = tol;
  if (window > 0) {
    opt.stiffness_window = window;
  }
  I integrator(m.scene, 0.0, s, opt);
  integrator.integrate(times, [&](double t, const SceneState& x) {
    // The first crank's angle from +y towards +x, from its body x axis (R x = (sin, cos)).
    const double theta = m.crank_angle(x);
    err = std::max(
        err, std::abs(std::remainder(theta - crank_angle(N, hanging, t), 2 * std::numbers::pi)));
    de = std::max(de, std::abs(energy(m.scene, x) - e0));
    drift = std::max(drift, constraint_residual(m.scene, x).position);
  });
  if (stats != nullptr) {
    *stats = integrator.statistics();
  }
  INFO("N = " << N << ": crank angle error " << err << " rad, energy change " << de << " J, drift "
              << drift << " m");
  CHECK(de <= 1e3 * tol * std::abs(e0));
  CHECK(drift <= 1e-12 * (N + 1));  // relative to the mechanism's size, N + 1 m
  return err;
}

TEMPLATE_TEST_CASE_SIG("IFToMM A02: the N-four-bar swinging against the minimal-coordinate "
                       "model",
                       "[joint][iftomm]", ((int N), N), 2, 10) {
  // Hanging, the loop (rank 12 N + 5 of 15 N + 5 rows: N + 1 redundant planar windows in 3D)
  // swings 0.3 rad about its stable position for the benchmark's 10 s.
  using I = OdeintIntegrator<NFourBar::SceneT>;
  CHECK(n_four_bar_error<N, I>(true, 10.0, 1e-10) <= 1e-8);
}

// The benchmark's own start (cranks up, B0 at 1 m/s) turns the cranks through the singular
// position (every link on the ground line, N + 1 degrees of freedom for an instant) twice per
// turn. Near the crossing the acceleration-level constraint solve is ill-conditioned, and the
// Runge-Kutta stages, off the manifold, see reactions that vary as 1 / distance^2; the rows that
// are redundant (frozen once per run, scene/joints.hpp) change there, and the explicit integrator
// decides them again when its projection after a step shows the retained rows failing
// (scene/assembly.hpp, retained_rows_failed). Its error test asks no more of a step than the
// solve's conditioning at the step's start allows (scene/joints.hpp, attainable_tolerance): asked
// for more, the steps shrank towards the crossing without end, and the stiffness test stopped the
// run. A stiffness window with such relaxed steps draws no verdict. Measured (GCC 12, 100
// outputs, 10 s), the crank angle against the minimal-coordinate model:
//                     tol 1e-8              1e-10                 1e-12
//   N = 2, before     5.8e-6                stopped at 3.17 s     stopped at 0.71 s
//   N = 2, after      5.8e-6                6.4e-8                stopped at 3.17 s
//   N = 2, pivots     5.8e-6                6.5e-8                stopped at 6.54 s
//   N = 2, floor      5.8e-6                5.0e-8                2.3e-8 (453 of 637 steps relaxed)
//   N = 1, pivots                           8.2e-8                stopped at 8.40 s
//   N = 1, floor                                                  2.1e-9 (304 of 546 steps relaxed)
//   N = 10, all       5.4e-6                stopped at 0.72 s     stopped at 0.72 s
//   N = 10, floor                           stopped at 2.68 s
//   N = 10, floor and window                3.9e-6 (1258 of 1505 steps relaxed)
// ("stopped": by the stiffness test, the steps held at the crossing; "pivots": the rows also
// decided again where the retained ones near dependence, 2026-12-02; "floor": the error test
// raised to the attainable tolerance, 2026-12-05, which is at most sqrt(eps) = 1.5e-8; "window":
// and no stiffness verdict from a window with relaxed steps, the same day). What is
// left is the formulation's own limit near the crossing: a state there is pinned to the branch
// only to rounding over the vanishing pivot, so a crossing costs about 1e-8 rad whatever the
// tolerance. Asserted: N = 2 at 1e-10, and N = 1 and 2 at 1e-12, within the bound this test had
// as a known defect, 1e-7.
TEST_CASE("IFToMM A02: the N-four-bar through its singular positions", "[joint][iftomm]") {
  using I = OdeintIntegrator<NFourBar::SceneT>;
  CHECK(n_four_bar_error<2, I>(false, 10.0, 1e-10) <= 1e-7);
}

TEMPLATE_TEST_CASE_SIG("IFToMM A02: the N-four-bar through its singular positions at 1e-12",
                       "[joint][iftomm]", ((int N), N), 1, 2) {
  using I = OdeintIntegrator<NFourBar::SceneT>;
  OdeintStatistics st;
  CHECK(n_four_bar_error<N, I>(false, 10.0, 1e-12, &st) <= 1e-7);
  INFO(st.relaxed_steps << " of " << st.steps << " steps relaxed, to at most "
                        << st.loosest_tolerance);
  CHECK(st.relaxed_steps > 0);
  CHECK(st.loosest_tolerance <= std::sqrt(std::numeric_limits<double>::epsilon()));
}

// At most 8 stiffness windows in a row with relaxed steps draw no verdict, counted within one
// output interval: counted over the whole run, windows of 50 attempts reached the cap on the
// 2-four-bar at 1e-12, the verdict read stiffness and the run stopped at 4.60 s (measured).
TEST_CASE("IFToMM A02: short stiffness windows through the singular positions", "[joint][iftomm]") {
  using I = OdeintIntegrator<NFourBar::SceneT>;
  OdeintStatistics st;
  CHECK(n_four_bar_error<2, I>(false, 10.0, 1e-12, &st, 50) <= 1e-7);
  CHECK(st.relaxed_steps > 0);
}

// Away from the singular positions (hanging) the solve is well-conditioned (the retained rows'
// pivots within 6e-2 of each other) and no step is relaxed.
TEST_CASE("IFToMM A02: no step of the hanging N-four-bar is relaxed", "[joint][iftomm]") {
  using I = OdeintIntegrator<NFourBar::SceneT>;
  OdeintStatistics st;
  CHECK(n_four_bar_error<2, I>(true, 10.0, 1e-12, &st) <= 1e-10);  // 1.9e-12 measured
  CHECK(st.relaxed_steps == 0);
  CHECK(st.loosest_tolerance == 0.0);
}

// The front door's stiffness test at the start measures the Jacobian by difference quotients of
// the right-hand side. With the N-four-bar's redundant rows (35 rows of rank 29) decided anew at
// each evaluation, the pivots could fall differently at the perturbed states, and the quotients
// measured that jump: h rho = 556 at tol 1e-4 (the smooth field's 0.35), after a change of
// rounding elsewhere (2026-12-02), and the scene went to BDF, three times slower and less
// accurate. The rows are now decided once at the start, as the integrators decide them.
// Measured at 1e-8 (GCC 12): h rho 0.12, crank angle within 6.2e-10 rad hanging and 5.8e-6 rad
// through the crossings (Fehlberg 7(8)'s own figure, above).
TEST_CASE("IFToMM A02: the front door runs the N-four-bar on the explicit path",
          "[joint][iftomm]") {
  for (const bool hanging : {true, false}) {
    NFourBar m(2, hanging);
    SceneState s = m.scene.initial_state();
    (void)assemble(m.scene, s);
    std::vector<double> times;
    for (int i = 0; i <= 100; ++i) {
      times.push_back(0.1 * i);
    }
    double err = 0.0;
    const AutoStatistics st = tumble::integrate(
        m.scene, 0.0, s, times,
        [&](double t, const SceneState& x) {
          err = std::max(err, std::abs(std::remainder(m.crank_angle(x) - crank_angle(2, hanging, t),
                                                      2 * std::numbers::pi)));
        },
        {.rtol = 1e-8, .atol = 1e-8});
    REQUIRE(!st.choices.empty());
    INFO((hanging ? "hanging: " : "turning: ")
         << st.choices.front().why << "; crank angle error " << err << " rad");
    CHECK(st.choices.size() == 1);
    CHECK(st.choices.front().method == AutoMethod::fehlberg78);
    CHECK(err <= (hanging ? 1e-8 : 1e-5));
  }
}

// KNOWN DEFECT, kept failing on purpose: N = 10 at 1e-10 runs the 10 s, but its crossings cost
// 100 times N = 2's (3.9e-6 rad, above). Over the steps held at a crossing the retained rows'
// pivot ratio stays near the rank test's threshold, 1e-10 (measured: 2e-11 to 3e-10), where the
// floor is at its cap.
// CVODE's BDF with difference-quotient Jacobians fails at the first crossing of N = 2 (t = 1.23
// s). Every crossing needs a formulation well-conditioned there (an index-3 augmented Lagrangian
// with projections, or the crossing located and stepped over).
TEST_CASE("IFToMM A02: the 10-four-bar through its singular positions at 1e-10",
          "[joint][iftomm][!shouldfail]") {
  using I = OdeintIntegrator<NFourBar::SceneT>;
  CHECK(n_four_bar_error<10, I>(false, 10.0, 1e-10) <= 1e-7);
}
