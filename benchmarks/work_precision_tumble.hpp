#pragma once
// tumble_bench: one problem integrated by tumble itself, a Scene of one RigidBody<P> with
// SceneIntegrator, for any orientation parameterization P. Instantiated for the sixteen
// parameterizations in work_precision_tumble_a.cpp and work_precision_tumble_b.cpp (two
// translation units so that a two-core build compiles them side by side).
//
// The scene is what a user would write for each problem: a body framed at its centroid
// (ReferencePoint::centroid) with no loads for the torque-free problems; framed at a point off
// its centroid (ReferencePoint::offset) with UniformGravity for the thrown body; and with
// UniformGravity and a SpringDamper from its reference point (the tip) to the inertial origin for
// the stiff top. Euler parameters are projected onto |p| = 1 after every BDF step and stabilized
// (Baumgarte) with Adams; three-parameter sets re-center their charts (SceneIntegrator).

#include <algorithm>
#include <exception>
#include <string>
#include <vector>

#include "tumble/cvode.hpp"
#include "work_precision.hpp"

namespace tumble::bench {

inline SceneIntegratorOptions scene_options(const MethodSetting& c) {
  SceneIntegratorOptions o;
  o.cvode.method = c.scheme == Scheme::bdf ? CvodeMethod::bdf : CvodeMethod::adams;
  o.cvode.rtol = c.tol;
  o.cvode.atol = c.tol;
  o.cvode.use_system_jacobian = c.exact_jacobian;
  o.cvode.fused_vector_operations = c.fused;
  return o;
}

inline InitialState initial_state(const Problem& p) {
  return {.position = p.position0, .rotation = p.r0, .velocity = p.velocity0, .omega = p.omega0};
}

inline MassProperties<> mass_properties(const Problem& p) {
  return MassProperties<>::about_centroid(p.mass, Eigen::Matrix3d(p.inertia.asDiagonal()),
                                          p.centroid);
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
        Sample& s = run.samples[k++];
        s.rotation = tumble::rotation(scene, id, y);
        s.omega = tumble::omega(scene, id, y);
        s.position = tumble::position(scene, id, y);
        s.velocity = tumble::velocity(scene, id, y);
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

/// tumble on problem `p` with parameterization P.
template <class P> Run run_tumble(const Problem& p, const MethodSetting& c, const Timing& timing) {
  switch (p.kind) {
    case ProblemKind::tumbling:
    case ProblemKind::minor_axis:
    case ProblemKind::major_axis:
    case ProblemKind::spinner: {
      using Body = RigidBody<P>;
      return run_scene<Scene<Bodies<Body>>, Body>(p, c, timing, [&](auto& scene) {
        return scene.add(Body(mass_properties(p)), initial_state(p));
      });
    }
    case ProblemKind::gravity_offset: {
      using Body = RigidBody<P, ReferencePoint::offset>;
      using SceneT = Scene<Bodies<Body>, Loads<UniformGravity>>;
      return run_scene<SceneT, Body>(p, c, timing, [&](auto& scene) {
        const auto id = scene.add(Body(mass_properties(p)), initial_state(p));
        scene.add_load(id, UniformGravity(p.gravity));
        return id;
      });
    }
    case ProblemKind::stiff_top: {
      using Body = RigidBody<P, ReferencePoint::offset>;
      using SceneT = Scene<Bodies<Body>, Loads<UniformGravity, SpringDamper>>;
      return run_scene<SceneT, Body>(p, c, timing, [&](auto& scene) {
        const auto id = scene.add(Body(mass_properties(p)), initial_state(p));
        scene.add_load(id, UniformGravity(p.gravity));
        scene.add_load(
            id, SpringDamper(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                             {.stiffness = p.stiffness, .damping = p.damping, .rest_length = 0.0}));
        return id;
      });
    }
  }
  Run failed;
  failed.ok = false;
  failed.error = "unknown problem";
  return failed;
}

/// The method entry of tumble with parameterization P on [q; qdot], CVODE Adams and BDF.
template <class P> Method tumble_method(bool quick) {
  return {.label = std::string(P::name),
          .family = "tumble",
          .parameterization = std::string(P::name),
          .schemes = {Scheme::adams, Scheme::bdf},
          .quick = quick,
          .applies = nullptr,
          .run = &run_tumble<P>};
}

}  // namespace tumble::bench
