#pragma once
// The resultant of the loads on one body, reduced to its reference point c.
//
// Reference chapter, Eqs. (1.28)-(1.31): a force F (inertial components) at a body point p adds
// F to the force and S(r_cp) F^f = r_cp x (R^T F) to the moment about c (body components); the
// generalized force is then Q = [F; G^T M_c] (Eq. 1.31). Force elements accumulate into a Wrench,
// and the body multiplies by G^T only when a generalized force is asked for: the accelerations use
// the wrench directly.

#include "tumble/core/types.hpp"

namespace tumble {

template <class S = double> struct Wrench {
  Vector3<S> force = Vector3<S>::Zero();   ///< resultant force, inertial components
  Vector3<S> moment = Vector3<S>::Zero();  ///< resultant moment about c, body components

  /// A force with inertial components `f` at the body point `r` (body components, relative to c).
  void add_force(const Matrix3<S>& rotation, const Vector3<S>& r, const Vector3<S>& f) {
    force += f;
    moment += r.cross(rotation.transpose() * f);  // Eq. (1.30): M_c = S(r) F^f
  }
  /// A force with body components `f` at the body point `r`.
  void add_body_force(const Matrix3<S>& rotation, const Vector3<S>& r, const Vector3<S>& f) {
    force += rotation * f;
    moment += r.cross(f);
  }
  /// A force with inertial components through the reference point c: no moment, no R needed.
  void add_force_at_reference(const Vector3<S>& f) { force += f; }
  /// A moment with body components.
  void add_moment(const Vector3<S>& m) { moment += m; }

  Wrench& operator+=(const Wrench& o) {
    force += o.force;
    moment += o.moment;
    return *this;
  }
};

/// No wrench at all, known at compile time: what a body of a scene without loads feels. The
/// rates leave the wrench's terms out (RigidBody::velocity_rates_into), which the compiler may not
/// do for a zero Wrench: 0 * x is not 0 when x is infinite.
struct NoWrench {};

}  // namespace tumble
