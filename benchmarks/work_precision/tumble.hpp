#pragma once
// tumble_bench: one problem integrated by tumble itself, a Scene of one RigidBody<P> with
// SceneIntegrator (CVODE Adams or BDF), for any orientation parameterization P and either state
// form: [q; qdot] (StateForm::generalized), instantiated for the sixteen parameterizations in
// work_precision/tumble_a.cpp and work_precision/tumble_b.cpp, and [q; v; omega]
// (StateForm::quasi_velocities) in work_precision/tumble_c.cpp (separate translation units so
// that a two-core build compiles them side by side). The scenes: work_precision/tumble_scene.hpp.
// Euler parameters are projected onto |p| = 1 after every BDF step and stabilized (Baumgarte, or
// the drift correction of the quasi form) with Adams; three-parameter sets re-center their charts
// (SceneIntegrator).

#include <algorithm>
#include <exception>
#include <string>
#include <vector>

#include "common/bench.hpp"
#include "tumble/cvode.hpp"
#include "work_precision/tumble_scene.hpp"

namespace tumble::bench {

inline SceneIntegratorOptions scene_options(const MethodSetting& c) {
  SceneIntegratorOptions o;
  o.method = c.scheme == Scheme::bdf ? CvodeMethod::bdf : CvodeMethod::adams;
  o.rtol = c.tol;
  o.atol = c.tol;
  o.cvode.use_system_jacobian = c.exact_jacobian;
  o.cvode.fused_vector_operations = c.fused;
  return o;
}

/// Times `reps` runs of: construct the SceneIntegrator, integrate over the output times and
/// record a Sample at each. `build(scene)` adds the body and its loads and returns its id; it
/// runs once, before the clock starts (the scene is only read by the runs).
template <class SceneT, class Body, class Build>
Run run_scene(const Problem& p, const MethodSetting& c, const Timing& timing, Build build) {
  Run run;
  run.samples.resize(p.times.size());
  std::vector<double> times;
  try {
    SceneT scene;
    const BodyId<Body> id = build(scene);
    do {
      const Stopwatch watch;
      SceneIntegrator integrator(scene, 0.0, scene_options(c));
      std::size_t k = 0;
      integrator.integrate(p.times, [&](double, const SceneState& y) {
        run.samples[k++] = scene_sample(scene, id, y);
      });
      record_time(run, times, watch, timing);
      const SceneStatistics st = integrator.statistics();
      record_statistics(run, st);
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

/// tumble on problem `p` with parameterization P, state form Form, CVODE.
template <class P, StateForm Form = StateForm::generalized>
Run run_tumble(const Problem& p, const MethodSetting& c, const Timing& timing) {
  return visit_problem_scene<P, Form>(p, [&]<class SceneT, class Body>(auto build) {
    return run_scene<SceneT, Body>(p, c, timing, build);
  });
}

/// The method entry of tumble with parameterization P on [q; qdot] (label: P's name) or on
/// [q; v; omega] (label: P's name and "quasi"), CVODE Adams and BDF.
template <class P, StateForm Form = StateForm::generalized> Method tumble_method(bool quick) {
  const std::string suffix = Form == StateForm::quasi_velocities ? " quasi" : "";
  return {.label = std::string(P::name) + suffix,
          .family = "tumble",
          .parameterization = std::string(P::name),
          .schemes = {Scheme::adams, Scheme::bdf},
          .quick = quick,
          .applies = nullptr,
          .run = &run_tumble<P, Form>};
}

}  // namespace tumble::bench
