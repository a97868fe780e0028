// tumble::AutoIntegrator and tumble::integrate, the front door (integrate/auto_integrator.hpp),
// and the vocabulary the three integrators share (integrate/common.hpp), each against an
// independent expectation:
//  - the torque-free tumbling body: the explicit path, no hand-over, and the attitude of the
//    Jacobi elliptic solution (tests/support/torque_free.hpp);
//  - a top on an overdamped stiff spring-damper at its tip (the main job's damped stiff top):
//    BDF from the start, and the trajectory of the CVODE SceneIntegrator with BDF at a tolerance
//    100 times tighter;
//  - a body that a heavily damped spring catches at t = 1 s (stiff from then on): the explicit
//    path, then BDF from a time after 1 s, and the trajectory of BDF over the whole run;
//  - outputs denser than the steps: the hand-over to Dormand-Prince's dense output;
//  - one generic function compiled for OdeintIntegrator, SceneIntegrator and AutoIntegrator:
//    the same option and statistics names, saved states that do not change when the integrator
//    goes on, the same errors.
// Measured numbers: run with TUMBLE_TEST_REPORT=1.

#include "tumble/integrate/auto_integrator.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "support/catch.hpp"
#include "support/random.hpp"
#include "support/scene_fixtures.hpp"
#include "support/torque_free.hpp"
#include "tumble/body/rigid_body.hpp"
#include "tumble/force/gravity.hpp"
#include "tumble/force/spring_damper.hpp"
#include "tumble/force/user_force.hpp"
#include "tumble/integrate/explicit_integrator.hpp"
#include "tumble/integrate/scene_integrator.hpp"
#include "tumble/orientation/euler_parameters.hpp"
#include "tumble/scene/observables.hpp"
#include "tumble/scene/scene.hpp"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using tumble::AutoIntegrator;
using tumble::AutoMethod;
using tumble::AutoOptions;
using tumble::Bodies;
using tumble::Loads;
using tumble::MassProperties;
using tumble::RigidBody;
using tumble::Scene;
using tumble::SceneState;
using tumble::test::rot;

bool reporting() {
  static const bool on = std::getenv("TUMBLE_TEST_REPORT") != nullptr;
  return on;
}
template <class... A> void report(const char* format, A... args) {
  if (reporting()) {
    std::printf(format, args...);
  }
}

void report_choices(const tumble::AutoStatistics& st) {
  for (const auto& c : st.choices) {
    report("  from t = %.6g: %s -- %s\n", c.from, tumble::name(c.method), c.why.c_str());
  }
}

AutoOptions tolerance(double tol) {
  AutoOptions o;
  o.rtol = tol;
  o.atol = tol;
  return o;
}

std::vector<double> grid(double t_end, int intervals) {
  std::vector<double> t;
  for (int k = 0; k <= intervals; ++k) {
    t.push_back(t_end * k / intervals);
  }
  return t;
}

/// The largest difference of the positions and of the attitudes (rad) of the one body of two
/// runs sampled at the same times.
struct Difference {
  double position = 0, attitude = 0;
};
template <class SceneT, class Id>
void accumulate(Difference& d, const SceneT& scene, Id id, const SceneState& a,
                const SceneState& b) {
  d.position = std::max(d.position,
                        (tumble::position(scene, id, a) - tumble::position(scene, id, b)).norm());
  d.attitude =
      std::max(d.attitude, tumble::test::rotation_angle_between(tumble::rotation(scene, id, a),
                                                                tumble::rotation(scene, id, b)));
}

// ---- scenes -------------------------------------------------------------------------------------

using Ep = RigidBody<tumble::EulerParameters>;

/// The tumbling body of the physics tests (I = diag(1, 2, 3), near the separatrix).
struct Tumbling {
  using SceneT = Scene<Bodies<Ep>>;
  SceneT scene;
  tumble::BodyId<Ep> id;
  Matrix3d r0 = rot(0.5, Vector3d(1, -1, 2));
  Tumbling() {
    id = scene.add(Ep(tumble::test::tumbling_mass()),
                   {.rotation = r0, .omega = tumble::test::kTumblingOmega});
  }
};

/// The main job's damped stiff top: a top (0.5 kg, spinning at 150 rad/s, tilted 0.35 rad)
/// whose tip is held by an overdamped spring-damper, k/m = 1e6 s^-2, c/m = 4e4 s^-1.
struct DampedStiffTop {
  using Body = RigidBody<tumble::EulerParameters, tumble::ReferencePoint::offset>;
  using SceneT = Scene<Bodies<Body>, Loads<tumble::UniformGravity, tumble::SpringDamper>>;
  SceneT scene;
  tumble::BodyId<Body> id;
  DampedStiffTop() {
    const auto mp = MassProperties<>::about_centroid(
        0.5, Vector3d(1.5e-3, 1.5e-3, 1.0e-3).asDiagonal(), Vector3d(0, 0, 0.05));
    id = scene.add(Body(mp), {.rotation = rot(0.35, Vector3d::UnitX()), .omega = {0, 0, 150}});
    scene.add_load(id, tumble::UniformGravity({0, 0, -9.81}));
    scene.add_load(id, tumble::SpringDamper(Vector3d::Zero(), Vector3d::Zero(),
                                            {.stiffness = 5e5, .damping = 2e4, .rest_length = 0}));
  }
};

/// A body tumbling freely until t = 1 s, when a spring-damper to the origin catches it at its
/// reference point (k/m = 10 s^-2, c/m = 1e5 s^-1: overdamped, a decay rate of 1e5 s^-1 beside
/// the motion's 1e-4 s^-1 and 2 rad/s).
struct CaughtAtOne {
  static constexpr double kMass = 1.0, kStiffness = 10.0, kDamping = 1e5, kCatch = 1.0;
  /// The spring-damper from kCatch on, for any scalar (so that BDF gets the exact Jacobian).
  struct Catch {
    template <class S, tumble::ReferencePoint Ref>
    tumble::Wrench<S> operator()(const S& t, const tumble::BodyKinematics<S, Ref>& k) const {
      tumble::Wrench<S> w;
      if (tumble::detail::value(t) >= kCatch) {
        w.force = -(S(kStiffness) * k.position + S(kDamping) * k.velocity);
      }
      return w;
    }
  };
  using Catcher = tumble::UserForce<Catch, false>;
  using SceneT = Scene<Bodies<Ep>, Loads<Catcher>>;
  SceneT scene;
  tumble::BodyId<Ep> id;
  CaughtAtOne() {
    id = scene.add(Ep(MassProperties<>::about_centroid(kMass, Vector3d(1, 2, 3).asDiagonal())),
                   {.position = {1.0, 0.5, -0.2},
                    .velocity = {0.3, -0.1, 0.2},
                    .omega = tumble::test::kTumblingOmega});
    scene.add_load(id, Catcher(Catch{}));
  }
};

}  // namespace

TEST_CASE("front door: the tumbling body takes the explicit path and meets the exact solution",
          "[integrate][auto_integrator]") {
  Tumbling s;
  const tumble::test::TorqueFreeBody exact(tumble::test::kTumblingInertia,
                                           tumble::test::kTumblingOmega, s.r0);
  const double tol = 1e-10;
  double err = 0;
  const tumble::AutoStatistics st = tumble::integrate(
      s.scene, 0.0, grid(50.0, 100),
      [&](double t, const SceneState& y) {
        err = std::max(err, tumble::test::rotation_angle_between(tumble::rotation(s.scene, s.id, y),
                                                                 exact.rotation(t)));
      },
      tolerance(tol));
  report("tumbling, tol %.0e: attitude error %.3g rad, %ld steps, %ld rhs\n", tol, err, st.steps,
         st.rhs_evals);
  report_choices(st);
  REQUIRE(st.choices.size() == 1);
  CHECK(st.choices.front().method == AutoMethod::fehlberg78);
  CHECK(st.choices.front().from == 0.0);
  CHECK(st.steps > 0);
  CHECK(st.projections == st.steps);  // Euler parameters projected after every step
  // Fehlberg 7(8) at 1e-10 on this body: 3.8e-9 rad (explicit_integrator.test.cpp).
  CHECK(err < 2e-8);
}

TEST_CASE("front door: the damped stiff top takes BDF from the start",
          "[integrate][auto_integrator]") {
  DampedStiffTop s;
  const double tol = 1e-7;
  const std::vector<double> times = grid(0.1, 50);
  std::vector<SceneState> got;
  const auto st = tumble::integrate(
      s.scene, 0.0, times, [&](double, const SceneState& y) { got.push_back(y); }, tolerance(tol));
  report("damped stiff top, tol %.0e: %ld steps, %ld rhs\n", tol, st.steps, st.rhs_evals);
  report_choices(st);
  REQUIRE(st.choices.size() == 1);
  CHECK(st.choices.front().method == AutoMethod::bdf);
  CHECK(st.choices.front().why.find("stiff at the start") != std::string::npos);
  // The same scene under SceneIntegrator, BDF, 100 times tighter.
  tumble::SceneIntegrator reference(
      s.scene, 0.0, tumble::test::integrator_options(tumble::CvodeMethod::bdf, tol / 100));
  Difference d;
  std::size_t k = 0;
  reference.integrate(
      times, [&](double, const SceneState& y) { accumulate(d, s.scene, s.id, got[k++], y); });
  report("  against BDF at %.0e: %.3g m, %.3g rad\n", tol / 100, d.position, d.attitude);
  CHECK(k == times.size());
  CHECK(d.position < 1e-5);
  CHECK(d.attitude < 1e-4);
}

TEST_CASE("front door: a scene that turns stiff mid-run hands over to BDF",
          "[integrate][auto_integrator]") {
  CaughtAtOne s;
  const double tol = 1e-8;
  const std::vector<double> times = grid(3.0, 30);
  // The outputs (every 0.1 s) would also hand Fehlberg 7(8) over to Dormand-Prince's dense
  // output (measured: at t = 0.2, its controller asking for 0.45 s); kept on Fehlberg 7(8) here,
  // the test is of the hand-over to BDF.
  AutoOptions o = tolerance(tol);
  o.dense_outputs = false;
  AutoIntegrator<CaughtAtOne::SceneT> integrator(s.scene, 0.0, o);
  CHECK(integrator.method() == AutoMethod::fehlberg78);
  std::vector<SceneState> got;
  integrator.integrate(times, [&](double, const SceneState& y) { got.push_back(y); });
  const auto st = integrator.statistics();
  report("caught at t = 1: %ld steps, %ld rejected, %ld rhs\n", st.steps, st.rejected_steps,
         st.rhs_evals);
  report_choices(st);
  REQUIRE(st.choices.size() == 2);
  CHECK(st.choices[0].method == AutoMethod::fehlberg78);
  CHECK(st.choices[1].method == AutoMethod::bdf);
  CHECK(st.choices[1].from >= CaughtAtOne::kCatch);
  CHECK(st.choices[1].from < times.back());
  CHECK(st.choices[1].why.find("looks stiff") != std::string::npos);
  CHECK(integrator.method() == AutoMethod::bdf);
  REQUIRE(got.size() == times.size());
  // The closed form: the translation is free until t = 1, then m x'' = -k x - c x' (the force acts
  // at the centroid, so the rotation stays torque-free: the Jacobi elliptic solution). With
  // x(1) = x1, x'(1) = v1 and the roots l1, l2 of m l^2 + c l + k = 0 (overdamped: l1 = -1e-4,
  // l2 = -1e5 s^-1), x(1 + s) = A e^(l1 s) + (x1 - A) e^(l2 s), A = (v1 - l2 x1) / (l1 - l2).
  // (BDF itself, at 100 times the tolerance, was no reference here: its implicit step over the
  // switch at t = 1 caught the body up to 5 ms early, 1.8e-3 m off.)
  const Vector3d x0(1.0, 0.5, -0.2), v0(0.3, -0.1, 0.2);
  const long double m = CaughtAtOne::kMass, c = CaughtAtOne::kDamping, k = CaughtAtOne::kStiffness;
  const long double root = std::sqrt(c * c - 4 * m * k);
  const long double l1 = (-c + root) / (2 * m), l2 = (-c - root) / (2 * m);
  const auto position_at = [&](double t) {
    Vector3d x;
    for (int i = 0; i < 3; ++i) {
      const long double x1 = x0(i) + v0(i) * std::min(t, CaughtAtOne::kCatch);
      if (t <= CaughtAtOne::kCatch) {
        x(i) = static_cast<double>(x1);
        continue;
      }
      const long double a = (v0(i) - l2 * x1) / (l1 - l2), sg = t - CaughtAtOne::kCatch;
      x(i) = static_cast<double>(a * std::exp(l1 * sg) + (x1 - a) * std::exp(l2 * sg));
    }
    return x;
  };
  const tumble::test::TorqueFreeBody exact(Vector3d(1, 2, 3), tumble::test::kTumblingOmega,
                                           Matrix3d::Identity());
  double dx = 0, dx_caught = 0, da = 0;
  for (std::size_t i = 0; i < times.size(); ++i) {
    const double e = (tumble::position(s.scene, s.id, got[i]) - position_at(times[i])).norm();
    (times[i] <= CaughtAtOne::kCatch ? dx : dx_caught) =
        std::max(times[i] <= CaughtAtOne::kCatch ? dx : dx_caught, e);
    da = std::max(da, tumble::test::rotation_angle_between(tumble::rotation(s.scene, s.id, got[i]),
                                                           exact.rotation(times[i])));
  }
  report("  against the closed form: %.3g m before the catch, %.3g m after, %.3g rad\n", dx,
         dx_caught, da);
  CHECK(dx < 1e-6);
  CHECK(da < 1e-6);
  // After the catch the position is 1.8e-3 m off (the body caught about 5 ms late or early): a
  // defect of the explicit step across the abrupt switch, shown by the next test case, not of
  // the hand-over. Recorded, not asserted away: dx_caught is reported above.
  // Caught: the spring holds the body near the origin (k x = -c v: it creeps in at k/c = 1e-4
  // per second from where the damper stopped it).
  CHECK(tumble::position(s.scene, s.id, got.back()).norm() < 2.0);
}

TEST_CASE("front door: outputs denser than the steps go to Dormand-Prince's dense output",
          "[integrate][auto_integrator]") {
  Tumbling s;
  const tumble::test::TorqueFreeBody exact(tumble::test::kTumblingInertia,
                                           tumble::test::kTumblingOmega, s.r0);
  const double tol = 1e-7;
  double err = 0;
  const auto st = tumble::integrate(
      s.scene, 0.0, grid(20.0, 2000),  // every 0.01 s
      [&](double t, const SceneState& y) {
        err = std::max(err, tumble::test::rotation_angle_between(tumble::rotation(s.scene, s.id, y),
                                                                 exact.rotation(t)));
      },
      tolerance(tol));
  report("tumbling, 2001 outputs, tol %.0e: attitude error %.3g rad, %ld steps, %ld rhs\n", tol,
         err, st.steps, st.rhs_evals);
  report_choices(st);
  REQUIRE(st.choices.size() == 2);
  CHECK(st.choices[1].method == AutoMethod::dopri5);
  CHECK(st.choices[1].from > 0.0);
  CHECK(st.choices[1].from < 0.1);
  // Far fewer steps than outputs: the outputs are interpolated.
  CHECK(st.steps < 1000);
  CHECK(err < 1e-5);
}

namespace {

/// Written once for any of the three integrators: the shared option names, advance, save,
/// state, statistics. Returns the saved state at t = 1 and the final one at t = 2.
template <class Integrator, class SceneT>
std::pair<SceneState, SceneState> generic_run(const SceneT& scene, double tol) {
  typename Integrator::Options o;
  o.rtol = tol;
  o.atol = tol;
  o.max_steps = 100000;
  o.max_step = 0.5;
  Integrator integrator(scene, 0.0, o);
  integrator.advance(1.0);
  const SceneState saved = integrator.save();
  const SceneState& now = integrator.state();  // a view: it moves on with the integrator
  integrator.advance(2.0);
  CHECK(now.y == integrator.state().y);
  const typename Integrator::Statistics st = integrator.statistics();
  CHECK(st.steps > 0);
  CHECK(st.rhs_evals > st.steps);
  CHECK(st.rejected_steps >= 0);
  CHECK(st.chart_switches == 0);
  CHECK(st.projections > 0);
  CHECK(st.events == 0);
  return {saved, integrator.save()};
}

}  // namespace

TEST_CASE("the shared vocabulary: one function for the three integrators",
          "[integrate][auto_integrator]") {
  Tumbling s;
  const tumble::test::TorqueFreeBody exact(tumble::test::kTumblingInertia,
                                           tumble::test::kTumblingOmega, s.r0);
  const auto check = [&](const std::pair<SceneState, SceneState>& r, double bound) {
    CHECK(tumble::test::rotation_angle_between(tumble::rotation(s.scene, s.id, r.first),
                                               exact.rotation(1.0)) < bound);
    CHECK(tumble::test::rotation_angle_between(tumble::rotation(s.scene, s.id, r.second),
                                               exact.rotation(2.0)) < bound);
  };
  using SceneT = Tumbling::SceneT;
  check(
      generic_run<tumble::OdeintIntegrator<SceneT, tumble::state_size<SceneT, Ep>>>(s.scene, 1e-10),
      1e-8);
  check(generic_run<tumble::SceneIntegrator<SceneT>>(s.scene, 1e-10), 1e-7);
  check(generic_run<AutoIntegrator<SceneT>>(s.scene, 1e-10), 1e-8);
  // The same defaults of the shared options.
  const tumble::OdeintOptions odeint;
  const tumble::SceneIntegratorOptions cvode;
  const AutoOptions front;
  CHECK(odeint.rtol == cvode.rtol);
  CHECK(front.rtol == cvode.rtol);
  CHECK(odeint.atol == cvode.atol);
  CHECK(front.atol == cvode.atol);
  CHECK(odeint.max_steps == 0);
  CHECK(cvode.max_steps == 0);
  CHECK(front.max_steps == 0);
}

TEST_CASE("the shared vocabulary: a spent step budget is IntegrationFailure::step_budget",
          "[integrate][auto_integrator]") {
  Tumbling s;
  const auto spend = [&](auto integrator) {
    try {
      integrator.advance(50.0);
      FAIL("no exception");
    } catch (const tumble::IntegrationError& e) {
      CHECK(e.reason() == tumble::IntegrationFailure::step_budget);
      CHECK(e.time() > 0.0);
      CHECK(e.time() < 50.0);
      CHECK(std::string(e.what()).find("max_steps") != std::string::npos);
    }
  };
  tumble::OdeintOptions o;
  o.rtol = 1e-10;
  o.atol = 1e-10;
  o.max_steps = 20;
  spend(tumble::OdeintIntegrator<Tumbling::SceneT>(s.scene, 0.0, o));
  tumble::SceneIntegratorOptions c;
  c.rtol = 1e-10;
  c.atol = 1e-10;
  c.max_steps = 20;
  spend(tumble::SceneIntegrator<Tumbling::SceneT>(s.scene, 0.0, c));
  AutoOptions a = tolerance(1e-10);
  a.max_steps = 20;
  spend(AutoIntegrator<Tumbling::SceneT>(s.scene, 0.0, a));
}

TEST_CASE("front door: per-entry absolute tolerances, and bad options named",
          "[integrate][auto_integrator]") {
  Tumbling s;
  AutoOptions o = tolerance(1e-10);
  Eigen::VectorXd atol = Eigen::VectorXd::Constant(s.scene.size(), 1e-10);
  o.atol = atol;
  AutoIntegrator<Tumbling::SceneT> integrator(s.scene, 0.0, o);
  integrator.advance(1.0);
  const SceneState a = integrator.save();
  AutoIntegrator<Tumbling::SceneT> scalar(s.scene, 0.0, tolerance(1e-10));
  scalar.advance(1.0);
  CHECK(a.y == scalar.state().y);  // the same tolerance, per entry or not: the same steps

  o.atol = Eigen::VectorXd::Constant(3, 1e-10);
  CHECK_THROWS_WITH(AutoIntegrator<Tumbling::SceneT>(s.scene, 0.0, o),
                    TUMBLE_CONTAINS("'atol' per entry must have the state's size"));
  AutoOptions bad = tolerance(1e-10);
  bad.rtol = -1;
  CHECK_THROWS_WITH(AutoIntegrator<Tumbling::SceneT>(s.scene, 0.0, bad),
                    TUMBLE_CONTAINS("'rtol' must be finite and > 0"));
  bad = tolerance(1e-10);
  bad.stiffness_window = -1;
  CHECK_THROWS_AS(AutoIntegrator<Tumbling::SceneT>(s.scene, 0.0, bad), std::invalid_argument);
  AutoIntegrator<Tumbling::SceneT> ok(s.scene, 0.0);
  ok.advance(1.0);
  CHECK_THROWS_AS(ok.integrate({0.5}, [](double, const SceneState&) {}), std::invalid_argument);
}

// A known defect, kept as a test that must fail until it is fixed: Fehlberg 7(8) alone, stepping
// from t = 1 (an output) with its controller's long step into the force that switched on there
// (c/m = 1e5 s^-1), accepts a step whose error estimate misses the stiff transient, and the
// body ends up about 1.8e-3 m from the closed form (measured), where the tolerance asks for 1e-8.
TEST_CASE("explicit integrator: a step across an abrupt switch to stiffness [known defect]",
          "[integrate][auto_integrator][!shouldfail]") {
  CaughtAtOne s;
  tumble::OdeintOptions o;
  o.rtol = 1e-8;
  o.atol = 1e-8;
  o.stiffness_window = 0;
  tumble::OdeintIntegrator<CaughtAtOne::SceneT> integrator(s.scene, 0.0, o);
  std::vector<SceneState> got;
  integrator.integrate(grid(1.1, 11), [&](double, const SceneState& y) { got.push_back(y); });
  const double x = 1.0 + 0.3 * 1.0;  // caught at t = 1 within 1e-5 s: x moves by v/(c/m) = 3e-6
  REQUIRE(got.size() == 12);
  CHECK(std::abs(tumble::position(s.scene, s.id, got.back()).x() - x) < 1e-5);
}
