#pragma once
// What ensemble.hpp and variants.hpp share: the integrator requirements, the check of the output
// times, and one run (advance to each output time, observe, catch the run's failure).

#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdio>
#include <exception>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

#include "tumble/ensemble/outcome.hpp"
#include "tumble/scene/state.hpp"

namespace tumble {

/// What an ensemble needs of an integrator: advance(t) to an output time, state() there, and
/// reset(t, s) to restart from another state. SceneIntegrator (CVODE) and
/// OdeintIntegrator (Boost.Odeint) model it.
template <class I>
concept EnsembleIntegrator = requires(I& integrator, double t, const SceneState& s) {
  integrator.advance(t);
  { integrator.state() } -> std::convertible_to<const SceneState&>;
  integrator.reset(t, s);
};

namespace detail {

/// \throws std::invalid_argument unless the output times are finite, non-decreasing and not
/// before t0 (checked once, before any run: a mistake of the ensemble, not of a run).
template <class Times> void check_output_times(double t0, const Times& times) {
  if (!std::isfinite(t0)) {
    throw std::invalid_argument("tumble::Ensemble: the start time is not finite");
  }
  double last = t0;
  for (const auto& value : times) {
    const double t = static_cast<double>(value);
    if (!std::isfinite(t) || t < last) {
      char buf[96];
      std::snprintf(buf, sizeof buf, "%.17g after %.17g", t, last);
      throw std::invalid_argument("tumble::Ensemble: the output times must be finite, "
                                  "non-decreasing and not before the start time; found " +
                                  std::string(buf));
    }
    last = t;
  }
}

/// Advances `integrator` to each output time and calls observe(result, run, t, state, scene)
/// there, or observe(result, run, t, state) when the observer takes no scene.
template <class R, class SceneT, class Integrator, class Times, class Observer>
R observe_run(const SceneT& scene, Integrator& integrator, std::size_t run, const Times& times,
              Observer& observe) {
  R result{};
  for (const auto& value : times) {
    const double t = static_cast<double>(value);
    integrator.advance(t);
    const SceneState& s = integrator.state();
    if constexpr (std::is_invocable_v<Observer&, R&, std::size_t, double, const SceneState&,
                                      const SceneT&>) {
      observe(result, run, t, s, scene);
    } else {
      observe(result, run, t, s);
    }
  }
  return result;
}

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
