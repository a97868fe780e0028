#pragma once
// The state of a scene: everything needed to restart an integration or to read an attitude.
//
// A scene (scene.hpp) is the model; a SceneState is one instant of it:
// - `y`, the continuous state the integrators advance: for each body in the order it was added,
//   one block whose layout is the scene's StateForm (below), with q = [r_oc; theta] (reference
//   chapter, Eq. 1.6) first in both forms:
//     StateForm::generalized       [q; qdot]       = [r_oc (3); theta (n); rdot_oc (3); thetadot
//     (n)] StateForm::quasi_velocities  [q; v; omega]   = [r_oc (3); theta (n); v (3); omega (3)]
//   with v = rdot_oc (inertial components) and omega the body's angular velocity in body
//   components (Eq. 1.5: omega = G thetadot). The rates start at offset + nq in both forms; a
//   body held at a fixed point (ReferencePoint::fixed_point) has no r_oc and no v: its block is
//   [theta; thetadot] or [theta; omega];
// - `base`, the discrete state: the chart base R0 of every body, one per body in the same order,
//   with the attitude R = R0 R(theta). A three-parameter body's base changes when its chart is
//   re-centered before a singularity (chart.hpp, charts.hpp); it is the identity for Euler
//   parameters and for a body whose chart was never re-centered.
// Both parts travel together: the same y read with another base is another attitude. A saved
// SceneState therefore restarts, and reads back, exactly the attitude it was saved at.

#include <span>
#include <vector>

#include <Eigen/Core>

#include "tumble/core/types.hpp"

namespace tumble {

/// The layout of a scene's continuous state, chosen at compile time (Scene's third parameter).
/// - quasi_velocities (the default): per body [q; v; omega]: the rates of the Newton-Euler
///   equations are integrated, and theta follows from the inverse kinematic map
///   thetadot = G^{-1} omega. Attitude errors then do not feed back into omega, which makes it
///   far more accurate per tolerance on a tumbling body, and neither thetaddot nor Gdot thetadot
///   is computed. Faster to a given accuracy than generalized on every problem of the work-
///   precision study, with either integrator (docs/choosing.md);
/// - generalized: per body [q; qdot], the reference chapter's form (Eq. 1.32 integrated as is).
enum class StateForm {
  generalized,      ///< [r_oc; theta; rdot_oc; thetadot] per body, size 2 nq
  quasi_velocities  ///< [r_oc; theta; v; omega] per body, size nq + 6 ([theta; omega] if fixed)
};

/// The chart bases of a scene's bodies, one per body (body id order).
using ChartBases = std::vector<Matrix3<double>>;

/// The physical initial state of one body (Scene::add).
struct InitialState {
  Vector3<double> position = Vector3<double>::Zero();      ///< r_oc, inertial, m
  Matrix3<double> rotation = Matrix3<double>::Identity();  ///< R, body -> inertial
  Vector3<double> velocity = Vector3<double>::Zero();      ///< rdot_oc, inertial, m/s
  Vector3<double> omega = Vector3<double>::Zero();         ///< angular velocity, body, rad/s
};

/// A read-only view of a scene's state: the continuous vector (in place, e.g. in an integrator's
/// memory) and the chart bases. What the observables (observables.hpp) and user event functions
/// read.
struct SceneStateView {
  Eigen::Map<const Eigen::VectorXd> y;
  std::span<const Matrix3<double>> base;

  SceneStateView(const double* data, Eigen::Index size, std::span<const Matrix3<double>> bases)
      : y(data, size), base(bases) {}
};

/// A scene's state, owned: the continuous vector y and the chart bases (one per body).
struct SceneState {
  Eigen::VectorXd y;
  ChartBases base;

  /// A view of this state (also an implicit conversion, so a SceneState goes wherever a view
  /// does).
  [[nodiscard]] SceneStateView view() const {
    return {y.data(), y.size(), std::span<const Matrix3<double>>(base)};
  }
  operator SceneStateView() const { return view(); }  // NOLINT(google-explicit-constructor)
};

}  // namespace tumble
