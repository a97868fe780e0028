#pragma once
// What the scene and integration tests share: the tumbling body of the physics tests (I =
// diag(1, 2, 3) kg m^2, omega0 = (0.1, 2, 0.05) rad/s: close to the separatrix, so it flips), an
// axis-angle rotation, and SceneIntegrator options for a method and a tolerance.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "tumble/body/mass_properties.hpp"
#include "tumble/integrate/scene_integrator.hpp"

namespace tumble::test {

inline const Eigen::Vector3d kTumblingInertia(1.0, 2.0, 3.0);
inline const Eigen::Vector3d kTumblingOmega(0.1, 2.0, 0.05);

/// Unit mass, inertia kTumblingInertia about the centroid (principal axes = body axes).
inline MassProperties<double> tumbling_mass() {
  return MassProperties<double>::about_centroid(1.0, kTumblingInertia.asDiagonal());
}

/// The rotation by `angle` (rad) about `axis` (normalized here).
inline Eigen::Matrix3d rot(double angle, const Eigen::Vector3d& axis) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

/// CVODE's method at rtol = atol = tol; `max_steps` bounds the steps of one advance() call (a
/// test that goes wrong then fails instead of running on).
inline SceneIntegratorOptions integrator_options(CvodeMethod method, double tol,
                                                 long max_steps = 1000000) {
  SceneIntegratorOptions o;
  o.method = method;
  o.rtol = tol;
  o.atol = tol;
  o.max_steps = max_steps;
  return o;
}

/// Bound on the global error of an attitude or angular-velocity history after `steps` steps at
/// tolerance `tol` over [0, t_end], for a motion turning at `rate` rad/s. Each step commits a
/// local error of about tol (CVODE's weighted norm); a rate error committed at time t shifts the
/// phase of the motion by rate x (t_end - t) times as much by t_end (torque-free motion is
/// neutrally stable: errors grow linearly, not exponentially), so the sum over the steps is below
/// tol x steps x (1 + rate x t_end). The factor 5 is the margin over the worst case measured
/// (nearly symmetric and thin bodies, Gibbs through 180 deg: about 1.5 of the model; GCC 12,
/// Clang 14, SUNDIALS 6.4); most runs stay far below it.
inline double global_error_bound(double tol, long steps, double rate, double t_end) {
  return 5.0 * tol * static_cast<double>(steps) * (1.0 + rate * t_end);
}

inline const char* method_name(CvodeMethod m) { return m == CvodeMethod::adams ? "Adams" : "BDF"; }

}  // namespace tumble::test
