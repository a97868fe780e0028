// Consumer check for tumble::tumble: builds against the installed (or add_subdirectory'd) package
// and checks EulerParameters against closed forms that do not use tumble: the rotation matrix
// against Eigen::AngleAxis, the round trip through from_rotation, and omega = G(p) pdot (Eq. 1.5).
// Exit status 0 when every check holds.

#include <cmath>
#include <cstdio>

#include <Eigen/Geometry>

#include "tumble/orientation/euler_parameters.hpp"

namespace {

bool check(const char* what, double error, double tolerance) {
  const bool ok = error <= tolerance;
  std::printf("%-44s error %.3e  (tolerance %.1e)  %s\n", what, error, tolerance,
              ok ? "ok" : "FAILED");
  return ok;
}

}  // namespace

int main() {
  using tumble::EulerParameters;
  const double pi = std::acos(-1.0);
  const double phi = 2.0 * pi / 3.0;
  const Eigen::Vector3d n = Eigen::Vector3d(1.0, 2.0, 2.0) / 3.0;  // unit axis

  // p = (cos(phi/2), n sin(phi/2)) for a rotation by phi about n.
  Eigen::Vector4d p;
  p << std::cos(phi / 2), n * std::sin(phi / 2);

  const Eigen::Matrix3d r = EulerParameters::rotation(p);
  const Eigen::Matrix3d r_expected = Eigen::AngleAxisd(phi, n).toRotationMatrix();

  const Eigen::Vector4d p_back = EulerParameters::from_rotation(r);

  const Eigen::Vector3d omega(0.3, -1.2, 2.5);  // body angular velocity, rad/s
  const Eigen::Vector4d pdot = EulerParameters::thetadot(p, omega);

  bool ok = true;
  ok &= check("R(p) against AngleAxis", (r - r_expected).norm(), 1e-14);
  ok &= check("from_rotation(R(p)) against p", (p_back - p).norm(), 1e-14);
  ok &= check("G(p) pdot against omega", (EulerParameters::G(p) * pdot - omega).norm(), 1e-14);
  ok &= check("p . pdot (tangent to |p| = 1)", std::abs(p.dot(pdot)), 1e-14);
  std::printf("%s\n", ok ? "consumer_core: all checks passed" : "consumer_core: FAILED");
  return ok ? 0 : 1;
}
