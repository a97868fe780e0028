// tumble_bench: tumble's scenes (work_precision/tumble_scene.hpp) integrated by
// tumble::OdeintIntegrator<SceneT, N> (docs/integrators.md), N = the scene's size at compile time
// (the state a std::array, no heap in a step), with Boost.Odeint's Fehlberg 7(8) and
// Dormand-Prince 5(4) pairs, rtol = atol = tol, in both state forms: [q; v; omega]
// (StateForm::quasi_velocities) and [q; qdot] (StateForm::generalized), for Euler parameters and
// modified Rodrigues parameters. What a run does between steps (projection of p, chart
// switches, output times reached by stepping to them) is the integrator's; nothing is tuned here.
//
// Two translation units (TUMBLE_BENCH_ODEINT_GROUP, set by main/tumble_bench.cmake): the
// headline configuration, Fehlberg 7(8) with Euler parameters on [q; v; omega] ("Odeint F78 EP
// quasi"), alone in unit 0, as a user's program with one scene type, and as each kind of the
// floors it is compared with (floors/odeint.cpp) is compiled; the other eight in unit 1. In one
// unit with the eight, GCC 12 -O3 reaches its whole-unit inlining limit (`--param
// inline-unit-growth`: -fopt-info-inline-missed names it 1,788 times, Odeint's stage sums and
// controller among them) and the headline ran 1.16-1.25x its floor in the main job's harness,
// 1.10-1.20x in a unit of its own, pinned, alternating the two builds (2026-12-05,
// twenty-fourth session; docs/benchmarks/floors.md). The eight others stay together: one unit
// per configuration took 840 CPU s to compile against 165 (2026-12-02, nineteenth session).

#ifndef TUMBLE_BENCH_ODEINT_GROUP
#error "compiled through the units main/tumble_bench.cmake generates (TUMBLE_BENCH_ODEINT_GROUP)"
#endif

#include <exception>
#include <string>
#include <vector>

#include "common/bench.hpp"
#include "tumble/integrate/explicit_integrator.hpp"
#include "work_precision/tumble_scene.hpp"

namespace tumble::bench {
namespace {

/// Times `reps` runs of: construct the OdeintIntegrator, integrate over the output times and
/// record a Sample at each (as run_scene does for CVODE, work_precision/tumble.hpp).
template <class SceneT, class Body, class Build>
Run run_odeint_scene(const Problem& p, const MethodSetting& c, const Timing& timing, Build build) {
  constexpr int N = SceneT::template Entry<Body>::block_size;  // one body: the scene's size
  Run run;
  run.samples.resize(p.times.size());
  std::vector<double> times;
  try {
    SceneT scene;
    const BodyId<Body> id = build(scene);
    OdeintOptions options;
    options.method = c.scheme == Scheme::dopri5 ? OdeintMethod::dopri5 : OdeintMethod::fehlberg78;
    options.rtol = c.tol;
    options.atol = c.tol;
    do {
      const Stopwatch watch;
      OdeintIntegrator<SceneT, N> integrator(scene, 0.0, options);
      std::size_t k = 0;
      integrator.integrate(p.times, [&](double, const SceneState& y) {
        run.samples[k++] = scene_sample(scene, id, y);
      });
      record_time(run, times, watch, timing);
      const OdeintStatistics st = integrator.statistics();
      run.steps = st.steps;
      run.rhs_evals = st.rhs_evals;
      run.error_test_failures = st.rejected_steps;
      run.chart_switches = st.chart_switches;
      if constexpr (Body::Param::has_constraint) {
        run.constraint_drift = tumble::constraint_drift(scene, integrator.state());
      }
    } while (another_rep(timing, times));
  } catch (const std::exception& e) {
    run.ok = false;
    run.error = e.what();
  }
  finish_timing(run, times);
  return run;
}

template <class P, StateForm Form, Translation T>
Run run_tumble_odeint(const Problem& p, const MethodSetting& c, const Timing& timing) {
  return visit_problem_scene<P, Form, T>(p, [&]<class SceneT, class Body>(auto build) {
    return run_odeint_scene<SceneT, Body>(p, c, timing, build);
  });
}

/// The entry "Odeint F78 EP quasi" (Fehlberg 7(8), Euler parameters, [q; v; omega]), ...; with
/// Translation::free, "... free": the torque-free problems with the body free (r and v in the
/// state), to show what carrying them costs.
template <class P, StateForm Form, Translation T = Translation::attitude_only>
Method odeint_method(Scheme scheme, const std::string& set, bool quick) {
  const std::string stepper = scheme == Scheme::dopri5 ? "DP5" : "F78";
  const std::string form = Form == StateForm::quasi_velocities ? "quasi" : "[q; qd]";
  const bool free = T == Translation::free;
  return {.label = "Odeint " + stepper + " " + set + " " + form + (free ? " free" : ""),
          .family = "tumble",
          .parameterization = std::string(P::name),
          .schemes = {scheme},
          .quick = quick,
          .applies = free ? &torque_free : nullptr,
          .run = &run_tumble_odeint<P, Form, T>};
}

}  // namespace

#if TUMBLE_BENCH_ODEINT_GROUP == 0
void add_tumble_methods_d(std::vector<Method>& list) {
  list.push_back(
      odeint_method<EulerParameters, StateForm::quasi_velocities>(Scheme::rkf78, "EP", true));
  add_tumble_methods_d_others(list);
}
#else
void add_tumble_methods_d_others(std::vector<Method>& list) {
  using EP = EulerParameters;
  using MRP = ModifiedRodriguesParameters;
  constexpr StateForm quasi = StateForm::quasi_velocities;
  constexpr StateForm generalized = StateForm::generalized;
  list.push_back(odeint_method<EP, quasi, Translation::free>(Scheme::rkf78, "EP", true));
  list.push_back(odeint_method<EP, quasi>(Scheme::dopri5, "EP", true));
  list.push_back(odeint_method<MRP, quasi>(Scheme::rkf78, "MRP", true));
  list.push_back(odeint_method<MRP, quasi>(Scheme::dopri5, "MRP", false));
  list.push_back(odeint_method<EP, generalized>(Scheme::rkf78, "EP", true));
  list.push_back(odeint_method<EP, generalized>(Scheme::dopri5, "EP", false));
  list.push_back(odeint_method<MRP, generalized>(Scheme::rkf78, "MRP", false));
  list.push_back(odeint_method<MRP, generalized>(Scheme::dopri5, "MRP", false));
}
#endif

}  // namespace tumble::bench
