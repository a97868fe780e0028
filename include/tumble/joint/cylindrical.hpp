#pragma once
// A cylindrical joint: body b's point stays on the line through body a's point along a's axis, and
// the axes stay parallel. 4 constraints; a rotation about and a translation along the axis left.

#include "tumble/joint/concept.hpp"

namespace tumble {

class Cylindrical {
 public:
  static constexpr int size = 4;
  static constexpr const char* name = "Cylindrical";

  /// Points r_cp and unit axes in each body's components (inertial for the ground).
  Cylindrical(const Vector3<double>& point_a, const Vector3<double>& axis_a,
              const Vector3<double>& point_b, const Vector3<double>& axis_b) {
    detail::check_joint_point(name, "point on body a", point_a);
    detail::check_joint_point(name, "point on body b", point_b);
    detail::check_joint_axis(name, "axis on body a", axis_a);
    detail::check_joint_axis(name, "axis on body b", axis_b);
    fa_ = detail::frame_from_axis(point_a, axis_a);
    fb_ = detail::frame_from_axis(point_b, axis_b);
  }

  template <class S>
  void evaluate(const KinematicsView<S>& a, const KinematicsView<S>& b,
                ConstraintRows<S, size>& r) const {
    const detail::JointSide<S> pa(a, fa_.point), pb(b, fb_.point);
    detail::perpendicular<0>(pa, fa_.axes.col(0), pb, fb_.axes.col(2), r);
    detail::perpendicular<1>(pa, fa_.axes.col(1), pb, fb_.axes.col(2), r);
    detail::offset_perpendicular<2>(pa, fa_.axes.col(0), pb, r);
    detail::offset_perpendicular<3>(pa, fa_.axes.col(1), pb, r);
  }

 private:
  JointFrame fa_, fb_;
};

static_assert(JointElement<Cylindrical>);

}  // namespace tumble
