#pragma once
// Sample attitudes for the tests of the vector charts (Gibbs, MRP, rotation vector), whose
// coordinates are x = f(phi) n for the rotation angle phi and the unit axis n.

#include <cstdint>
#include <initializer_list>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "support/random.hpp"

namespace tumble::test {

/// A sample attitude: the coordinates built from (phi, n) by the chart's definition
/// (Definition::magnitude(phi) = f(phi)) and rounded to S; phi and n are then recomputed from the
/// rounded coordinates in long double (Definition::angle(|x|) = phi), so that the references
/// describe exactly the coordinates under test.
template <class S, class Definition> struct AxisAngleSample {
  using Vector3ld = Eigen::Matrix<long double, 3, 1>;
  Eigen::Matrix<S, 3, 1> coords;
  long double phi;
  Vector3ld n;
  AxisAngleSample(long double phi0, const Vector3ld& n0) {
    coords = (Definition::magnitude(phi0) * n0.normalized()).template cast<S>();
    const Vector3ld xl = coords.template cast<long double>();
    phi = Definition::angle(xl.norm());
    n = xl.norm() > 0 ? Vector3ld(xl.normalized()) : Vector3ld::UnitX();
  }
  [[nodiscard]] Eigen::Matrix<long double, 3, 3> reference_rotation() const {
    return Eigen::AngleAxis<long double>(phi, n).toRotationMatrix();
  }
};

/// The fixed attitudes (phi, n), then `count` random ones with phi uniform in [0, phi_max) and a
/// Gaussian axis, drawn from Random(seed).
template <class Sample>
std::vector<Sample> axis_angle_samples(
    std::uint64_t seed,
    std::initializer_list<std::pair<long double, Eigen::Matrix<long double, 3, 1>>> fixed,
    long double phi_max, int count) {
  tumble::test::Random rnd(seed);
  std::vector<Sample> out;
  for (const auto& [phi, n] : fixed) {
    out.emplace_back(phi, n);
  }
  for (int i = 0; i < count; ++i) {
    out.emplace_back(static_cast<long double>(rnd.uniform(0.0, static_cast<double>(phi_max))),
                     rnd.vector().cast<long double>());
  }
  return out;
}

}  // namespace tumble::test
