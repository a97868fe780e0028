#pragma once
// The closed form of the pendulum released at rest: the angle from hanging straight down,
//   theta(t) = 2 asin(k sn(K(k) - w0 t | k^2)),   k = sin(theta0 / 2),
// w0^2 = g / l for the simple pendulum (IFToMM A01), m g d / I_o for a physical one, with sn
// Jacobi's elliptic function and K the complete elliptic integral of the first kind (modulus k).
// At t = 0, sn(K) = 1 and theta = theta0; the period is 4 K / w0. Valid for |theta0| < pi (the
// pendulum swings; it does not turn over). Shared by tests/joint (pendulum.test.cpp,
// iftomm.test.cpp) and tumble_bench's mechanism study (benchmarks/mechanisms/pendulum.cpp).

#include <cmath>

#include "support/elliptic.hpp"

namespace tumble::test {

/// The angle (rad) at time t of a pendulum released at rest from theta0, w0 = sqrt(g / l).
inline double pendulum_angle(double theta0, double w0, double t) {
  const double k = std::sin(0.5 * theta0);
  const double kk = std::comp_ellint_1(k);
  return 2.0 * std::asin(k * jacobi_sn_cn_dn(kk - w0 * t, k * k).sn);
}

}  // namespace tumble::test
