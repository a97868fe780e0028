#pragma once
// Independent derivatives for the property suites: central finite differences in long double
// with Richardson extrapolation, and forward-mode AD (Eigen's AutoDiffScalar) along one direction.
//
// Richardson. The central difference D(h) = (f(h) - f(-h)) / (2h) is an even function of h,
// D(h) = f'(0) + c1 h^2 + c2 h^4 + ..., so Neville's scheme on h0, h0/2, ..., h0/2^(n-1) removes
// the terms up to h^(2n-2) (T[i][j] = T[i][j-1] + (T[i][j-1] - T[i-1][j-1]) / (4^j - 1)); the
// leading remainder is c_n h0^2 (h0/2)^2 ... (h0/2^(n-1))^2 = c_n h0^(2n) 2^-(n(n-1)).
// How small h0 must be depends on f. Measured on R(theta + t thetadot) with h0 = L / 8, L the
// length on which R varies along thetadot (1 / |thetadot| for the trigonometric charts, the
// distance sqrt(1 + |theta|^2) / |thetadot| to the complex poles of the rational ones): five
// levels leave ~1e-16 |f'| for Euler angles but up to ~1e-13 |f'| for the Gibbs vector and MRP
// (a pole at distance 8 h0 makes the remainder decay only like 8^-2n); six levels leave
// < 0.15 eps_double |f'| for all of them. So the default is six levels and callers use L / 8.
// Rounding: f is evaluated in long double (eps_ld = 1.1e-19 on x86-64) to a few ulps, the
// smallest step h0 / 32 turns that into 32 eps_ld |f| / h0, and the extrapolation weights sum to
// < 3: ~100 eps_ld |f| / h0 = 9e-17 |f| / L for h0 = L / 8, below double's epsilon.
// `error` is that rounding bound plus the size of the last correction |T[n-1][n-1] - T[n-1][n-2]|
// (which estimates the truncation and shows any larger noise of f), so callers can check that the
// difference is sharp enough for what they test. Where f varies on a long scale but its
// derivative is tiny relative to f (a chart near its singularity, R ~ I + O(1/|theta|^2)),
// `error` grows accordingly and the AD derivative is the sharp reference.

#include <cmath>
#include <limits>
#include <type_traits>
#include <utility>

#include <Eigen/Core>
#include <unsupported/Eigen/AutoDiff>

namespace tumble::test {

/// A derivative and a bound on its error (max-abs over the entries).
template <class M> struct FdDerivative {
  M value;
  long double error;
};

namespace detail_fd {
template <class M> long double max_abs(const M& m) {
  if constexpr (std::is_arithmetic_v<M>) {
    return std::fabs(static_cast<long double>(m));
  } else {
    return m.cwiseAbs().maxCoeff();
  }
}
}  // namespace detail_fd

namespace detail_fd {
/// Neville's scheme on the even difference quotient q(h) at h0, h0/2, ...: the value and the size
/// of the last correction.
template <class Q> auto neville(Q&& q, long double h0, int levels) {
  using M = std::decay_t<decltype(q(1.0L))>;
  constexpr int kMax = 8;
  levels = levels > kMax ? kMax : (levels < 2 ? 2 : levels);
  M t[kMax][kMax];
  long double h = h0;
  for (int i = 0; i < levels; ++i, h /= 2) {
    t[i][0] = q(h);
    long double factor = 1;
    for (int j = 1; j <= i; ++j) {
      factor *= 4;
      t[i][j] = t[i][j - 1] + (t[i][j - 1] - t[i - 1][j - 1]) / (factor - 1);
    }
  }
  const int n = levels - 1;
  return std::pair<M, long double>(t[n][n], max_abs(M(t[n][n] - t[n][n - 1])));
}
}  // namespace detail_fd

/// d/dt f(t) at t = 0, f: long double -> long double or a fixed-size Eigen matrix of long double.
/// h0: the first step (about 1/8 of the length on which f varies); levels: Richardson levels.
template <class F> auto richardson_derivative(F&& f, long double h0, int levels = 6) {
  using M = std::decay_t<decltype(f(0.0L))>;
  long double f_scale = detail_fd::max_abs(f(0.0L));
  const auto q = [&](long double h) {
    const M fp = f(h);
    const M fm = f(-h);
    f_scale = std::fmax(f_scale, std::fmax(detail_fd::max_abs(fp), detail_fd::max_abs(fm)));
    return M((fp - fm) / (2 * h));
  };
  const auto [value, correction] = detail_fd::neville(q, h0, levels);
  const long double eps_ld = std::numeric_limits<long double>::epsilon();
  const long double h_min = std::ldexp(h0, -(levels - 1));
  return FdDerivative<M>{value, correction + 3 * eps_ld * f_scale / h_min};
}

/// d^2/dt^2 f(t) at t = 0 from the second difference (f(h) - 2 f(0) + f(-h)) / h^2, also even
/// in h, with the same extrapolation; its rounding part is 3 * 4 eps_ld |f| / h_min^2.
template <class F> auto richardson_second_derivative(F&& f, long double h0, int levels = 6) {
  using M = std::decay_t<decltype(f(0.0L))>;
  const M f0 = f(0.0L);
  long double f_scale = detail_fd::max_abs(f0);
  const auto q = [&](long double h) {
    const M fp = f(h);
    const M fm = f(-h);
    f_scale = std::fmax(f_scale, std::fmax(detail_fd::max_abs(fp), detail_fd::max_abs(fm)));
    return M((fp - 2 * f0 + fm) / (h * h));
  };
  const auto [value, correction] = detail_fd::neville(q, h0, levels);
  const long double eps_ld = std::numeric_limits<long double>::epsilon();
  const long double h_min = std::ldexp(h0, -(levels - 1));
  return FdDerivative<M>{value, correction + 12 * eps_ld * f_scale / (h_min * h_min)};
}

/// Five-point central difference of f(t) at t = 0 in long double: truncation ~h^4 |f^(5)| / 30
/// (~3e-18 |f^(5)| for h = 1e-4), rounding ~eps_ld |f| / h ~ 1e-15 |f|. For smooth, moderate
/// inputs, where the extrapolation above is not needed.
template <class F> auto five_point_derivative(F f, long double h = 1e-4L) {
  using R = decltype(f(h));
  return R((f(-2 * h) - f(2 * h) + 8 * (f(h) - f(-h))) / (12 * h));
}
/// Bound for five_point_derivative on the smooth, moderate inputs of the chart tests.
inline constexpr long double kFivePointTol = 1e-11L;

/// Forward-mode AD scalar with a dynamic derivative vector.
using ADScalar = Eigen::AutoDiffScalar<Eigen::VectorXd>;

/// x(i) as AD variables with the derivative direction d(i). The derivative vectors get two
/// components, the second always zero: with one (8 bytes), GCC 12 at -O2 flags Eigen's packet
/// copy of the derivative vector with a false -Warray-bounds (a 16-byte load from an 8-byte
/// allocation, in a loop that never runs for size 1).
template <class DX, class DD>
Eigen::Matrix<ADScalar, DX::RowsAtCompileTime, 1> ad_seed(const Eigen::MatrixBase<DX>& x,
                                                          const Eigen::MatrixBase<DD>& d) {
  Eigen::Matrix<ADScalar, DX::RowsAtCompileTime, 1> out(x.size());
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    Eigen::VectorXd der = Eigen::VectorXd::Zero(2);
    der(0) = static_cast<double>(d(i));
    out(i) = ADScalar(static_cast<double>(x(i)), der);
  }
  return out;
}

/// x(i) as AD constants: zero derivative vectors of the size ad_seed gives (Eigen's AutoDiff
/// resizes an empty derivative vector to its partner's only in simple binary operations).
template <class DX>
Eigen::Matrix<ADScalar, DX::RowsAtCompileTime, 1> ad_constant(const Eigen::MatrixBase<DX>& x) {
  return ad_seed(x, DX::Zero(x.size()));
}

/// The one-entry derivative vector (dx). Not inlined: when GCC 12 sees the 8-byte allocation and
/// Eigen's 16-byte packet copy of the same vector in one function, it reports a false
/// -Warray-bounds (the packet path is dead for size 1).
[[gnu::noinline]] inline Eigen::VectorXd direction(double dx) {
  return Eigen::VectorXd::Constant(1, dx);
}

/// x + t dx with one derivative direction t: its derivative is dx.
template <int N>
Eigen::Matrix<ADScalar, N, 1> along(const Eigen::Matrix<double, N, 1>& x,
                                    const Eigen::Matrix<double, N, 1>& dx) {
  Eigen::Matrix<ADScalar, N, 1> r;
  for (int i = 0; i < N; ++i) {
    r(i) = ADScalar(x(i), direction(dx(i)));
  }
  return r;
}

/// The first derivative component of an AD scalar (0 when it carries none: a constant).
inline double ad_derivative(const ADScalar& x) {
  return x.derivatives().size() > 0 ? x.derivatives()(0) : 0.0;
}

/// Values and first derivative components of a matrix of AD scalars, in double.
template <class D> auto ad_values(const Eigen::MatrixBase<D>& m) {
  return m.unaryExpr([](const ADScalar& x) { return x.value(); }).eval();
}
template <class D> auto ad_derivatives(const Eigen::MatrixBase<D>& m) {
  return m.unaryExpr([](const ADScalar& x) { return ad_derivative(x); }).eval();
}

}  // namespace tumble::test
