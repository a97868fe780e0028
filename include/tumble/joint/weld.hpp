#pragma once
// A weld (fixed joint): a frame on body a and a frame on body b coincide; no relative motion.
// 6 constraints: the origins coincide (3), and x_a . y_b = y_a . z_b = z_a . x_b = 0 (3), which
// with aligned frames has full rank (a relative rotation delta changes them by -delta_z,
// -delta_x, -delta_y).

#include "tumble/joint/concept.hpp"

namespace tumble {

class Weld {
 public:
  static constexpr int size = 6;
  static constexpr const char* name = "Weld";

  /// A frame on each body (origin r_cp and axes in body components; inertial for the ground),
  /// coincident in the initial state.
  Weld(const JointFrame& frame_a, const JointFrame& frame_b) : fa_(frame_a), fb_(frame_b) {
    detail::check_joint_frame(name, "frame on body a", fa_);
    detail::check_joint_frame(name, "frame on body b", fb_);
  }

  template <class S>
  void evaluate(const KinematicsView<S>& a, const KinematicsView<S>& b,
                ConstraintRows<S, size>& r) const {
    const detail::JointSide<S> pa(a, fa_.point), pb(b, fb_.point);
    detail::point_coincidence<0>(pa, fa_.point, pb, fb_.point, r);
    detail::perpendicular<3>(pa, fa_.axes.col(0), pb, fb_.axes.col(1), r);
    detail::perpendicular<4>(pa, fa_.axes.col(1), pb, fb_.axes.col(2), r);
    detail::perpendicular<5>(pa, fa_.axes.col(2), pb, fb_.axes.col(0), r);
  }

 private:
  JointFrame fa_, fb_;
};

static_assert(JointElement<Weld>);

}  // namespace tumble
