#pragma once
// The coefficient functions of the rotation vector (rotation_vector.hpp, whose file comment
// derives them and says which form is used where): their series in x = phi^2 (exact rational
// Taylor coefficients, the number of terms and the thresholds for each value type, Estrin's
// scheme, scalar and packed), their closed forms, and PhiFunctions, which evaluates each lazily.

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <limits>
#include <type_traits>
#include <utility>

#include <Eigen/Core>

#include "tumble/core/math.hpp"

namespace tumble {

namespace detail::rotation_vector {

// Taylor coefficients in x = phi^2 (exact rationals: sympy series of each closed form; the
// largest denominators exceed 2^64 and are written as long double literals, rounded once).
// cos(phi/2)
inline constexpr long double kHalfCos[] = {1.0L,
                                           -1.0L / 8.0L,
                                           1.0L / 384.0L,
                                           -1.0L / 46080.0L,
                                           1.0L / 10321920.0L,
                                           -1.0L / 3715891200.0L,
                                           1.0L / 1961990553600.0L,
                                           -1.0L / 1428329123020800.0L,
                                           1.0L / 1371195958099968000.0L,
                                           -1.0L / 1678343852714360832000.0L,
                                           1.0L / 2551082656125828464640000.0L,
                                           -1.0L / 4714400748520531002654720000.0L,
                                           1.0L / 10409396852733332453861621760000.0L,
                                           -1.0L / 27064431817106664380040216576000000.0L};
// sin(phi/2) / phi
inline constexpr long double kHalfSinc[] = {1.0L / 2.0L,
                                            -1.0L / 48.0L,
                                            1.0L / 3840.0L,
                                            -1.0L / 645120.0L,
                                            1.0L / 185794560.0L,
                                            -1.0L / 81749606400.0L,
                                            1.0L / 51011754393600.0L,
                                            -1.0L / 42849873690624000.0L,
                                            1.0L / 46620662575398912000.0L,
                                            -1.0L / 63777066403145711616000.0L,
                                            1.0L / 107145471557284795514880000.0L,
                                            -1.0L / 216862434431944426122117120000.0L,
                                            1.0L / 520469842636666622693081088000000.0L,
                                            -1.0L / 1461479318123759876522171695104000000.0L};
// A2 = (1/2 - a) / x = (cos phi - 1 + phi^2 / 2) / phi^4 (the series of a from its second term,
// negated)
inline constexpr long double kA2[] = {1.0L / 24.0L,
                                      -1.0L / 720.0L,
                                      1.0L / 40320.0L,
                                      -1.0L / 3628800.0L,
                                      1.0L / 479001600.0L,
                                      -1.0L / 87178291200.0L,
                                      1.0L / 20922789888000.0L,
                                      -1.0L / 6402373705728000.0L,
                                      1.0L / 2432902008176640000.0L,
                                      -1.0L / 1124000727777607680000.0L,
                                      1.0L / 620448401733239439360000.0L,
                                      -1.0L / 403291461126605635584000000.0L,
                                      1.0L / 304888344611713860501504000000.0L,
                                      -1.0L / 265252859812191058636308480000000.0L,
                                      1.0L / 263130836933693530167218012160000000.0L,
                                      -1.0L / 295232799039604140847618609643520000000.0L};
// B2 = (1/6 - b) / x = (sin phi - phi + phi^3 / 6) / phi^5 (the series of b from its second term,
// negated)
inline constexpr long double kB2[] = {1.0L / 120.0L,
                                      -1.0L / 5040.0L,
                                      1.0L / 362880.0L,
                                      -1.0L / 39916800.0L,
                                      1.0L / 6227020800.0L,
                                      -1.0L / 1307674368000.0L,
                                      1.0L / 355687428096000.0L,
                                      -1.0L / 121645100408832000.0L,
                                      1.0L / 51090942171709440000.0L,
                                      -1.0L / 25852016738884976640000.0L,
                                      1.0L / 15511210043330985984000000.0L,
                                      -1.0L / 10888869450418352160768000000.0L,
                                      1.0L / 8841761993739701954543616000000.0L,
                                      -1.0L / 8222838654177922817725562880000000.0L,
                                      1.0L / 8683317618811886495518194401280000000.0L,
                                      -1.0L / 10333147966386144929666651337523200000000.0L};
// atan(t) / t in t^2 (radius of convergence t^2 < 1)
inline constexpr long double kAtanc[] = {1.0L,         -1.0L / 3.0L,  1.0L / 5.0L,  -1.0L / 7.0L,
                                         1.0L / 9.0L,  -1.0L / 11.0L, 1.0L / 13.0L, -1.0L / 15.0L,
                                         1.0L / 17.0L, -1.0L / 19.0L, 1.0L / 21.0L, -1.0L / 23.0L,
                                         1.0L / 25.0L, -1.0L / 27.0L};

// The caps of the series' intervals (see the file comment): phi <= 2 for the half-angle functions,
// phi <= 3.5 for A2 and B2 (canonical vectors, phi <= pi, and the stages of a step past pi).
inline constexpr long double kXMax = 4.0L;
inline constexpr long double kCoefficientXMax = 12.25L;

/// The number of terms of the series c kept for the value type V: all up to the first whose
/// magnitude at x_max is below eps |c_0| (the later ones are smaller still on [0, x_max] and do
/// not change the sum), at most all N.
template <class V, std::size_t N>
[[nodiscard]] constexpr std::size_t series_terms(const long double (&c)[N], long double x_max) {
  const long double eps = static_cast<long double>(std::numeric_limits<V>::epsilon());
  const long double c0 = c[0] < 0 ? -c[0] : c[0];
  long double p = 1;  // x_max^k
  for (std::size_t k = 0; k < N; ++k) {
    const long double t = (c[k] < 0 ? -c[k] : c[k]) * p;
    if (t <= eps * c0) {
      return k + 1;
    }
    p *= x_max;
  }
  return N;
}

/// The upper end, in x, of the interval on which the series c is used: the x where the last term
/// kept, c_{n-1} x^{n-1} (n = series_terms), is eps |c_0| (see the file comment), capped at x_max.
template <class V, std::size_t N>
[[nodiscard]] V series_limit(const long double (&c)[N], long double x_max) {
  using std::fabs;
  using std::pow;
  const std::size_t n = series_terms<V>(c, x_max);
  const long double eps = static_cast<long double>(std::numeric_limits<V>::epsilon());
  const long double x = pow(eps * fabs(c[0] / c[n - 1]), 1.0L / static_cast<long double>(n - 1));
  return static_cast<V>(std::min(x, x_max));
}

/// sum_{k < n} c[off + k] x^k by Estrin's scheme, p = lo + x^m hi with m the largest power of two
/// below n: log2(n) levels of multiply-adds whose chains run in parallel, where Horner's rule is
/// one chain of n - 1 (the latency of a call's whole series branch). xp[j] = x^(2^j).
template <const auto& c, std::size_t off, std::size_t n, class S>
[[nodiscard, gnu::always_inline]] inline S estrin(const S (&xp)[4]) {
  using V = decltype(value(std::declval<S>()));
  if constexpr (n == 1) {
    return S(V(c[off]));
  } else {
    constexpr std::size_t m = std::bit_floor(n - 1);
    static_assert(m <= 8, "estrin: xp holds x^(2^j) for j <= 3");
    const S hi = estrin<c, off + m, n - m>(xp);
    return estrin<c, off, m>(xp) + xp[std::countr_zero(m)] * hi;
  }
}

/// The series c at x, its first n terms, by Estrin's scheme.
template <const auto& c, std::size_t n, class S>
[[nodiscard, gnu::always_inline]] inline S series(const S& x) {
  const S x2 = x * x;
  const S x4 = x2 * x2;
  const S xp[4] = {x, x2, x4, S(x4 * x4)};
  return estrin<c, 0, n>(xp);
}

/// Two series c and d at the same x, as one Estrin evaluation of the pair (c_k, d_k) on a packed
/// 2-vector A (Eigen::Array<V, 2, 1>): the same operations as two `estrin` calls, each applied
/// to both lanes at once.
template <const auto& c, const auto& d, std::size_t off, std::size_t n, class A>
[[nodiscard, gnu::always_inline]] inline A estrin2(const A (&xp)[4]) {
  using V = typename A::Scalar;
  if constexpr (n == 1) {
    return A(V(c[off]), V(d[off]));
  } else {
    constexpr std::size_t m = std::bit_floor(n - 1);
    const A hi = estrin2<c, d, off + m, n - m>(xp);
    return estrin2<c, d, off, m>(xp) + xp[std::countr_zero(m)] * hi;
  }
}

/// The thresholds for the value type V, computed once: `series` for the coefficient functions
/// of the file comment (those of A2 and B2, from which they all follow), the others for their
/// own series.
template <class V> struct Limits { V series, half_cos, half_sinc, atanc; };

template <class V> [[nodiscard]] const Limits<V>& limits() {
  constexpr long double x_max = kXMax;
  constexpr long double xc_max = kCoefficientXMax;
  static const Limits<V> l{std::min(series_limit<V>(kA2, xc_max), series_limit<V>(kB2, xc_max)),
                           series_limit<V>(kHalfCos, x_max), series_limit<V>(kHalfSinc, x_max),
                           series_limit<V>(kAtanc, x_max)};
  return l;
}

/// A2 and B2 at x, each with the terms the longer needs on [0, kCoefficientXMax] (one more than
/// the other at most); for a plain floating-point S in one packed evaluation.
template <class S> [[gnu::always_inline]] inline void remainders(const S& x, S& a2, S& b2) {
  using V = decltype(value(std::declval<S>()));
  constexpr std::size_t n =
      std::max(series_terms<V>(kA2, kCoefficientXMax), series_terms<V>(kB2, kCoefficientXMax));
  if constexpr (std::is_floating_point_v<S>) {
    using A = Eigen::Array<S, 2, 1>;
    const S x2 = x * x;
    const S x4 = x2 * x2;
    const A xp[4] = {A::Constant(x), A::Constant(x2), A::Constant(x4), A::Constant(x4 * x4)};
    const A r = estrin2<kA2, kB2, 0, n>(xp);
    a2 = r(0);
    b2 = r(1);
  } else {
    a2 = series<kA2, n>(x);
    b2 = series<kB2, n>(x);
  }
}

/// The coefficient functions of rotation_vector.hpp's file comment at one x = phi^2.
template <class S> struct Coefficients { S sinc, a, b, c1, c2, d; };

/// The coefficient functions below the threshold, from x, A2 and B2 (see PhiFunctions).
template <class S>
[[nodiscard, gnu::always_inline]] inline Coefficients<S> from_remainders(const S& x, const S& a2,
                                                                         const S& b2) {
  using V = decltype(value(std::declval<S>()));
  Coefficients<S> c;
  c.a = S(0.5) - x * a2;
  c.b = S(V(1) / V(6)) - x * b2;
  c.sinc = S(1) - x * c.b;
  c.c1 = S(2) * a2 - c.b;
  c.c2 = S(3) * b2 - a2;
  c.d = -c.c1 / (S(2) * c.a);  // = (b - 2 A2) / (2 a); one division
  return c;
}

/// The coefficient functions of the file comment at x = phi^2 = v.v. Below the threshold
/// (x < limits().series) all follow from two series, A2 = (1/2 - a) / x and B2 = (1/6 - b) / x
/// (no sqrt, so AD derivatives stay finite at v = 0), without cancellation:
///     a = 1/2 - x A2,   b = 1/6 - x B2,   sin phi / phi = 1 - x b,
///     c1 = 2 A2 - b,    c2 = 3 B2 - A2,   d = (b - 2 A2) / (2 a) = -c1 / (2 a)
/// (d: (phi/2) cot(phi/2) = sinc / (2 a), so d = (2 a - sinc) / (2 a x), and 2 a - sinc =
/// x (b - 2 A2); regular through phi = pi, where a = 2 / pi^2).
/// Above it, their closed forms. phi, sin(phi/2) and cos(phi/2) (one sincos; sin phi is
/// 2 sin(phi/2) cos(phi/2)), or A2 and B2, are computed once, and only when needed.
template <class S> class PhiFunctions {
 public:
  using V = decltype(value(std::declval<S>()));

  explicit PhiFunctions(const S& x)
      : x_(x), series_(value(x) < limits<V>().series), xv_(value(x)), lim_(limits<V>()) {}

  /// True when the coefficient functions come from the series (x below the threshold).
  [[nodiscard]] bool uses_series() const { return series_; }

  /// sin(phi) / phi
  S sinc() {
    if (series_) return from_series().sinc;
    trig();
    return s_ / phi_;
  }
  /// a = (1 - cos phi) / phi^2, as 2 sin^2(phi/2) / phi^2 (no cancellation).
  S a() {
    if (series_) return from_series().a;
    trig();
    return S(2) * sh_ * sh_ / x_;
  }
  /// b = (phi - sin phi) / phi^3
  S b() {
    if (series_) return from_series().b;
    trig();
    return (phi_ - s_) / (x_ * phi_);
  }
  /// d = 1/phi^2 - cos(phi/2) / (2 phi sin(phi/2)) (regular at phi = pi, singular at 2 pi).
  S d() {
    if (series_) return from_series().d;
    trig();
    return (S(2) * sh_ - phi_ * ch_) / (S(2) * x_ * sh_);  // one division
  }
  /// c1 = (phi sin phi - 2 (1 - cos phi)) / phi^4
  S c1() {
    if (series_) return from_series().c1;
    trig();
    return (phi_ * s_ - S(4) * sh_ * sh_) / (x_ * x_);
  }
  /// c2 = ((1 - cos phi) phi - 3 (phi - sin phi)) / phi^5
  S c2() {
    if (series_) return from_series().c2;
    trig();
    return (S(2) * sh_ * sh_ * phi_ - S(3) * (phi_ - s_)) / (x_ * x_ * phi_);
  }
  /// All six at once.
  Coefficients<S> all() { return {sinc(), a(), b(), c1(), c2(), d()}; }
  /// cos(phi/2)
  S half_cos() {
    if (xv_ < lim_.half_cos) return series<kHalfCos, series_terms<V>(kHalfCos, kXMax)>(x_);
    trig();
    return ch_;
  }
  /// sin(phi/2) / phi
  S half_sinc() {
    if (xv_ < lim_.half_sinc) return series<kHalfSinc, series_terms<V>(kHalfSinc, kXMax)>(x_);
    trig();
    return sh_ / phi_;
  }

 private:
  const Coefficients<S>& from_series() {
    if (!have_series_) {
      S a2, b2;
      remainders(x_, a2, b2);
      series_values_ = from_remainders(x_, a2, b2);
      have_series_ = true;
    }
    return series_values_;
  }
  void trig() {
    if (have_trig_) return;
    using std::cos;
    using std::sin;
    using std::sqrt;
    phi_ = sqrt(x_);
    const S h = S(0.5) * phi_;
    sh_ = sin(h);
    ch_ = cos(h);
    s_ = S(2) * sh_ * ch_;  // sin phi: no second call (sin and cos of h are one sincos)
    have_trig_ = true;
  }

  S x_;
  bool series_;
  V xv_;
  const Limits<V>& lim_;
  bool have_trig_ = false;
  bool have_series_ = false;
  // Value-initialized: each is read only once its flag above is set, which GCC's
  // -Wmaybe-uninitialized does not follow at -O1 (a -Werror build there failed). The stores are off
  // the hot path: in registers they vanish (the inlined series below the threshold), and
  // closed_forms, the one out-of-line user, is cold (GCC 12 -O3: 80 bytes zeroed there, nothing
  // else changed).
  Coefficients<S> series_values_{};
  S phi_{}, s_{}, sh_{}, ch_{};
};

}  // namespace detail::rotation_vector

}  // namespace tumble
