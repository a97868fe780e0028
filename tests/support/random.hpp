#pragma once
// Reproducible random inputs for the property suites: uniformly distributed rotations (unit
// quaternions from normalized 4D Gaussians), angular velocities, and positions.

#include <cstdint>
#include <random>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace tumble::test {

class Random {
 public:
  explicit Random(std::uint64_t seed = 20261121) : gen_(seed) {}

  double uniform(double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(gen_);
  }
  double normal() { return std::normal_distribution<double>(0.0, 1.0)(gen_); }

  Eigen::Vector3d vector(double scale = 1.0) {
    return scale * Eigen::Vector3d(normal(), normal(), normal());
  }
  /// A uniformly distributed unit quaternion (Haar measure on SO(3)).
  Eigen::Quaterniond quaternion() {
    Eigen::Vector4d v(normal(), normal(), normal(), normal());
    v.normalize();
    return Eigen::Quaterniond(v(0), v(1), v(2), v(3));
  }
  Eigen::Matrix3d rotation() { return quaternion().toRotationMatrix(); }

 private:
  std::mt19937_64 gen_;
};

/// The rotation angle between two rotation matrices (geodesic distance on SO(3)), in rad.
inline double rotation_angle_between(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  const Eigen::Matrix3d d = a.transpose() * b;
  const Eigen::Vector3d ax(d(2, 1) - d(1, 2), d(0, 2) - d(2, 0), d(1, 0) - d(0, 1));
  return std::atan2(0.5 * ax.norm(), 0.5 * (d.trace() - 1.0));
}

}  // namespace tumble::test
