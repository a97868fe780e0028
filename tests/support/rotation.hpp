#pragma once
// The rotation that turns one direction onto another, for tests that set up an attitude so.

#include <cmath>
#include <stdexcept>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace tumble::test {

/// The rotation that turns the direction of a onto that of b, about a x b: the arithmetic of
/// Eigen's Quaternion::FromTwoVectors for directions that are not opposite, so the same doubles,
/// without its branch for opposite ones, whose SVD cost every source that used it about 7 s of
/// GCC's time (-O1).
inline Eigen::Matrix3d rotation_onto(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d v0 = a.normalized(), v1 = b.normalized();
  const double c = v1.dot(v0);
  if (c < -1.0 + Eigen::NumTraits<double>::dummy_precision()) {
    throw std::invalid_argument("rotation_onto: opposite directions");
  }
  const double s = std::sqrt((1.0 + c) * 2.0);
  Eigen::Quaterniond q;
  q.vec() = v0.cross(v1) * (1.0 / s);
  q.w() = s * 0.5;
  return q.toRotationMatrix();
}

}  // namespace tumble::test
