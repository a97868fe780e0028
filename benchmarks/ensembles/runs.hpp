#pragma once
// tumble_bench, the ensemble study: its runs, shared by the section in tumble_bench
// (ensembles/ensemble.cpp: threads) and by tumble_bench_mpi (ensembles/mpi.cpp:
// MPI ranks), so that both time the same runs and can compare their results bitwise.
//
// The tumbling body of the work-precision sweep: principal inertia I = diag(1, 2, 3) kg m^2,
// framed at its centroid, no loads; MRP in the quasi-velocity form [r; sigma; v; omega] (12
// states, the size known at compile time: a std::array state, no heap in a step), integrated by
// OdeintIntegrator with Boost.Odeint's Fehlberg 7(8), rtol = atol = tol, from t = 0 to 50 s with
// one output time. Run i starts at rest attitude R = I with omega0 = (0.1, 2, 0.05) rad/s
// dispersed by up to 1 % per component (a formula of i: the same on every thread, rank and
// platform). A run keeps one double: the angle (rad) between its body x axis and the inertial
// x axis at 50 s.

#include <algorithm>
#include <cmath>
#include <cstddef>

#include <Eigen/Core>

#include "tumble/body/mass_properties.hpp"
#include "tumble/body/rigid_body.hpp"
#include "tumble/integrate/explicit_integrator.hpp"
#include "tumble/orientation/modified_rodrigues.hpp"
#include "tumble/scene/observables.hpp"
#include "tumble/scene/scene.hpp"

namespace tumble::bench::ensemble {

using Body = RigidBody<ModifiedRodriguesParameters>;
using TumblingScene = Scene<Bodies<Body>, Loads<>, StateForm::quasi_velocities>;
inline constexpr int kStates = 12;       ///< [r; sigma; v; omega]
inline constexpr double kEnd = 50.0;     ///< s, the one output time
inline constexpr double kSpread = 0.01;  ///< the largest relative dispersion of a component
inline const Eigen::Vector3d kInertia(1.0, 2.0, 3.0);  ///< kg m^2
inline const Eigen::Vector3d kOmega(0.1, 2.0, 0.05);   ///< rad/s, body components

/// The Fehlberg 7(8) pair at rtol = atol = tol.
inline OdeintOptions odeint_options(double tol) {
  OdeintOptions o;
  o.method = OdeintMethod::fehlberg78;
  o.rtol = tol;
  o.atol = tol;
  return o;
}

/// The integrator of a run (the ensemble's factory): one per thread, reset for each run.
struct MakeIntegrator {
  OdeintOptions options;
  OdeintIntegrator<TumblingScene, kStates> operator()(const TumblingScene& scene, double t0,
                                                      const SceneState& s0) const {
    return OdeintIntegrator<TumblingScene, kStates>(scene, t0, s0, options);
  }
};

/// The scene (built once, then only read) and the runs' initial states.
struct Tumbling {
  TumblingScene scene;
  BodyId<Body> body;

  Tumbling()
      : body(scene.add(Body(MassProperties<double>::about_centroid(
                           1.0, Eigen::Matrix3d(kInertia.asDiagonal()))),
                       {.omega = kOmega})) {}
  Tumbling(const Tumbling&) = delete;
  Tumbling& operator=(const Tumbling&) = delete;

  /// Run i's initial body rates: kOmega with each component scaled by 1 + kSpread d_k(i),
  /// |d_k| <= 1.
  static Eigen::Vector3d omega0(std::size_t i) {
    const double x = static_cast<double>(i);
    const Eigen::Vector3d d(std::sin(1.1 * x), std::cos(0.7 * x), std::sin(0.3 * x));
    return kOmega.cwiseProduct(Eigen::Vector3d::Ones() + kSpread * d);
  }
  /// The scene's initial state with body rates w (R = I, at rest in translation).
  [[nodiscard]] SceneState state_with(const Eigen::Vector3d& w) const {
    SceneState s = scene.initial_state();
    set_velocity(scene, body, s, Eigen::Vector3d::Zero(), w);
    return s;
  }
  /// Run i's initial state.
  [[nodiscard]] SceneState initial(std::size_t i) const { return state_with(omega0(i)); }
};

/// The observer of every run: keeps the angle (rad) between the body x axis and the inertial x
/// axis, acos(R_11), at the output time.
struct KeepAngle {
  const Tumbling* tumbling;
  void operator()(double& angle, std::size_t, double, const SceneState& s) const {
    const double c = rotation(tumbling->scene, tumbling->body, s)(0, 0);
    angle = std::acos(std::clamp(c, -1.0, 1.0));
  }
};

}  // namespace tumble::bench::ensemble
