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
  o.cvode.method = method;
  o.cvode.rtol = tol;
  o.cvode.atol = tol;
  o.cvode.max_steps_per_call = max_steps;
  return o;
}

inline const char* method_name(CvodeMethod m) {
  return m == CvodeMethod::adams ? "Adams" : "BDF";
}

}  // namespace tumble::test
