#pragma once
// What force elements see of a body at one instant: its reference point's position and velocity,
// its rotation matrix (computed only when some load needs it), its angular velocity, and its mass
// properties. Reference chapter, Eqs. (1.1) and (1.4).

#include "tumble/body/mass_properties.hpp"
#include "tumble/core/types.hpp"

namespace tumble {

enum class ReferencePoint {
  centroid,  ///< the body frame sits at the centroid: m12 and f_v^r vanish (Eq. 1.33)
  offset,    ///< the body frame sits anywhere: the coupling terms are computed
  /// The body frame sits anywhere, and its origin c is held fixed in F (a top on its tip, a
  /// pendulum on its pivot): r_oc is constant, the coordinates are theta alone, the equations of
  /// motion are the theta-rows of Eq. (1.32) with rddot_oc = 0, and the r-rows give the reaction
  /// force at c.
  fixed_point,
};

/// The kinematic state of a body, whatever its reference point: what loads between two bodies
/// read.
template <class S> struct KinematicsView {
  const MassProperties<S>* mass_properties = nullptr;
  Vector3<S> position = Vector3<S>::Zero();      ///< r_oc, inertial components
  Vector3<S> velocity = Vector3<S>::Zero();      ///< rdot_oc, inertial components
  Matrix3<S> rotation = Matrix3<S>::Identity();  ///< R, body -> inertial (when loads need it)
  Vector3<S> omega = Vector3<S>::Zero();         ///< angular velocity, body components (Eq. 1.5)

  /// Eq. (1.1): r_op = r_oc + R r_cp.
  [[nodiscard]] Vector3<S> point_position(const Vector3<S>& r) const {
    return position + rotation * r;
  }
  /// Eq. (1.4): rdot_op = rdot_oc + R (omega x r_cp).
  [[nodiscard]] Vector3<S> point_velocity(const Vector3<S>& r) const {
    return velocity + rotation * omega.cross(r);
  }
};

/// The same, with the body's reference point known at compile time (what single-body loads
/// read, so that e.g. gravity on a centroidal body skips its moment).
template <class S, ReferencePoint Ref = ReferencePoint::centroid>
struct BodyKinematics : KinematicsView<S> {
  static constexpr ReferencePoint reference = Ref;
};

}  // namespace tumble
