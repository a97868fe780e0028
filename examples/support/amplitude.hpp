#pragma once
// Jacobi's amplitude am(u | k^2), the closed forms' special function in the pendulum examples
// (pendulum.cpp, four_bar.cpp): the phi with F(phi | k^2) = u, F the incomplete elliptic integral
// of the first kind, which the standard library has (std::ellint_1, C++17). am(u + 2K) = am(u) + pi
// (K = F(pi/2 | k^2), std::comp_ellint_1) takes u to [-K, K], where phi lies in [-pi/2, pi/2] and
// F is odd and increasing, dF/dphi = 1 / sqrt(1 - k^2 sin^2 phi); there Newton's method, kept
// inside a bisection bracket, solves F(phi) = u to rounding. Jacobi's sn(u | k^2) = sin(am(u)).

#include <cmath>
#include <numbers>

namespace tumble_examples {

/// am(u | k^2) for the modulus 0 <= k < 1 (rad).
inline double jacobi_am(double u, double k) {
  constexpr double pi = std::numbers::pi;
  const double kk = std::comp_ellint_1(k);
  const double turns = std::round(u / (2 * kk));
  const double v = u - 2 * kk * turns;  // in [-K, K]
  double lo = -pi / 2, hi = pi / 2;
  double phi = v / kk * (pi / 2);  // F is nearly linear in phi: the first guess
  for (int i = 0; i < 60; ++i) {
    const double f = std::ellint_1(k, phi) - v;
    if (f == 0) {
      break;
    }
    (f > 0 ? hi : lo) = phi;
    const double s = std::sin(phi);
    double next = phi - f * std::sqrt(1 - k * k * s * s);
    if (!(next > lo && next < hi)) {
      next = 0.5 * (lo + hi);  // Newton left the bracket: bisect
    }
    const bool done = std::abs(next - phi) <= 1e-15;
    phi = next;
    if (done) {
      break;
    }
  }
  return turns * pi + phi;
}

}  // namespace tumble_examples
