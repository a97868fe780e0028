#pragma once
// Ensembles whose runs differ in the model itself: each run builds its own scene (dispersed
// inertia, masses, load parameters) and integrates it from that scene's initial state. The same
// contract as Ensemble::integrate (ensemble.hpp): a result or a RunError per run, in run order,
// the same to the bit for any thread count.
//
// An integrator refers to its scene, so here each run makes its own from its own scene (the
// integrators are not reused across runs, as in Ensemble). When only the initial state differs,
// Ensemble with one shared scene is cheaper.

#include <cstddef>
#include <type_traits>
#include <utility>
#include <vector>

#include "tumble/ensemble/detail/run.hpp"
#include "tumble/ensemble/options.hpp"
#include "tumble/ensemble/outcome.hpp"
#include "tumble/ensemble/parallel.hpp"

namespace tumble {

namespace detail {

/// Run i of integrate_variants: its scene, a new integrator of it, the observations; its
/// outcome (shared with mpi_integrate_variants, mpi.hpp).
template <class R, class MakeScene, class MakeIntegrator, class Times, class Observer>
RunOutcome<R> variant_run(std::size_t i, MakeScene& make_scene, MakeIntegrator& make_integrator,
                          double t0, const Times& times, Observer& observe) {
  using SceneT = std::remove_cvref_t<std::invoke_result_t<MakeScene&, std::size_t>>;
  using Integrator = FactoryIntegrator<MakeIntegrator, SceneT>;
  static_assert(EnsembleIntegrator<Integrator>,
                "the factory must return an integrator with integrate(times, observer) and "
                "reset(t, state)");
  return guarded_run<R>(i, [&] {
    const SceneT scene = make_scene(i);
    Integrator integrator = make_for_run(make_integrator, scene, t0, scene.initial_state(), i);
    return observe_run<R>(scene, integrator, i, times, observe);
  });
}

}  // namespace detail

/// Runs 0, ..., runs-1: run i builds its scene, scene = make_scene(i) (a Scene, by value, its
/// initial state the run's), integrates it with make_integrator(scene, t0,
/// scene.initial_state() [, i]) (the run index if the factory takes it) over `times`, with the
/// integrator's integrate(), and calls observe(R& result, std::size_t run,
/// double t, const SceneState& [, const SceneT& the run's scene]) at each.
///
/// \returns one RunOutcome per run, in run order.
/// \throws std::invalid_argument for bad output times or options (before any run).
template <class R, class MakeScene, class MakeIntegrator, class Times, class Observer>
std::vector<RunOutcome<R>> integrate_variants(std::size_t runs, MakeScene&& make_scene,
                                              MakeIntegrator&& make_integrator, double t0,
                                              const Times& times, Observer&& observe,
                                              const EnsembleOptions& options = {}) {
  detail::check_output_times(t0, times);
  struct NoWorker {};
  std::vector<RunOutcome<R>> out(runs);
  for_each_run<NoWorker>(runs, options, [&](NoWorker&, std::size_t i) {
    out[i] = detail::variant_run<R>(i, make_scene, make_integrator, t0, times, observe);
  });
  return out;
}

}  // namespace tumble
