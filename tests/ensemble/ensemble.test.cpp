// tumble::Ensemble and tumble::integrate_variants (include/tumble/ensemble/), each property
// against an independent expectation:
//  - the tumbling body (I = diag(1, 2, 3), omega0 = (0.1, 2, 0.05) rad/s dispersed per run, MRP in
//    the quasi-velocity form, so that runs switch charts) integrated by OdeintIntegrator
//    (Fehlberg 7(8); Dormand-Prince, whose integrate() interpolates its outputs, with one output
//    time and with several) and by the CVODE SceneIntegrator (Adams and BDF): every run's result,
//    with 1 thread and with 2 threads (several grain sizes), and over two calls of one ensemble
//    (its integrators kept), bitwise equal to a plain serial loop that makes a new integrator
//    for each run and calls its integrate(); and each run's attitude near the Jacobi elliptic
//    solution (tests/support/torque_free.hpp);
//  - a factory that takes the run index (per-run options: a step budget that run 2 cannot
//    meet), against the serial loop of the same factory;
//  - more threads than the machine has: the threads the ensemble says it runs, and the
//    statistics of a call;
//  - failing runs (a non-finite initial state, an observer that throws, a load that throws in a
//    per-run scene) reported with their index and message, the other runs' results unchanged and
//    equal to the serial loop's, including the run a thread does right after a failed one; their
//    sum, by fold_runs and by Ensemble::fold in blocks, equal to the serial loop's in run order;
//  - per-run scenes (dispersed inertia) against the same serial loop and the closed form;
//  - the integrators' per-step buffers on whole cache lines (Odeint's dynamic state, CVODE's
//    vectors and their clones);
//  - no allocation per step (operator new counted, tests/integrate/alloc_counter.hpp), and fewer
//    per run than making an integrator.

// Must precede every Eigen include (see alloc_counter.hpp).
#define EIGEN_RUNTIME_NO_MALLOC

#include "tumble/ensemble/ensemble.hpp"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include <Eigen/Core>
#include <oneapi/tbb/info.h>

#include "integrate/alloc_counter.hpp"
#include "support/catch.hpp"
#include "support/random.hpp"
#include "support/scene_fixtures.hpp"
#include "support/torque_free.hpp"
#include "tumble/body/rigid_body.hpp"
#include "tumble/core/cache_line.hpp"
#include "tumble/ensemble/variants.hpp"
#include "tumble/force/user_force.hpp"
#include "tumble/integrate/explicit_integrator.hpp"
#include "tumble/integrate/scene_integrator.hpp"
#include "tumble/orientation/modified_rodrigues.hpp"
#include "tumble/scene/observables.hpp"
#include "tumble/scene/scene.hpp"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using tumble::Bodies;
using tumble::EnsembleOptions;
using tumble::Loads;
using tumble::RunOutcome;
using tumble::SceneState;
using tumble::StateForm;
using tumble::test::kTumblingInertia;
using tumble::test::kTumblingOmega;

using Body = tumble::RigidBody<tumble::ModifiedRodriguesParameters>;
using SceneT = tumble::Scene<Bodies<Body>, Loads<>, StateForm::quasi_velocities>;
constexpr int kN = 3 + 3 + 6;  // [r; sigma; v; omega]
using Odeint = tumble::OdeintIntegrator<SceneT, kN>;

const Matrix3d kR0 = tumble::test::rot(0.5, Vector3d(1, -1, 2));
constexpr double kTol = 1e-10;
constexpr double kEnd = 20.0;

/// Run i's initial rates: omega0 dispersed by up to 2 % per component.
Vector3d run_omega(std::size_t i) {
  const double x = static_cast<double>(i);
  return kTumblingOmega.cwiseProduct(
      Vector3d::Ones() + 0.02 * Vector3d(std::sin(1.1 * x), std::cos(0.7 * x), std::sin(0.3 * x)));
}

/// What a run keeps: its state at the last output time and the number of outputs seen.
struct Final {
  Matrix3d attitude = Matrix3d::Zero();
  Vector3d omega = Vector3d::Zero();
  int outputs = 0;
};

struct Tumbling {
  SceneT scene;
  tumble::BodyId<Body> b;
  std::vector<SceneState> states;  ///< per run
  std::vector<double> times;

  explicit Tumbling(std::size_t runs, std::vector<double> outputs = {0.0, 5.0, 10.0, 15.0, kEnd})
      : times(std::move(outputs)) {
    b = scene.add(Body(tumble::test::tumbling_mass()), {.rotation = kR0, .omega = kTumblingOmega});
    for (std::size_t i = 0; i < runs; ++i) {
      SceneState s = scene.initial_state();
      tumble::set_velocity(scene, b, s, Vector3d::Zero(), run_omega(i));
      states.push_back(s);
    }
  }

  /// The observer of every ensemble here and of the serial loops.
  auto observer() const {
    return [this](Final& f, std::size_t, double, const SceneState& s) {
      f.attitude = tumble::rotation(scene, b, s);
      f.omega = tumble::omega(scene, b, s);
      ++f.outputs;
    };
  }
};

tumble::OdeintOptions odeint_options() {
  tumble::OdeintOptions o;
  o.rtol = kTol;
  o.atol = kTol;
  return o;
}
const auto make_odeint = [](const SceneT& s, double t0, const SceneState& y0) {
  return Odeint(s, t0, y0, odeint_options());
};
const auto make_cvode = [](const SceneT& s, double t0, const SceneState& y0) {
  return tumble::SceneIntegrator<SceneT>(
      s, t0, y0, tumble::test::integrator_options(tumble::CvodeMethod::adams, kTol));
};
// Dormand-Prince: integrate() reads the outputs off the dense output (interpolate_outputs, on by
// default), where advance(t) would step to each output time: a run must take the same path.
const auto make_dopri = [](const SceneT& s, double t0, const SceneState& y0) {
  tumble::OdeintOptions o = odeint_options();
  o.method = tumble::OdeintMethod::dopri5;
  return Odeint(s, t0, y0, o);
};
// The size known only at run time: the state and Odeint's stage buffers are vectors on cache
// lines of their own (detail::OdeintState), where the fixed size keeps them in the integrator.
const auto make_odeint_dynamic = [](const SceneT& s, double t0, const SceneState& y0) {
  return tumble::OdeintIntegrator<SceneT>(s, t0, y0, odeint_options());
};
// BDF keeps more between steps (the Newton iteration, the exact Jacobian and when to update it):
// all of it reset() must not carry from one run into the next.
const auto make_cvode_bdf = [](const SceneT& s, double t0, const SceneState& y0) {
  return tumble::SceneIntegrator<SceneT>(
      s, t0, y0, tumble::test::integrator_options(tumble::CvodeMethod::bdf, kTol));
};

/// The independent expectation: run i alone, a new integrator from make, its integrate().
struct SerialRun {
  Final final;
  long steps = 0;
  long switches = 0;  ///< chart switches: a reused integrator must restart on the run's own chart
};
template <class Make>
std::vector<SerialRun> serial_loop(const Tumbling& t, const Make& make, std::size_t runs) {
  std::vector<SerialRun> out(runs);
  for (std::size_t i = 0; i < runs; ++i) {
    auto integrator = make(t.scene, 0.0, t.states[i]);
    const auto observe = t.observer();
    integrator.integrate(t.times,
                         [&](double tk, const SceneState& s) { observe(out[i].final, i, tk, s); });
    out[i].steps = integrator.statistics().steps;
    out[i].switches = integrator.statistics().chart_switches;
  }
  return out;
}

void check_same(const RunOutcome<Final>& got, const Final& want, std::size_t i) {
  INFO("run " << i);
  REQUIRE(got.ok());
  CHECK(got.value().outputs == want.outputs);
  CHECK(got.value().attitude == want.attitude);  // bitwise
  CHECK(got.value().omega == want.omega);
}

/// Each serial run against the Jacobi elliptic solution of its own omega0.
void check_physics(const Tumbling& t, const std::vector<SerialRun>& serial) {
  for (std::size_t i = 0; i < serial.size(); ++i) {
    const tumble::test::TorqueFreeBody exact(kTumblingInertia, run_omega(i), kR0);
    const double bound = tumble::test::global_error_bound(kTol, serial[i].steps, 2.0, kEnd);
    INFO("run " << i << ", " << serial[i].steps << " steps, bound " << bound);
    CHECK(serial[i].final.outputs == static_cast<int>(t.times.size()));
    CHECK(serial[i].switches > 0);
    CHECK(tumble::test::rotation_angle_between(serial[i].final.attitude, exact.rotation(kEnd)) <
          bound);
    CHECK((serial[i].final.omega - exact.omega(kEnd)).norm() < bound);
  }
}

template <class Make>
void check_thread_independence(const Make& make, std::size_t runs,
                               std::vector<double> times = {0.0, 5.0, 10.0, 15.0, kEnd}) {
  const Tumbling t(runs, std::move(times));
  const auto serial = serial_loop(t, make, runs);
  check_physics(t, serial);
  const tumble::Ensemble ensemble1(t.scene, make, {.threads = 1});
  const auto initial = [&](std::size_t i) -> const SceneState& { return t.states[i]; };
  const auto one = ensemble1.template integrate<Final>(runs, initial, 0.0, t.times, t.observer());
  REQUIRE(one.size() == runs);
  for (std::size_t i = 0; i < runs; ++i) {
    check_same(one[i], serial[i].final, i);
  }
  for (const std::size_t grain : {std::size_t{1}, std::size_t{3}}) {
    for (const int threads : {2, 0}) {
      const tumble::Ensemble ensemble(t.scene, make, {.threads = threads, .grain = grain});
      // Twice: the second call runs on the integrators the first one left in the threads.
      for (const int call : {1, 2}) {
        INFO(threads << " threads, grain " << grain << ", call " << call);
        const auto many =
            ensemble.template integrate<Final>(runs, initial, 0.0, t.times, t.observer());
        REQUIRE(many.size() == runs);
        for (std::size_t i = 0; i < runs; ++i) {
          check_same(many[i], serial[i].final, i);
        }
      }
    }
  }
}

bool mentions(const std::string& what, const std::string& part) {
  return what.find(part) != std::string::npos;
}

}  // namespace

TEST_CASE("ensemble: runs equal a serial loop to the bit, whatever the threads",
          "[ensemble][ensemble]") {
  SECTION("OdeintIntegrator, Fehlberg 7(8)") { check_thread_independence(make_odeint, 16); }
  SECTION("OdeintIntegrator, Fehlberg 7(8), N = Eigen::Dynamic") {
    check_thread_independence(make_odeint_dynamic, 8);
  }
  SECTION("OdeintIntegrator, Fehlberg 7(8), one output") {
    check_thread_independence(make_odeint, 8, {kEnd});
  }
  SECTION("OdeintIntegrator, Dormand-Prince, several outputs") {
    check_thread_independence(make_dopri, 16);
  }
  // The case: outputs inside the steps, read off the dense output.
  SECTION("OdeintIntegrator, Dormand-Prince, two outputs") {
    check_thread_independence(make_dopri, 8, {0.5 * kEnd, kEnd});
  }
  SECTION("OdeintIntegrator, Dormand-Prince, one output") {
    check_thread_independence(make_dopri, 8, {kEnd});
  }
  SECTION("SceneIntegrator (CVODE, Adams)") { check_thread_independence(make_cvode, 8); }
  SECTION("SceneIntegrator (CVODE, BDF)") { check_thread_independence(make_cvode_bdf, 6); }
}

TEST_CASE("ensemble: a failing run is reported with its index, the others are kept",
          "[ensemble][ensemble]") {
  constexpr std::size_t runs = 10;
  Tumbling t(runs);
  const auto serial = serial_loop(t, make_odeint, runs);
  t.states[3].y[kN - 2] = std::numeric_limits<double>::quiet_NaN();  // omega_y of run 3
  const auto observe = [base = t.observer()](Final& f, std::size_t i, double tk,
                                             const SceneState& s) {
    if (i == 6 && tk > 7.0) {
      throw std::runtime_error("observer refuses run 6");
    }
    base(f, i, tk, s);
  };
  const auto initial = [&](std::size_t i) -> const SceneState& { return t.states[i]; };
  for (const int threads : {1, 2}) {
    INFO(threads << " threads");
    const tumble::Ensemble ensemble(t.scene, make_odeint, {.threads = threads});
    const auto got = ensemble.integrate<Final>(runs, initial, 0.0, t.times, observe);
    REQUIRE(got.size() == runs);
    const auto errors = tumble::failures(got);
    REQUIRE(errors.size() == 2);
    CHECK(errors[0].run == 3);
    CHECK(mentions(errors[0].message, "not finite"));
    CHECK(errors[1].run == 6);
    CHECK(errors[1].message == "observer refuses run 6");
    CHECK(got[3].failed());
    CHECK(got[6].failed());
    CHECK_THROWS_AS(got[3].value(), std::logic_error);
    for (std::size_t i = 0; i < runs; ++i) {
      if (i != 3 && i != 6) {
        check_same(got[i], serial[i].final, i);  // runs 4 and 7 follow a failure
      }
    }
    // fold_runs: the successful runs, in run order.
    const double sum = tumble::fold_runs(
        got, 0.0, [](double acc, std::size_t, const Final& f) { return acc + f.omega.norm(); });
    double want = 0.0;
    for (std::size_t i = 0; i < runs; ++i) {
      want += (i != 3 && i != 6) ? serial[i].final.omega.norm() : 0.0;
    }
    CHECK(sum == want);
    // Ensemble::fold: the same sum, three runs at a time, the errors in run order.
    const auto folded = ensemble.fold<Final>(
        runs, initial, 0.0, t.times, observe, 0.0,
        [](double acc, std::size_t, const Final& f) { return acc + f.omega.norm(); }, 3);
    CHECK(folded.value == want);
    CHECK(folded.completed == runs - 2);
    REQUIRE(folded.errors.size() == 2);
    CHECK(folded.errors[0].run == 3);
    CHECK(folded.errors[1].run == 6);
    CHECK(folded.errors[1].message == "observer refuses run 6");
  }
}

// A factory that takes the run index gives each run options of its own: here run 2 a step
// budget it cannot meet and the odd runs a looser tolerance. The expectation is a serial loop
// of the same factory's integrators.
TEST_CASE("ensemble: a factory with the run index gives per-run options", "[ensemble][ensemble]") {
  constexpr std::size_t runs = 8, starved = 2;
  const Tumbling t(runs);
  const auto make = [](const SceneT& s, double t0, const SceneState& y0, std::size_t run) {
    tumble::OdeintOptions o = odeint_options();
    o.rtol = run % 2 == 1 ? 1e3 * kTol : kTol;
    o.atol = o.rtol;
    o.max_steps = run == starved ? 5 : o.max_steps;
    return Odeint(s, t0, y0, o);
  };
  std::vector<Final> want(runs);
  for (std::size_t i = 0; i < runs; ++i) {
    if (i != starved) {
      Odeint integrator = make(t.scene, 0.0, t.states[i], i);
      integrator.integrate(
          t.times, [&](double tk, const SceneState& s) { t.observer()(want[i], i, tk, s); });
    }
  }
  CHECK(want[1].attitude != want[0].attitude);  // the tolerances differ, so do the results
  const auto initial = [&](std::size_t i) -> const SceneState& { return t.states[i]; };
  for (const int threads : {1, 2}) {
    INFO(threads << " threads");
    const tumble::Ensemble ensemble(t.scene, make, {.threads = threads});
    STATIC_REQUIRE(decltype(ensemble)::per_run_factory);
    const auto got = ensemble.integrate<Final>(runs, initial, 0.0, t.times, t.observer());
    REQUIRE(got.size() == runs);
    for (std::size_t i = 0; i < runs; ++i) {
      if (i == starved) {
        REQUIRE(got[i].failed());
        CHECK(mentions(got[i].error().message, "max_steps"));
      } else {
        check_same(got[i], want[i], i);
      }
    }
    const tumble::EnsembleStatistics st = ensemble.statistics();
    CHECK(st.runs == runs);
    CHECK(st.failed == 1);
  }
}

// More threads than the machine lets this process use: the ensemble runs as many as it may
// (TBB's default concurrency, an independent count) and says so; the results are unchanged.
TEST_CASE("ensemble: more threads than cores run as many as there are, and say so",
          "[ensemble][ensemble]") {
  constexpr std::size_t runs = 6;
  const Tumbling t(runs, {kEnd});
  const auto serial = serial_loop(t, make_odeint, runs);
  const auto initial = [&](std::size_t i) -> const SceneState& { return t.states[i]; };
  const int cores = oneapi::tbb::info::default_concurrency();
  const tumble::Ensemble ensemble(t.scene, make_odeint, {.threads = cores + 3});
  CHECK(ensemble.threads() == cores);
  CHECK(ensemble.options().threads == cores + 3);  // what was asked stays readable
  CHECK(ensemble.statistics().runs == 0);          // no call yet
  const auto got = ensemble.integrate<Final>(runs, initial, 0.0, t.times, t.observer());
  for (std::size_t i = 0; i < runs; ++i) {
    check_same(got[i], serial[i].final, i);
  }
  const tumble::EnsembleStatistics st = ensemble.statistics();
  CHECK(st.runs == runs);
  CHECK(st.failed == 0);
  CHECK(st.threads == cores);
  CHECK(st.threads_used >= 1);
  CHECK(st.threads_used <= cores);
  const tumble::Ensemble serial_ensemble(t.scene, make_odeint, {.threads = 1});
  CHECK(serial_ensemble.threads() == 1);
}

TEST_CASE("ensemble: bad output times or options throw before any run", "[ensemble][ensemble]") {
  const Tumbling t(2);
  const auto initial = [&](std::size_t i) -> const SceneState& { return t.states[i]; };
  const tumble::Ensemble ensemble(t.scene, make_odeint);
  const std::vector<double> backwards{1.0, 0.5};
  CHECK_THROWS_AS(ensemble.integrate<Final>(2, initial, 0.0, backwards, t.observer()),
                  std::invalid_argument);
  const std::vector<double> before{-1.0};
  CHECK_THROWS_AS(ensemble.integrate<Final>(2, initial, 0.0, before, t.observer()),
                  std::invalid_argument);
  CHECK_THROWS_AS(tumble::Ensemble(t.scene, make_odeint, {.threads = -1}), std::invalid_argument);
  CHECK_THROWS_AS(tumble::Ensemble(t.scene, make_odeint, {.grain = 0}), std::invalid_argument);
}

namespace {

/// A load that applies nothing, except that it throws in run `fail`: a user load that fails.
struct FailingLoad {
  std::size_t run = 0, fail = 0;
  template <class Kinematics> tumble::Wrench<double> operator()(double, const Kinematics&) const {
    if (run == fail) {
      throw std::runtime_error("load of run " + std::to_string(run) + " failed");
    }
    return tumble::Wrench<double>{};
  }
};
using LoadT = tumble::UserForce<FailingLoad, false>;
using VariantScene = tumble::Scene<Bodies<Body>, Loads<LoadT>, StateForm::quasi_velocities>;
using VariantOdeint = tumble::OdeintIntegrator<VariantScene, kN>;

/// Run i's inertia: diag(1, 2, 3) with the two smaller moments up to 3 % larger and the largest
/// up to 3 % smaller (diag(1, 2, 3) lies on the triangle inequality's bound, I3 <= I1 + I2).
Vector3d run_inertia(std::size_t i) {
  const double x = static_cast<double>(i);
  const Vector3d a(std::abs(std::cos(0.9 * x)), std::abs(std::sin(1.7 * x)),
                   -std::abs(std::cos(0.4 * x)));
  return kTumblingInertia.cwiseProduct(Vector3d::Ones() + 0.03 * a);
}

}  // namespace

TEST_CASE("ensemble: per-run scenes (dispersed inertia) and a failing load",
          "[ensemble][variants]") {
  constexpr std::size_t runs = 6, fail = 2;
  const auto make_scene = [](std::size_t i) {
    VariantScene s;
    const auto b = s.add(
        Body(tumble::MassProperties<double>::about_centroid(1.0, run_inertia(i).asDiagonal())),
        {.rotation = kR0, .omega = run_omega(i)});
    s.add_load(b, LoadT(FailingLoad{i, fail}));
    return s;
  };
  const auto make = [](const VariantScene& s, double t0, const SceneState& y0) {
    return VariantOdeint(s, t0, y0, odeint_options());
  };
  const std::vector<double> times{0.0, 10.0, kEnd};
  // The observer reads the attitude through the run's own scene (its fifth argument).
  const auto observe = [](Final& f, std::size_t, double, const SceneState& s,
                          const VariantScene& scene) {
    f.attitude = tumble::rotation(scene, tumble::BodyId<Body>{0, 0}, s);
    f.omega = tumble::omega(scene, tumble::BodyId<Body>{0, 0}, s);
    ++f.outputs;
  };
  // The serial loop: the same scene, a new integrator, integrate().
  std::vector<Final> want(runs);
  for (std::size_t i = 0; i < runs; ++i) {
    if (i == fail) {
      continue;
    }
    const VariantScene s = make_scene(i);
    auto integrator = make(s, 0.0, s.initial_state());
    integrator.integrate(times,
                         [&](double tk, const SceneState& st) { observe(want[i], i, tk, st, s); });
    const tumble::test::TorqueFreeBody exact(run_inertia(i), run_omega(i), kR0);
    const double bound =
        tumble::test::global_error_bound(kTol, integrator.statistics().steps, 2.0, kEnd);
    INFO("run " << i << ", bound " << bound);
    CHECK(tumble::test::rotation_angle_between(want[i].attitude, exact.rotation(kEnd)) < bound);
    CHECK((want[i].omega - exact.omega(kEnd)).norm() < bound);
  }
  for (const int threads : {1, 2}) {
    INFO(threads << " threads");
    const auto got = tumble::integrate_variants<Final>(runs, make_scene, make, 0.0, times, observe,
                                                       {.threads = threads});
    REQUIRE(got.size() == runs);
    for (std::size_t i = 0; i < runs; ++i) {
      INFO("run " << i);
      if (i == fail) {
        REQUIRE(got[i].failed());
        CHECK(got[i].error().run == fail);
        // The integrator's what(): where and when the load threw, then its own message, as
        // CVODE words it (below).
        CHECK_THAT(got[i].error().message,
                   TUMBLE_CONTAINS("rhs() threw at t = 0: load of run 2 failed"));
      } else {
        REQUIRE(got[i].ok());
        CHECK(got[i].value().outputs == 3);
        CHECK(got[i].value().attitude == want[i].attitude);  // bitwise
        CHECK(got[i].value().omega == want[i].omega);
      }
    }
  }
  // CVODE's runs record the failing load in the same words (its what() says more before them).
  const auto cvode = [](const VariantScene& s, double t0, const SceneState& y0) {
    return tumble::SceneIntegrator(s, t0, y0);
  };
  const auto with_cvode =
      tumble::integrate_variants<Final>(runs, make_scene, cvode, 0.0, times, observe, {});
  REQUIRE(with_cvode[fail].failed());
  CHECK_THAT(with_cvode[fail].error().message,
             TUMBLE_CONTAINS("rhs() threw at t = 0: load of run 2 failed"));
  CHECK(with_cvode[fail + 1].ok());
}

// The ensemble allocates nothing per step (operator new counted; Eigen's own allocations are
// the integrators' concern, tested in tests/integrate/), and less per run than making an
// integrator costs: a thread's integrator is reset, not made again, and kept for the next call.
TEST_CASE("ensemble: no allocation per step, less per run than an integrator",
          "[ensemble][ensemble]") {
  const Tumbling t(8);
  const auto initial = [&](std::size_t i) -> const SceneState& { return t.states[i]; };
  const auto observe = [&](Final& f, std::size_t, double, const SceneState& s) {
    f.omega = s.y.tail<3>();
    ++f.outputs;
  };
  using E = tumble::Ensemble<SceneT, decltype(make_odeint)>;
  const auto count = [&](const E& ensemble, std::size_t runs, double end) {
    const std::vector<double> times{end};
    tumble::test::reset_allocation_count();
    tumble::test::set_allocation_counting(true);
    const auto r = ensemble.integrate<Final>(runs, initial, 0.0, times, observe);
    tumble::test::set_allocation_counting(false);
    CHECK(tumble::failures(r).empty());
    return tumble::test::allocation_count();
  };
  // Each on a new ensemble: the first call makes the thread's integrator.
  const auto fresh = [&](std::size_t runs, double end) {
    return count(E(t.scene, make_odeint, {.threads = 1}), runs, end);
  };
  const long short_runs = fresh(4, 2.0);
  const long long_runs = fresh(4, kEnd);  // ten times the steps
  CHECK(long_runs == short_runs);
  const long per_run = (fresh(8, 2.0) - short_runs) / 4;
  tumble::test::reset_allocation_count();
  tumble::test::set_allocation_counting(true);
  { const Odeint one(t.scene, 0.0, t.states[0], odeint_options()); }
  tumble::test::set_allocation_counting(false);
  const long construction = tumble::test::allocation_count();
  INFO(per_run << " allocations per run, " << construction << " to make an integrator");
  CHECK(per_run < construction);
  // A second call of one ensemble runs on the integrator the first one made: its results'
  // vector and its runs' resets, nothing more.
  const E kept(t.scene, make_odeint, {.threads = 1});
  const long first = count(kept, 4, 2.0);
  const long second = count(kept, 4, 2.0);
  INFO(first << " allocations in the first call, " << second << " in the second");
  CHECK(second <= 1 + 4 * per_run);
  CHECK(second < first);
}

// What an integrator writes at every step, where it is on the heap, is whole cache lines of its
// own (core/cache_line.hpp): two threads' integrators never write one line, wherever the heap
// puts them (docs/benchmarks.md, "calls in a row").
TEST_CASE("ensemble: what the integrators write at every step is on cache lines of their own",
          "[ensemble][ensemble]") {
  const auto on_lines = [](const void* p) {
    return reinterpret_cast<std::uintptr_t>(p) % tumble::kCacheLine == 0;
  };
  // OdeintIntegrator with N = Eigen::Dynamic: its state vectors, and Odeint's stage buffers of the
  // same type.
  static_assert(std::is_same_v<tumble::detail::OdeintState<Eigen::Dynamic>::allocator_type,
                               tumble::CacheLineAllocator<double>>);
  tumble::detail::OdeintState<Eigen::Dynamic> x(5, 0.0);
  CHECK(on_lines(x.data()));
  // CVODE: the vector tumble gives CVodeInit and every clone CVODE makes of it (the Nordsieck
  // array, the weights, the solvers' work vectors), freed by SUNDIALS' own destroy.
  for (const bool fused : {false, true}) {
    tumble::detail::ErrorCapture capture;
    const tumble::detail::ContextHandle ctx = tumble::detail::make_context(capture);
    const tumble::detail::NVectorHandle y =
        tumble::detail::make_serial_vector(13, ctx.get(), fused);
    CHECK(on_lines(N_VGetArrayPointer(y.get())));
    CHECK(N_VGetLength(y.get()) == 13);
    const tumble::detail::NVectorHandle clone(N_VClone(y.get()));
    REQUIRE(clone != nullptr);
    CHECK(on_lines(N_VGetArrayPointer(clone.get())));
    const tumble::detail::NVectorHandle grandchild(N_VClone(clone.get()));
    REQUIRE(grandchild != nullptr);
    CHECK(on_lines(N_VGetArrayPointer(grandchild.get())));
    N_VConst(1.5, grandchild.get());
    CHECK(N_VMaxNorm(grandchild.get()) == 1.5);
  }
  const Tumbling t(1);
  tumble::SceneIntegrator<SceneT> cvode = make_cvode_bdf(t.scene, 0.0, t.states[0]);
  cvode.advance(1.0);
  CHECK(on_lines(cvode.cvode().state().data()));
}
