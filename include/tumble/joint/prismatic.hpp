#pragma once
// A prismatic joint (slider): body b translates along an axis fixed in body a and does not turn
// relative to it. 5 constraints; one translation along the axis left.

#include "tumble/joint/concept.hpp"

namespace tumble {

class Prismatic {
 public:
  static constexpr int size = 5;
  static constexpr const char* name = "Prismatic";

  /// A frame on each body (origin r_cp and axes in body components; inertial for the ground): the
  /// frames' z axes are the sliding axis, and their x axes stay parallel (the frames keep their
  /// relative orientation: give them aligned in the initial state).
  Prismatic(const JointFrame& frame_a, const JointFrame& frame_b) : fa_(frame_a), fb_(frame_b) {
    detail::check_joint_frame(name, "frame on body a", fa_);
    detail::check_joint_frame(name, "frame on body b", fb_);
  }

  template <class S>
  void evaluate(const KinematicsView<S>& a, const KinematicsView<S>& b,
                ConstraintRows<S, size>& r) const {
    const detail::JointSide<S> pa(a, fa_.point), pb(b, fb_.point);
    detail::perpendicular<0>(pa, fa_.axes.col(0), pb, fb_.axes.col(2), r);
    detail::perpendicular<1>(pa, fa_.axes.col(1), pb, fb_.axes.col(2), r);
    detail::offset_perpendicular<2>(pa, fa_.axes.col(0), pb, r);
    detail::offset_perpendicular<3>(pa, fa_.axes.col(1), pb, r);
    detail::perpendicular<4>(pa, fa_.axes.col(0), pb, fb_.axes.col(1), r);
  }

 private:
  JointFrame fa_, fb_;
};

static_assert(JointElement<Prismatic>);

}  // namespace tumble
