#pragma once
// A distance constraint (massless rod with spherical ends): a point of body a and a point of body
// b stay at the distance L > 0. 1 constraint.

#include <string>

#include "tumble/joint/concept.hpp"

namespace tumble {

class Distance {
 public:
  static constexpr int size = 1;
  static constexpr const char* name = "Distance";

  /// Points r_cp in each body's components (inertial for the ground) and the length L, m (> 0:
  /// coincident points are a spherical joint).
  Distance(const Vector3<double>& point_a, const Vector3<double>& point_b, double length)
      : sa_(point_a), sb_(point_b), length_(length) {
    detail::check_joint_point(name, "point on body a", sa_);
    detail::check_joint_point(name, "point on body b", sb_);
    if (!(std::isfinite(length) && length > 0.0)) {
      throw std::invalid_argument("tumble::Distance: the length must be finite and > 0 (got " +
                                  std::to_string(length) +
                                  "); coincident points are a Spherical joint");
    }
  }

  template <class S>
  void evaluate(const KinematicsView<S>& a, const KinematicsView<S>& b,
                ConstraintRows<S, size>& r) const {
    const detail::JointSide<S> pa(a, sa_), pb(b, sb_);
    detail::distance<0>(pa, sa_, pb, sb_, length_, r);
  }

  [[nodiscard]] double length() const { return length_; }

 private:
  Vector3<double> sa_, sb_;
  double length_;
};

static_assert(JointElement<Distance>);

}  // namespace tumble
