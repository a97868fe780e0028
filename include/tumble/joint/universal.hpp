#pragma once
// A universal (Cardan, Hooke) joint: a point of body a and a point of body b coincide, and the
// cross's two arms, one fixed in a and one fixed in b, stay perpendicular. 4 constraints; two
// rotations left (about each arm).

#include "tumble/joint/concept.hpp"

namespace tumble {

class Universal {
 public:
  static constexpr int size = 4;
  static constexpr const char* name = "Universal";

  /// Points r_cp and the arms' unit axes in each body's components (inertial for the ground).
  /// The arms must be perpendicular in the initial state (the constraint keeps them so).
  Universal(const Vector3<double>& point_a, const Vector3<double>& axis_a,
            const Vector3<double>& point_b, const Vector3<double>& axis_b)
      : sa_(point_a), sb_(point_b), xa_(axis_a), yb_(axis_b) {
    detail::check_joint_point(name, "point on body a", sa_);
    detail::check_joint_point(name, "point on body b", sb_);
    detail::check_joint_axis(name, "axis on body a", xa_);
    detail::check_joint_axis(name, "axis on body b", yb_);
  }

  template <class S>
  void evaluate(const KinematicsView<S>& a, const KinematicsView<S>& b,
                ConstraintRows<S, size>& r) const {
    const detail::JointSide<S> pa(a, sa_), pb(b, sb_);
    detail::point_coincidence<0>(pa, sa_, pb, sb_, r);
    detail::perpendicular<3>(pa, xa_, pb, yb_, r);
  }

 private:
  Vector3<double> sa_, sb_, xa_, yb_;
};

static_assert(JointElement<Universal>);

}  // namespace tumble
