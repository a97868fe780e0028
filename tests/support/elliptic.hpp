#pragma once
// Jacobi's elliptic functions sn, cn, dn, the complete and incomplete elliptic integrals of the
// first kind, and adaptive Gauss-Legendre quadrature, all in long double: the special functions
// of the test support's closed forms (torque_free.hpp, the torque-free rigid body; pendulum.hpp,
// the pendulum). Self-contained (Eigen-free, std only), so that the benchmarks share them.
//
// Sources.
//  - Jacobi elliptic functions sn, cn, dn from the arithmetic-geometric mean (AGM) / descending
//    Landen (Gauss) transformation: Abramowitz & Stegun, Handbook of Mathematical Functions
//    (1964), 16.4 (the amplitude recursion 16.4.3), and its algebraic form by R. Bulirsch,
//    "Numerical calculation of elliptic integrals and elliptic functions", Numer. Math. 7 (1965)
//    78-90 (procedure sncndn), which jacobi_sn_cn_dn uses because it is about five times faster.
//  - Complete elliptic integral K(m) = pi / (2 AGM(1, sqrt(1 - m))): A&S 17.6.
//  - Incomplete integral F(phi | m) = sin(phi) R_F(cos^2 phi, 1 - m sin^2 phi, 1) with Carlson's
//    duplication algorithm for R_F: B. C. Carlson, "Numerical computation of real or complex
//    elliptic integrals", Numerical Algorithms 10 (1995) 13-26 (also DLMF 19.25.5, 19.36.1).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <type_traits>
#include <utility>

namespace tumble::test {

// ==== Elliptic functions ======================================================================

template <class T> struct JacobiSnCnDn {
  T sn;
  T cn;
  T dn;
};

namespace detail_elliptic {
constexpr int kMaxAgmSteps = 64;

/// The AGM sequences of A&S 16.4.2 from a0 = 1, b0 = sqrt(m1), c0 = sqrt(m), up to the first
/// index n with c_n <= eps a_n; c_{n+1} is computed as c_n^2 / (4 a_{n+1}) (= (a_n - b_n) / 2,
/// without the cancellation).
struct Agm {
  std::array<long double, kMaxAgmSteps + 1> a{}, b{}, c{};
  int n = 0;
};

inline Agm agm(long double m, long double m1) {
  const long double eps = std::numeric_limits<long double>::epsilon();
  Agm s;
  s.a[0] = 1.0L;
  s.b[0] = std::sqrt(m1);
  s.c[0] = std::sqrt(m);
  int n = 0;
  while (s.c[n] > eps * s.a[n] && n < kMaxAgmSteps) {
    s.a[n + 1] = 0.5L * (s.a[n] + s.b[n]);
    s.b[n + 1] = std::sqrt(s.a[n] * s.b[n]);
    s.c[n + 1] = s.c[n] * s.c[n] / (4.0L * s.a[n + 1]);
    ++n;
  }
  s.n = n;
  return s;
}

inline void check_parameter(long double m, long double m1) {
  if (!(m >= 0.0L && m1 >= 0.0L && m <= 1.0L && m1 <= 1.0L)) {
    throw std::domain_error("elliptic functions: the parameter m must lie in [0, 1]");
  }
}
}  // namespace detail_elliptic

/// K(m) = pi / (2 AGM(1, sqrt(m1))), m1 = 1 - m given separately so that m -> 1 keeps its
/// accuracy (A&S 17.6). K(0) = pi/2; K(1) = +inf.
inline long double elliptic_k(long double m, long double m1) {
  detail_elliptic::check_parameter(m, m1);
  if (m1 == 0.0L) return std::numeric_limits<long double>::infinity();
  const detail_elliptic::Agm s = detail_elliptic::agm(m, m1);
  return std::numbers::pi_v<long double> / (2.0L * s.a[s.n]);
}

/// K(m) for float, double or long double; computed in long double.
template <class T> T elliptic_k(T m) {
  static_assert(std::is_floating_point_v<T>);
  const long double ml = m;
  return static_cast<T>(elliptic_k(ml, 1.0L - ml));
}

/// sn(u|m), cn(u|m), dn(u|m) for one parameter m (m1 = 1 - m given separately), with the AGM
/// sequences of A&S 16.4.2 computed once. Two evaluations from the same sequences:
/// operator() (Bulirsch's algebraic form of the descending Gauss transformation: R. Bulirsch,
/// "Numerical calculation of elliptic integrals and elliptic functions", Numer. Math. 7 (1965)
/// 78-90, procedure sncndn) is the fast one that TorqueFreeBody uses; by_amplitude() (the
/// amplitude recursion of A&S 16.4.3) is the textbook one; the tests check them against each
/// other and against mpmath.
class JacobiElliptic {
 public:
  JacobiElliptic(long double m, long double m1) : m_(m), m1_(m1) {
    detail_elliptic::check_parameter(m, m1);
    if (m1 == 0.0L) {
      k_ = std::numeric_limits<long double>::infinity();
    } else {
      agm_ = detail_elliptic::agm(m, m1);
      k_ = std::numbers::pi_v<long double> / (2.0L * agm_.a[agm_.n]);
    }
  }
  /// K(m).
  [[nodiscard]] long double k() const { return k_; }

  /// sn, cn, dn by Bulirsch's algebraic form of the descending Gauss transformation: one sine and
  /// one cosine, then divisions only (about five times faster than by_amplitude()).
  [[nodiscard]] JacobiSnCnDn<long double> operator()(long double u) const {
    if (m_ == 0.0L) return {std::sin(u), std::cos(u), 1.0L};
    if (m1_ == 0.0L) return sech_tanh(u);
    const detail_elliptic::Agm& s = agm_;
    const int n = s.n;
    const long double v = u * s.a[n];
    const long double sv = std::sin(v), cv = std::cos(v);
    if (sv == 0.0L) return {0.0L, cv < 0.0L ? -1.0L : 1.0L, 1.0L};
    // c -> cn/sn and dn through the levels n, ..., 1 (every quantity keeps its sign: no
    // cancellation).
    long double a = cv / sv;
    long double c = s.a[n] * a;
    long double dn = 1.0L;
    for (int i = n; i >= 1; --i) {
      const long double ai = s.a[i - 1], bi = s.b[i - 1];
      a *= c;
      c *= dn;
      dn = (bi + a) / (ai + a);
      a = c / ai;
    }
    const long double sn_abs = 1.0L / std::sqrt(c * c + 1.0L);
    const long double sn = sv >= 0.0L ? sn_abs : -sn_abs;
    return {sn, c * sn, dn};
  }

  /// sn, cn, dn by the amplitude recursion of A&S 16.4.3: u is first reduced modulo the period
  /// 4K; then phi_N = 2^N a_N u, phi_{n-1} = (phi_n + asin(c_n / a_n sin phi_n)) / 2,
  /// sn = sin phi_0, cn = cos phi_0, and dn = sqrt(m1 + m cn^2) (A&S 16.9.1; no cancellation,
  /// and no 0/0 where cn = 0 as in cos phi_0 / cos(phi_1 - phi_0)).
  /// The arcsine is evaluated as atan2(x, sqrt(1 - x^2)) with
  ///   1 - x^2 = (a_n^2 cos^2 phi_n + b_n^2 sin^2 phi_n) / a_n^2   (a_n^2 - c_n^2 = b_n^2):
  /// for m -> 1, x = c_1 / a_1 sin phi_1 comes within ~2 sqrt(m1) of 1, where asin(x)
  /// would amplify the rounding of x by 1 / (2 m1^(1/4)) (5e3 for m1 = 1e-16); this form has none.
  [[nodiscard]] JacobiSnCnDn<long double> by_amplitude(long double u) const {
    if (m_ == 0.0L) return {std::sin(u), std::cos(u), 1.0L};
    if (m1_ == 0.0L) return sech_tanh(u);
    const detail_elliptic::Agm& s = agm_;
    const int n = s.n;
    const long double turns = std::nearbyint(u / (4.0L * k_));
    const long double ur = u - turns * 4.0L * k_;  // in [-2K, 2K]
    long double phi = std::ldexp(s.a[n] * ur, n);
    for (int i = n; i >= 1; --i) {
      const long double sp = std::sin(phi), cp = std::cos(phi);
      const long double root = std::sqrt(s.a[i] * s.a[i] * cp * cp + s.b[i] * s.b[i] * sp * sp);
      phi = 0.5L * (phi + std::atan2(s.c[i] * sp, root));
    }
    const long double sn = std::sin(phi);
    const long double cn = std::cos(phi);
    return {sn, cn, std::sqrt(m1_ + m_ * cn * cn)};
  }

 private:
  long double m_, m1_;
  detail_elliptic::Agm agm_{};
  long double k_ = 0.0L;

  // m = 1: the AGM does not converge (b0 = 0); sn = tanh, cn = dn = sech (A&S 16.15).
  static JacobiSnCnDn<long double> sech_tanh(long double u) {
    const long double sech = 1.0L / std::cosh(u);
    return {std::tanh(u), sech, sech};
  }
};

/// sn, cn, dn at one point (JacobiElliptic's operator()); m1 = 1 - m given separately.
inline JacobiSnCnDn<long double> jacobi_sn_cn_dn(long double u, long double m, long double m1) {
  return JacobiElliptic(m, m1)(u);
}

/// sn, cn, dn for float, double or long double; computed in long double.
template <class T> JacobiSnCnDn<T> jacobi_sn_cn_dn(T u, T m) {
  static_assert(std::is_floating_point_v<T>);
  const long double ml = m;
  const auto r = jacobi_sn_cn_dn(static_cast<long double>(u), ml, 1.0L - ml);
  return {static_cast<T>(r.sn), static_cast<T>(r.cn), static_cast<T>(r.dn)};
}

/// Carlson's symmetric integral R_F(x, y, z) = 1/2 int_0^inf dt / sqrt((t+x)(t+y)(t+z)) for
/// x, y, z >= 0, at most one zero, by duplication (Carlson 1995, Algorithm 1; DLMF 19.36.1):
/// iterate until 4^-n max|A0 - x_i| (3 eps)^(-1/6) < |A_n|, then the fifth-order series.
inline long double carlson_rf(long double x, long double y, long double z) {
  if (!(x >= 0.0L && y >= 0.0L && z >= 0.0L) || (x + y == 0.0L) || (y + z == 0.0L) ||
      (x + z == 0.0L)) {
    throw std::domain_error("carlson_rf: arguments must be >= 0 with at most one zero");
  }
  const long double eps = std::numeric_limits<long double>::epsilon();
  long double a = (x + y + z) / 3.0L;
  long double q = std::pow(3.0L * eps, -1.0L / 6.0L) *
                  std::max({std::fabs(a - x), std::fabs(a - y), std::fabs(a - z)});
  for (int i = 0; i < 200 && q >= std::fabs(a); ++i) {
    const long double sx = std::sqrt(x), sy = std::sqrt(y), sz = std::sqrt(z);
    const long double lam = sx * sy + sy * sz + sz * sx;
    x = 0.25L * (x + lam);
    y = 0.25L * (y + lam);
    z = 0.25L * (z + lam);
    a = 0.25L * (a + lam);
    q *= 0.25L;
  }
  const long double dx = 1.0L - x / a, dy = 1.0L - y / a;
  const long double dz = -(dx + dy);
  const long double e2 = dx * dy - dz * dz, e3 = dx * dy * dz;
  return (1.0L - e2 / 10.0L + e3 / 14.0L + e2 * e2 / 24.0L - 3.0L * e2 * e3 / 44.0L) / std::sqrt(a);
}

/// The incomplete integral F(phi|m) = int_0^phi dt / sqrt(1 - m sin^2 t), any real phi:
/// F(phi) = 2 n K + F(phi - n pi) with n = round(phi / pi), and for |phi| <= pi/2
/// F = sin(phi) R_F(cos^2 phi, m1 + m cos^2 phi, 1) (DLMF 19.25.5; 1 - m sin^2 written as
/// m1 + m cos^2 to keep m -> 1 accurate).
inline long double elliptic_f(long double phi, long double m, long double m1) {
  detail_elliptic::check_parameter(m, m1);
  const long double pi = std::numbers::pi_v<long double>;
  const long double n = std::nearbyint(phi / pi);
  const long double r = phi - n * pi;
  const long double s = std::sin(r), c = std::cos(r);
  const long double base = (s == 0.0L) ? 0.0L : s * carlson_rf(c * c, m1 + m * c * c, 1.0L);
  if (n == 0.0L) return base;
  return 2.0L * n * elliptic_k(m, m1) + base;
}

/// F(phi|m) for float, double or long double; computed in long double.
template <class T> T elliptic_f(T phi, T m) {
  static_assert(std::is_floating_point_v<T>);
  const long double ml = m;
  return static_cast<T>(elliptic_f(static_cast<long double>(phi), ml, 1.0L - ml));
}

/// The argument u in (-2K, 2K] with sn(u|m) = s, cn(u|m) = c for a point (c, s) of the unit circle
/// (normalized here): u = F(atan2(s, c)|m), evaluated without forming the angle. For c >= 0,
/// u = s R_F(c^2, m1 + m c^2, 1) in [-K, K]; for c < 0, u = sign(s) 2K - s R_F(...) (from
/// sn(2K - v) = sn v, cn(2K - v) = -cn v). For m = 1, c must be > 0 (cn = sech > 0).
inline long double jacobi_argument(long double s, long double c, long double m, long double m1) {
  detail_elliptic::check_parameter(m, m1);
  const long double r = std::hypot(s, c);
  if (!(r > 0.0L)) throw std::domain_error("jacobi_argument: (c, s) must not be (0, 0)");
  s /= r;
  c /= r;
  const long double v = (s == 0.0L) ? 0.0L : s * carlson_rf(c * c, m1 + m * c * c, 1.0L);
  if (c >= 0.0L) return v;
  if (m1 == 0.0L) throw std::domain_error("jacobi_argument: cn < 0 is impossible for m = 1");
  const long double two_k = 2.0L * elliptic_k(m, m1);
  return (s >= 0.0L ? two_k : -two_k) - v;
}

// ==== Quadrature ==============================================================================

namespace detail_quadrature {
constexpr int kGaussPoints = 20;

struct GaussLegendre {
  std::array<long double, kGaussPoints> x{};  // nodes on [-1, 1]
  std::array<long double, kGaussPoints> w{};  // weights
};

/// (P_n(x), P_n'(x)) by the three-term recurrence.
inline std::pair<long double, long double> legendre(int n, long double x) {
  long double p0 = 1.0L, p1 = x;
  for (int k = 2; k <= n; ++k) {
    const long double kk = static_cast<long double>(k);
    const long double p2 = ((2.0L * kk - 1.0L) * x * p1 - (kk - 1.0L) * p0) / kk;
    p0 = p1;
    p1 = p2;
  }
  return {p1, static_cast<long double>(n) * (x * p1 - p0) / (x * x - 1.0L)};
}

/// The kGaussPoints-point Gauss-Legendre rule: the roots of P_n by Newton's method in long double
/// from the guesses cos(pi (i + 3/4) / (n + 1/2)), weights 2 / ((1 - x^2) P_n'(x)^2).
inline const GaussLegendre& gauss_legendre() {
  static const GaussLegendre rule = [] {
    GaussLegendre g;
    constexpr int n = kGaussPoints;
    const long double pi = std::numbers::pi_v<long double>;
    for (int i = 0; i < n; ++i) {
      long double x = std::cos(pi * (static_cast<long double>(i) + 0.75L) /
                               (static_cast<long double>(n) + 0.5L));
      for (int it = 0; it < 100; ++it) {
        const auto [p, dp] = legendre(n, x);
        const long double dx = p / dp;
        x -= dx;
        if (std::fabs(dx) <= 2.0L * std::numeric_limits<long double>::epsilon()) break;
      }
      const long double dp = legendre(n, x).second;
      g.x[i] = x;
      g.w[i] = 2.0L / ((1.0L - x * x) * dp * dp);
    }
    return g;
  }();
  return rule;
}

template <class F> long double gauss_panel(const F& f, long double a, long double b) {
  const GaussLegendre& g = gauss_legendre();
  const long double mid = 0.5L * (a + b), half = 0.5L * (b - a);
  long double sum = 0.0L;
  for (int i = 0; i < kGaussPoints; ++i) sum += g.w[i] * f(mid + half * g.x[i]);
  return half * sum;
}

template <class F>
long double adapt(const F& f, long double a, long double b, long double whole, long double tol,
                  int depth) {
  const long double mid = 0.5L * (a + b);
  const long double left = gauss_panel(f, a, mid), right = gauss_panel(f, mid, b);
  const long double both = left + right;
  if (depth <= 0 || std::fabs(both - whole) <= tol) return both;
  return adapt(f, a, mid, left, 0.5L * tol, depth - 1) +
         adapt(f, mid, b, right, 0.5L * tol, depth - 1);
}
}  // namespace detail_quadrature

/// int_a^b f by adaptive 20-point Gauss-Legendre in long double: panels of width <= max_panel,
/// each bisected (at most 12 levels deep) until the rule on a piece and on its two halves agree to
/// rel_tol times the panel's integral. For smooth (analytic) integrands the 20-point rule is exact
/// to rounding on panels much narrower than the distance to the nearest complex singularity.
template <class F>
long double integrate(const F& f, long double a, long double b, long double max_panel = 0.5L,
                      long double rel_tol = 32 * std::numeric_limits<long double>::epsilon()) {
  if (a == b) return 0.0L;
  const long double len = std::fabs(b - a);
  const long double panels = std::max(1.0L, std::ceil(len / max_panel));
  const long double step = (b - a) / panels;
  long double sum = 0.0L;
  const int np = static_cast<int>(panels);
  for (int p = 0; p < np; ++p) {
    const long double lo = a + step * static_cast<long double>(p);
    const long double hi = (p + 1 == np) ? b : a + step * static_cast<long double>(p + 1);
    const long double whole = detail_quadrature::gauss_panel(f, lo, hi);
    const long double scale = std::fabs(whole) + std::numeric_limits<long double>::min();
    sum += detail_quadrature::adapt(f, lo, hi, whole, rel_tol * scale, 12);
  }
  return sum;
}

}  // namespace tumble::test
