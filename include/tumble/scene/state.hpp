#pragma once
// The state of a scene: everything needed to restart an integration or to read an attitude.
//
// A scene (scene.hpp) is the model; a SceneState is one instant of it:
// - `y`, the continuous state the integrators advance: for each body in the order it was added,
//   [q; qdot] with q = [r_oc; theta] (reference chapter, Eq. 1.6);
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
