#pragma once
// A spherical joint (ball and socket): a point of body a and a point of body b (or of the ground)
// coincide. 3 constraints; 3 rotational degrees of freedom left.

#include "tumble/joint/concept.hpp"

namespace tumble {

class Spherical {
 public:
  static constexpr int size = 3;
  static constexpr const char* name = "Spherical";

  /// point_a: r_cp on body a (body a components, from its reference point); point_b: the same
  /// point on body b (body b components), or inertial for the ground.
  Spherical(const Vector3<double>& point_a, const Vector3<double>& point_b)
      : sa_(point_a), sb_(point_b) {
    detail::check_joint_point(name, "point on body a", sa_);
    detail::check_joint_point(name, "point on body b", sb_);
  }

  template <class S>
  void evaluate(const KinematicsView<S>& a, const KinematicsView<S>& b,
                ConstraintRows<S, size>& r) const {
    const detail::JointSide<S> pa(a, sa_), pb(b, sb_);
    detail::point_coincidence<0>(pa, sa_, pb, sb_, r);
  }

  [[nodiscard]] const Vector3<double>& point_a() const { return sa_; }
  [[nodiscard]] const Vector3<double>& point_b() const { return sb_; }

 private:
  Vector3<double> sa_, sb_;
};

static_assert(JointElement<Spherical>);

}  // namespace tumble
