#pragma once
// The numerics OdeintIntegrator (explicit_integrator.hpp) wraps around Odeint's steppers, each a
// function of a right-hand side and vectors only: the initial step size, the root of an event
// function on a step, and the largest eigenvalue modulus of the Jacobian (the stiffness test).

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

#include <Eigen/Core>

namespace tumble::detail {

/// The initial step for a method of order p at (t, y) with y' = f0 (Hairer, Norsett and Wanner,
/// Solving ODEs I, Sec. II.4: one Euler step of size h0, then the second derivative from it).
/// f(y1, f1) evaluates the right-hand side at y1 into f1 and may throw; y1 and f1 are scratch.
/// atol: one value, or a vector of one per entry. Returns h0 when the trial point cannot be
/// evaluated.
template <class F, class V, class W, class A>
double initial_step(F&& f, const V& y, const V& f0, W& y1, W& f1, const A& atol, double rtol,
                    double order, double max_step) {
  const auto scale = [&] {
    if constexpr (std::is_arithmetic_v<A>) {
      return (atol + rtol * y.array().abs()).eval();
    } else {
      return (atol.array() + rtol * y.array().abs()).eval();
    }
  }();
  const double d0 = std::sqrt((y.array() / scale).square().mean());
  const double d1 = std::sqrt((f0.array() / scale).square().mean());
  double h0 = (d0 < 1e-5 || d1 < 1e-5) ? 1e-6 : 0.01 * d0 / d1;
  h0 = std::min(h0, max_step);
  y1 = y + h0 * f0;
  if (!f(y1, f1)) {
    return h0;
  }
  const double d2 = std::sqrt(((f1 - f0).array() / scale).square().mean()) / h0;
  const double dm = std::max(d1, d2);
  const double h1 =
      dm <= 1e-15 ? std::max(1e-6, 1e-3 * h0) : std::pow(0.01 / dm, 1.0 / (order + 1));
  return std::min({100.0 * h0, h1, max_step});
}

/// A root of g on [a, b], where g(a) = ga and g(b) = gb have opposite signs, by the Illinois
/// method (modified regula falsi; bisection after 60 iterations or when the secant leaves the
/// bracket), to |b - a| <= tol: returns the end of the final bracket on b's side, where g has
/// the sign of gb (or is zero).
template <class G> double illinois(G&& g, double a, double b, double ga, double gb, double tol) {
  int side = 0;
  for (int it = 0; it < 200 && b - a > tol; ++it) {
    double c = it < 60 ? (a * gb - b * ga) / (gb - ga) : 0.5 * (a + b);
    if (!(c > a && c < b)) {
      c = 0.5 * (a + b);
    }
    const double gc = g(c);
    if (gc == 0.0) {
      return c;
    }
    if ((gc > 0.0) == (gb > 0.0)) {
      b = c, gb = gc;
      if (side == 1) {
        ga *= 0.5;
      }
      side = 1;
    } else {
      a = c, ga = gc;
      if (side == -1) {
        gb *= 0.5;
      }
      side = -1;
    }
  }
  return b;
}

/// The largest eigenvalue modulus of df/dy at y (with f(y) = f0), by 30 steps of power
/// iteration on forward difference quotients. f(y1, f1) as for initial_step; v, y1 and f1 are
/// scratch of y's size. 0 when a trial point cannot be evaluated or the iteration degenerates.
template <class F, class V, class W>
double spectral_radius(F&& f, const V& y, const V& f0, W& v, W& y1, W& f1) {
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    v[i] = 1.0 + 0.1 * static_cast<double>(i % 7);  // no special direction
  }
  v.normalize();
  double rho = 0.0;
  const double scale = std::sqrt(std::numeric_limits<double>::epsilon()) * (1.0 + y.norm());
  for (int k = 0; k < 30; ++k) {
    y1 = y + scale * v;
    if (!f(y1, f1)) {
      return 0.0;
    }
    v = (f1 - f0) / scale;
    rho = v.norm();
    if (!(rho > 0.0) || !std::isfinite(rho)) {
      return 0.0;
    }
    v /= rho;
  }
  return rho;
}

}  // namespace tumble::detail
