#pragma once
// A constant force at a body point, given in inertial or in body components (Eqs. 1.28-1.30).
// A body-fixed force (e.g. a thruster) turns with the body; an inertial one does not.

#include <stdexcept>

#include "tumble/core/math.hpp"
#include "tumble/force/concept.hpp"

namespace tumble {

enum class Components { inertial, body };

class PointForce {
 public:
  /// `point`: r_cp in body components; `force`: in `components`.
  PointForce(const Vector3<double>& point, const Vector3<double>& force,
             Components components = Components::inertial)
      : point_(point), force_(force), components_(components) {
    if (!detail::all_finite(point) || !detail::all_finite(force)) {
      throw std::invalid_argument("tumble::PointForce: the point or the force is not finite");
    }
  }

  static constexpr bool needs_rotation(ReferencePoint /*ref*/) { return true; }

  template <class S, ReferencePoint Ref>
  void apply(const S& /*t*/, const BodyKinematics<S, Ref>& k, Wrench<S>& w) const {
    if (components_ == Components::inertial) {
      w.add_force(k.rotation, detail::cast<S>(point_), detail::cast<S>(force_));
    } else {
      w.add_body_force(k.rotation, detail::cast<S>(point_), detail::cast<S>(force_));
    }
  }

 private:
  Vector3<double> point_;
  Vector3<double> force_;
  Components components_;
};

/// A constant moment, body components (Eq. 1.31). Needs no rotation matrix.
class BodyMoment {
 public:
  explicit BodyMoment(const Vector3<double>& moment) : moment_(moment) {
    if (!detail::all_finite(moment)) {
      throw std::invalid_argument("tumble::BodyMoment: the moment is not finite");
    }
  }
  static constexpr bool needs_rotation(ReferencePoint /*ref*/) { return false; }

  template <class S, ReferencePoint Ref>
  void apply(const S& /*t*/, const BodyKinematics<S, Ref>& /*k*/, Wrench<S>& w) const {
    w.add_moment(detail::cast<S>(moment_));
  }

 private:
  Vector3<double> moment_;
};

static_assert(ForceElement<PointForce>);
static_assert(ForceElement<BodyMoment>);

}  // namespace tumble
