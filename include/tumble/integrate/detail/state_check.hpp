#pragma once
// What both integrators check of a SceneState they are given (construction, reset): the sizes
// match the scene, every chart base is a proper rotation, and a mechanism's state is on its
// joints' constraints (to kJointStartTolerance; the projection after the first step removes what
// is left); for the explicit integrator also that the time and the state are finite (CVODE's core
// checks its own).

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "tumble/core/format.hpp"
#include "tumble/core/types.hpp"
#include "tumble/scene/assembly.hpp"
#include "tumble/scene/state.hpp"

namespace tumble::detail {

/// How far (relative to max(1 m, the largest |r_oc|), and in m/s or rad/s) a mechanism's initial
/// state may be from its constraints.
inline constexpr double kJointStartTolerance = 1e-6;

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
  if constexpr (SceneT::has_joints) {
    const ConstraintResidual r = constraint_residual(scene, s);
    double scale = 1.0;
    scene.for_each_entry([&](const auto& e) {
      if constexpr (!std::remove_cvref_t<decltype(e.body)>::fixed) {
        scale = std::max(scale, s.y.template segment<3>(e.offset).norm());
      }
    });
    if (!(r.position <= kJointStartTolerance * scale) ||
        !(r.velocity <= kJointStartTolerance * scale)) {
      std::ostringstream os;
      os.precision(6);
      os << who << ": the state is off the joints' constraints: " << describe_joint(scene, r.joint)
         << " has |C| = " << r.position << ", and max |J nu| = " << r.velocity
         << " (accepted: " << kJointStartTolerance
         << " relative); put the state on them with tumble::assemble(scene, state)";
      throw std::invalid_argument(os.str());
    }
  }
}

/// check_scene_state, and that the time t and every entry of s.y are finite.
template <class SceneT>
void check_scene_state_at(const SceneT& scene, const SceneState& s, double t,
                          const std::string& who) {
  if (!std::isfinite(t)) {
    throw std::invalid_argument(who + ": the time " + format_double(t) + " is not finite");
  }
  check_scene_state(scene, s, who);
  for (Eigen::Index i = 0; i < s.y.size(); ++i) {
    if (!std::isfinite(s.y[i])) {
      throw std::invalid_argument(who + ": the state is not finite: y[" + std::to_string(i) +
                                  "] = " + format_double(s.y[i]));
    }
  }
}

}  // namespace tumble::detail
