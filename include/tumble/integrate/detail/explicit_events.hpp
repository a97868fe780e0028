#pragma once
// A scene's user events (scene/scene.hpp, Event) on the explicit integrator's steps
// (explicit_integrator.hpp): their functions at the two ends of each accepted step, the first
// that crossed zero located on the step's interpolant by the Illinois method, the step cut at its
// root and the event's action applied there. CVODE finds roots itself (scene_integrator.hpp).
// Nothing is allocated after construction, the user's callables aside.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "tumble/core/cache_line.hpp"
#include "tumble/integrate/detail/callback_error.hpp"
#include "tumble/integrate/detail/event_action.hpp"
#include "tumble/integrate/detail/explicit_numerics.hpp"
#include "tumble/scene/scene.hpp"
#include "tumble/scene/state.hpp"

namespace tumble::detail {

/// Whether an event function going from a to b crossed zero in the event's direction (> 0: rising
/// only, < 0: falling only, 0: both).
[[nodiscard]] inline bool crosses(double a, double b, int direction) {
  return (direction >= 0 && a < 0.0 && b >= 0.0) || (direction <= 0 && a > 0.0 && b <= 0.0);
}

/// The first of `events` whose function crossed zero over the step from t_old to t_new (values
/// g_old, g_new at its ends), its root located by the Illinois method to 1e-12 of the time scale
/// on value(i, t), event i's function at t on the step's interpolant. Returns events.size() when
/// none crossed; else the index, with its root in t_first.
template <class Events, class Values, class Value>
std::size_t first_event(const Events& events, const Values& g_old, const Values& g_new,
                        double t_old, double t_new, Value&& value, double& t_first) {
  std::size_t first = events.size();
  t_first = t_new;
  const double tol = 1e-12 * std::max(std::abs(t_new), t_new - t_old);
  for (std::size_t i = 0; i < events.size(); ++i) {
    if (!crosses(g_old[i], g_new[i], events[i].direction)) {
      continue;
    }
    const double b =
        illinois([&](double c) { return value(i, c); }, t_old, t_new, g_old[i], g_new[i], tol);
    if (b < t_first || first == events.size()) {
      first = i;
      t_first = b;
    }
  }
  return first;
}

/// The events of one scene on one integrator's steps. After each accepted step the integrator
/// calls on_step (which may cut the step at a root), then changes the state as it does between
/// steps (projection, charts), then next_step. An event function's exception becomes the
/// integrator's (guard_callbacks, "roots()").
class StepEvents {
 public:
  /// For `events` (not owned: the scene's) on states of n entries and `bodies` chart bases.
  StepEvents(const std::vector<Event>& events, Eigen::Index n, std::size_t bodies, const char* who)
      : events_(&events), n_(n), who_(who), fired_(events.size()) {
    g_old_.assign(events.size(), 0.0);
    g_new_.assign(events.size(), 0.0);
    seen_.y.setZero(n);  // what an action sees: sized once
    seen_.base.assign(bodies, Matrix3<double>::Identity());
  }

  [[nodiscard]] bool empty() const { return g_old_.empty(); }

  /// The functions at (t, x), where the next step starts (a reset).
  void start(double t, const double* x, std::span<const Matrix3<double>> base) {
    fired_ = events_->size();
    if (!empty()) {
      evaluate(t, SceneStateView(x, n_, base), g_old_);
    }
  }

  /// After a step accepted from t_old to t, ending at x: finds the first event that crossed zero
  /// on it, the step's state at any time c written into `scratch` by state_at(c, scratch). When
  /// one did, the step is cut at its root: x and t become the state just past it (scratch keeps
  /// the step's end), and its action is applied to (x, base). True if an event fired.
  template <class State, class StateAt>
  bool on_step(double t_old, double& t, State& x, State& scratch, ChartBases& base,
               StateAt&& state_at) {
    const auto& events = *events_;
    fired_ = events.size();
    evaluate(t, SceneStateView(x.data(), n_, base), g_new_);
    double t_first = t;
    const std::size_t first = first_event(
        events, g_old_, g_new_, t_old, t,
        [&](std::size_t i, double c) {
          state_at(c, scratch);
          return guard_callbacks(who_, "roots()", c, t, [&] {
            return events[i].function(c, SceneStateView(scratch.data(), n_, base));
          });
        },
        t_first);
    if (first == events.size()) {
      return false;
    }
    fired_ = first;
    if (t_first < t) {  // the state just past the root (its function on the new side)
      state_at(t_first, scratch);
      std::swap(x, scratch);
      t = t_first;
    }
    if (events[first].action) {
      Eigen::Map<Eigen::VectorXd> y(x.data(), n_);
      apply_event_action(events[first], t, seen_, y, base);
    }
    evaluate(t, SceneStateView(x.data(), n_, base), g_new_);  // after the action
    return true;
  }

  /// Before the next step from (t, x): `changed`, whether the integrator changed the state since
  /// on_step (an action, a projection, a chart re-centered), so that the functions are evaluated
  /// again instead of taken from the step's end.
  void next_step(bool changed, double t, const double* x, std::span<const Matrix3<double>> base) {
    if (empty()) {  // called after every step: nothing to do without events
      return;
    }
    if (!changed) {
      std::swap(g_old_, g_new_);
      return;
    }
    evaluate(t, SceneStateView(x, n_, base), g_old_);
    // When projection or re-centering (rounding, drift) moved the fired event's function back
    // across zero, the next step would find the same root again: it starts from zero instead.
    if (fired_ < events_->size() && (g_new_[fired_] < 0.0) != (g_old_[fired_] < 0.0)) {
      g_old_[fired_] = 0.0;
    }
  }

 private:
  void evaluate(double t, const SceneStateView& x, CacheLineVector<double>& g) {
    const auto& events = *events_;
    guard_callbacks(who_, "roots()", t, t, [&] {
      for (std::size_t i = 0; i < events.size(); ++i) {
        g[i] = events[i].function(t, x);
      }
    });
  }

  const std::vector<Event>* events_;
  Eigen::Index n_;
  const char* who_;
  CacheLineVector<double> g_old_;  ///< the functions at the step's start
  CacheLineVector<double> g_new_;  ///< and at its end
  std::size_t fired_;              ///< the event fired on the last step, or events_->size()
  SceneState seen_;
};

}  // namespace tumble::detail
