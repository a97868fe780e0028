#pragma once
// What ensemble.hpp and variants.hpp share: the integrator requirements, the check of the output
// times, and one run (the integrator's own integrate() over the output times, the observer at
// each, the run's failure caught).

#include <cmath>
#include <cstddef>
#include <exception>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "tumble/core/format.hpp"
#include "tumble/ensemble/outcome.hpp"
#include "tumble/integrate/common.hpp"
#include "tumble/scene/state.hpp"

namespace tumble {

namespace detail {
/// An observer of integrate() that keeps nothing (what EnsembleIntegrator is checked with).
struct IgnoreOutput {
  void operator()(double, const SceneState&) const {}
};
}  // namespace detail

/// What an ensemble needs of an integrator: integrate(times, observer), calling observer(t,
/// const SceneState&) at each output time, and reset(t, s) to restart from another state.
/// SceneIntegrator (CVODE), OdeintIntegrator (Boost.Odeint) and AutoIntegrator model it. A run is
/// its integrator's integrate(), so that it computes what a serial integrate() computes, to the
/// bit, with every option of the integrator (Dormand-Prince's interpolated outputs among them).
template <class I>
concept EnsembleIntegrator = requires(I& integrator, double t, const SceneState& s,
                                      const std::vector<double>& times) {
  integrator.integrate(times, detail::IgnoreOutput{});
  integrator.reset(t, s);
};

namespace detail {

/// \throws std::invalid_argument unless the output times are finite, non-decreasing and not
/// before t0 (checked once, before any run: a mistake of the ensemble, not of a run).
template <class Times> void check_output_times(double t0, const Times& times) {
  if (!std::isfinite(t0)) {
    throw std::invalid_argument("tumble::Ensemble: the start time is not finite");
  }
  check_output_times("tumble::Ensemble", t0, times, "the start time");
}

/// Integrates over the output times with the integrator's own integrate() and calls
/// observe(result, run, t, state, scene) at each, or observe(result, run, t, state) when the
/// observer takes no scene.
template <class R, class SceneT, class Integrator, class Times, class Observer>
R observe_run(const SceneT& scene, Integrator& integrator, std::size_t run, const Times& times,
              Observer& observe) {
  R result{};
  integrator.integrate(times, [&](double t, const SceneState& s) {
    if constexpr (std::is_invocable_v<Observer&, R&, std::size_t, double, const SceneState&,
                                      const SceneT&>) {
      observe(result, run, t, s, scene);
    } else {
      observe(result, run, t, s);
    }
  });
  return result;
}

/// True when the factory takes the run's index too: make(scene, t0, s0, run).
template <class Make, class SceneT>
inline constexpr bool factory_takes_run =
    std::is_invocable_v<const Make&, const SceneT&, double, const SceneState&, std::size_t>;

/// The integrator of run `run` from (t0, s0): make(scene, t0, s0, run), or make(scene, t0, s0)
/// for a factory that takes no run index.
template <class Make, class SceneT>
auto make_for_run(const Make& make, const SceneT& scene, double t0, const SceneState& s0,
                  std::size_t run) {
  if constexpr (factory_takes_run<Make, SceneT>) {
    return make(scene, t0, s0, run);
  } else {
    return make(scene, t0, s0);
  }
}

/// The type of integrator a factory makes (with or without the run index).
template <class Make, class SceneT>
using FactoryIntegrator = std::remove_cvref_t<decltype(make_for_run(
    std::declval<const Make&>(), std::declval<const SceneT&>(), 0.0,
    std::declval<const SceneState&>(), std::size_t{}))>;

/// The outcome of a run: body() -> R, or the RunError of what it threw.
template <class R, class Body> RunOutcome<R> guarded_run(std::size_t run, Body&& body) {
  try {
    return RunOutcome<R>(body());
  } catch (const std::exception& e) {
    return RunOutcome<R>(RunError{run, e.what()});
  } catch (...) {
    return RunOutcome<R>(RunError{run, "an exception not derived from std::exception"});
  }
}

}  // namespace detail
}  // namespace tumble
