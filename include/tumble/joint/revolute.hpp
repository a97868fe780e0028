#pragma once
// A revolute joint (hinge): a point of body a and a point of body b coincide, and an axis fixed
// in a stays parallel to an axis fixed in b. 5 constraints; one rotation about the axis left.

#include "tumble/joint/concept.hpp"

namespace tumble {

class Revolute {
 public:
  static constexpr int size = 5;
  static constexpr const char* name = "Revolute";

  /// Points r_cp and unit axes in each body's components (inertial for the ground).
  Revolute(const Vector3<double>& point_a, const Vector3<double>& axis_a,
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
    detail::point_coincidence<0>(pa, fa_.point, pb, fb_.point, r);
    // z_b is perpendicular to x_a and y_a: parallel to z_a.
    detail::perpendicular<3>(pa, fa_.axes.col(0), pb, fb_.axes.col(2), r);
    detail::perpendicular<4>(pa, fa_.axes.col(1), pb, fb_.axes.col(2), r);
  }

  [[nodiscard]] const JointFrame& frame_a() const { return fa_; }
  [[nodiscard]] const JointFrame& frame_b() const { return fb_; }

 private:
  JointFrame fa_, fb_;
};

static_assert(JointElement<Revolute>);

}  // namespace tumble
