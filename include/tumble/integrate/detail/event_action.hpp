#pragma once
// What both integrators do when a user event (scene/scene.hpp, Event) with an action fires: the
// action sees the state as a SceneState, `seen` (the integrator's own, sized once, so that
// copying into it allocates nothing), may change its values but not its sizes, and what it leaves
// becomes the integrator's state y and chart bases.

#include <stdexcept>

#include "tumble/scene/scene.hpp"
#include "tumble/scene/state.hpp"

namespace tumble::detail {

/// Runs event.action at t on (y, base) through `seen`; throws std::invalid_argument, leaving y
/// and base as they were, when the action changed a size.
template <class Y, class Base>
void apply_event_action(const Event& event, double t, SceneState& seen, Y& y, Base& base) {
  seen.y = y;
  seen.base = base;
  event.action(t, seen);
  if (seen.y.size() != y.size() || seen.base.size() != base.size()) {
    throw std::invalid_argument("tumble::Event: an action changed the size of the state");
  }
  y = seen.y;
  base = seen.base;
}

}  // namespace tumble::detail
