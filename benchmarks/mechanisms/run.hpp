#pragma once
// tumble_bench, study (e): one timed run of a mechanism by one of tumble's integrators, for the
// problems' translation units (mechanisms/<problem>.cpp). Timed as the single-body study times
// its runs (common/bench.hpp): construction of the integrator plus integrate() over all output
// times, best of Timing::reps; the observer records what the problem's error measure needs (the
// error itself is computed after the run, outside the timing).

#include <cstddef>
#include <exception>
#include <string>
#include <utility>
#include <vector>

#include "common/bench.hpp"
#include "mechanisms/mechanisms.hpp"
#include "mechanisms/track.hpp"  // PointTrackError, the measure of A01 and A04
#include "tumble/integrate.hpp"

namespace tumble::bench {

/// Runs `scene` from its initial state over `times` with integrator I at rtol = atol = tol;
/// record(k, state) at the k-th output. Fills the timing, counters and, in constraint_drift, the
/// constraint residual max |C| at the end of the last repetition. Returns true when the run was
/// refused as stiff (StiffSceneError: an explicit method at its stability bound), which says
/// nothing of the tighter tolerances, where the accuracy asked for sets the steps.
template <class I, class SceneT, class Record>
bool timed_mechanism_run(const SceneT& scene, typename I::Options options,
                         const std::vector<double>& times, const Timing& timing, Record& record,
                         Run& run, std::string& note) {
  bool stiff = false;
  std::vector<double> seconds;
  try {
    do {
      const Stopwatch watch;
      I integrator(scene, 0.0, options);
      std::size_t k = 0;
      integrator.integrate(times, [&](double, const SceneState& s) { record(k++, s); });
      record_time(run, seconds, watch, timing);
      const auto st = integrator.statistics();
      run.steps = st.steps;
      run.rhs_evals = st.rhs_evals;
      if constexpr (requires { st.rejected_steps; }) {
        run.error_test_failures = st.rejected_steps;
      } else {
        run.error_test_failures = st.error_test_failures;
      }
      if constexpr (requires { st.relaxed_steps; }) {
        run.relaxed_steps = st.relaxed_steps;
      }
      // CVODE's counters, SceneIntegrator's too (its statistics also have rejected_steps).
      if constexpr (requires { st.nonlinear_convergence_failures; }) {
        run.convergence_failures = st.nonlinear_convergence_failures;
        run.jacobian_evals = st.jacobian_evals;
      }
      if constexpr (requires { st.choices; }) {
        note.clear();
        for (const MethodChoice& c : st.choices) {
          note += (note.empty() ? "" : ", then ") + std::string(name(c.method));
        }
      }
      run.constraint_drift = constraint_residual(scene, integrator.state()).position;
    } while (another_rep(timing, seconds));
  } catch (const StiffSceneError& e) {
    run.ok = false;
    run.error = e.what();
    stiff = true;
  } catch (const std::exception& e) {
    run.ok = false;
    run.error = e.what();
  }
  finish_timing(run, seconds);
  return stiff;
}

/// Every method of the plan at every tolerance on `scene`: `record` as above, `measure()` the
/// error of the run just made (called after each tolerance's runs when they succeeded).
template <class SceneT, class Record, class Measure>
std::vector<MechanismRow> mechanism_sweep(const MechanismPlan& plan, const SceneT& scene,
                                          const std::vector<double>& times, Record& record,
                                          Measure measure, const std::function<void()>& step) {
  std::vector<MechanismRow> rows;
  for (const MechanismMethod m : plan.methods) {
    bool failed = false;  // at a looser tolerance: the tighter ones are not tried
    bool stiff = false;   // the run was refused as stiff: the tighter ones are tried
    for (const double tol : plan.tolerances) {
      MechanismRow r;
      r.method = mechanism_method_label(m);
      r.tol = tol;
      if (failed) {
        r.run.ok = false;
        r.run.error = "not run: failed at a looser tolerance";
        rows.push_back(std::move(r));
        step();
        continue;
      }
      switch (m) {
        case MechanismMethod::front_door:
          stiff = timed_mechanism_run<AutoIntegrator<SceneT>>(
              scene, {.rtol = tol, .atol = tol}, times, plan.timing, record, r.run, r.note);
          break;
        case MechanismMethod::odeint_f78: {
          OdeintOptions o;
          o.method = OdeintMethod::fehlberg78;
          o.rtol = tol;
          o.atol = tol;
          stiff = timed_mechanism_run<OdeintIntegrator<SceneT>>(scene, o, times, plan.timing,
                                                                record, r.run, r.note);
          break;
        }
        case MechanismMethod::cvode_bdf: {
          SceneIntegratorOptions o;
          o.method = CvodeMethod::bdf;
          o.cvode.use_system_jacobian = true;
          o.rtol = tol;
          o.atol = tol;
          stiff = timed_mechanism_run<SceneIntegrator<SceneT>>(scene, o, times, plan.timing, record,
                                                               r.run, r.note);
          break;
        }
      }
      if (r.run.ok) {
        r.error = measure();
      } else if (!stiff) {
        failed = true;
      } else {
        measure();  // clears the outputs the refused run recorded
      }
      rows.push_back(std::move(r));
      step();
    }
  }
  return rows;
}

}  // namespace tumble::bench
