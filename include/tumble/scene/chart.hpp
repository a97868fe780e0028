#pragma once
// Charts of three-parameter sets and how a scene leaves one before it becomes singular.
//
// Every three-parameter set is singular somewhere (Euler angles at gimbal lock, Gibbs at 180 deg,
// MRP and the rotation vector at 360 deg). A scene never integrates through such a point: each
// body carries a constant chart base R0 and its attitude is R = R0 R(theta). When the distance to
// the nearest singularity (P::singularity_distance, in rad) falls below half its value at the
// chart's center, CVODE's root finding stops the integration there and the chart is re-centered:
//   R0' = R0 R(theta) R(theta_c)^T,  theta' = theta_c,  thetadot' = P::thetadot(theta_c, omega),
// with omega, and so the physics, unchanged (omega = G thetadot is the same in every chart since
// R0 is constant: R^T Rdot = R(theta)^T Rdot(theta)). MRP switch to their shadow set instead
// (same attitude, same chart base). Euler parameters have no singular attitude.
// The one rule "switch at half the center's distance" gives: Tait-Bryan angles at 45 deg from
// gimbal lock, proper Euler angles at 45 deg from theta2 in {0, pi}, Gibbs at phi = 90 deg, the
// rotation vector at phi = 180 deg and MRP at |sigma| = 1.

#include <numbers>

#include "tumble/core/types.hpp"
#include "tumble/orientation/concept.hpp"

namespace tumble {

template <Orientation P> struct Chart {
  using Coords = typename P::template Coords<double>;

  /// True when the set has singular attitudes, so the scene watches it.
  static constexpr bool has_singularity = !P::has_constraint;

  /// True for MRP: leave the chart through the shadow set.
  static constexpr bool uses_shadow_set = requires(const Coords& s) { P::shadow(s); };

  /// The coordinates farthest from any singularity: zero, except for proper Euler sequences,
  /// whose zero is itself singular (they provide chart_center()).
  static Coords center() {
    if constexpr (requires { P::template chart_center<double>(); }) {
      return P::template chart_center<double>();
    } else if constexpr (requires { P::is_tait_bryan; }) {
      // Euler angles: Tait-Bryan sequences are farthest from gimbal lock at theta2 = 0, proper
      // sequences (singular at theta2 = 0 and pi) at theta2 = pi/2.
      return Coords(0.0, P::is_tait_bryan ? 0.0 : std::numbers::pi / 2, 0.0);
    } else {
      return Coords::Zero();
    }
  }

  /// The distance to the singularity (rad) below which the scene leaves the chart.
  static double switch_distance() {
    if constexpr (has_singularity) {
      return 0.5 * P::singularity_distance(center());
    } else {
      return 0.0;
    }
  }
};

}  // namespace tumble
