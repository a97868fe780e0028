#pragma once
// What both integrators check of a SceneState they are given (construction, reset): the sizes
// match the scene, and every chart base is a proper rotation.

#include <stdexcept>
#include <string>

#include "tumble/core/types.hpp"
#include "tumble/scene/state.hpp"

namespace tumble::detail {

/// Throws std::invalid_argument, its message starting with `who`, when s does not fit `scene`.
template <class SceneT>
void check_scene_state(const SceneT& scene, const SceneState& s, const std::string& who) {
  if (s.y.size() != scene.size() || static_cast<int>(s.base.size()) != scene.body_count()) {
    throw std::invalid_argument(
        who + ": the state has " + std::to_string(s.y.size()) + " entries and " +
        std::to_string(s.base.size()) + " chart bases, but the scene has size " +
        std::to_string(scene.size()) + " and " + std::to_string(scene.body_count()) + " bodies");
  }
  for (const auto& b : s.base) {
    if (!b.allFinite() ||
        (b.transpose() * b - Matrix3<double>::Identity()).cwiseAbs().maxCoeff() > 1e-9 ||
        b.determinant() < 0) {
      throw std::invalid_argument(who + ": a chart base of the state is not a proper rotation");
    }
  }
}

}  // namespace tumble::detail
