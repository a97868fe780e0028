#pragma once
// The rotation vector (exponential coordinates): v = phi n for the rotation by the angle phi
// about the unit axis n, R = exp(S(v)).
//
// Reference: Chapter 1, "Rigid body" (the "reference chapter"), Sec. 1.1:
// R (Eq. 1.1), G with omega = G thetadot (Eq. 1.5), the product Gdot thetadot (Eq. 1.10).
//
// Conventions (docs/conventions.md): R maps body components to inertial ones, r_F = R r_f, and
// omega is the body's angular velocity in BODY components, S(omega) = R^T Rdot. With phi = |v|,
//     R     = I + (sin phi / phi) S(v) + a S(v)^2                   (Rodrigues' formula; Eq. 1.1)
//     G     = I - a S(v) + b S(v)^2,        omega = G vdot  (the right Jacobian of SO(3); Eq. 1.5)
//     G^-1  = I + 1/2 S(v) + d S(v)^2,      vdot  = G^-1 omega
//     Gdot vdot = -adot v x vdot + bdot v x (v x vdot) + b vdot x (v x vdot)      (Eq. 1.10)
// (the terms -a vdot x vdot and b v x (vdot x vdot) of Gdot vdot vanish), with
//     a = (1 - cos phi) / phi^2 = 2 sin^2(phi/2) / phi^2,      b = (phi - sin phi) / phi^3,
//     d = 1/phi^2 - (1 + cos phi) / (2 phi sin phi) = 1/phi^2 - cos(phi/2) / (2 phi sin(phi/2)),
//     adot = (v.vdot) c1,  c1 = a'(phi) / phi = (phi sin phi - 2 (1 - cos phi)) / phi^4,
//     bdot = (v.vdot) c2,  c2 = b'(phi) / phi = ((1 - cos phi) phi - 3 (phi - sin phi)) / phi^5.
// d is evaluated through cot(phi/2), which is regular at phi = pi where (1 + cos) / sin is 0/0.
// The unit quaternion is (cos(phi/2), (sin(phi/2) / phi) v).
//
// Small angles. Every coefficient above is an even, entire (d: analytic for phi < 2 pi) function
// of phi, so it is a power series in x = phi^2 = v.v. The closed forms lose accuracy as phi -> 0
// by cancellation (measured in float, double and long double against mpmath: ~2.5 eps/x for b,
// ~17 eps/x for d and c1, ~100 eps/x^2 for c2; sin phi / phi, a, cos(phi/2), sin(phi/2) / phi
// do not cancel but are 0/0 at v = 0), and phi = sqrt(v.v) has an infinite derivative at the
// origin, which makes AD derivatives NaN there. So each coefficient f has a Taylor branch: its
// 14-term series in x (exact rational coefficients, derived with sympy, evaluated by
// detail::horner; no sqrt) is used for x < x_f, with the threshold following from the scalar
// type's epsilon:
//     x_f = min(4, (eps |c_0 / c_13|)^(1/13))
// where the last term kept is eps times the first, so the truncation error (the next term, a
// further factor x / (28 * 29), or x / (4 pi^2) for d, smaller) is below eps. The cap x <= 4
// (phi <= 2) is where the closed forms are accurate again (c2, the worst, to ~11 eps) and the
// alternating series' rounding is still ~1 eps. This gives phi_f = 2 for every coefficient in
// float, double and x86 long double except d (double: 1.60, long double: 1.19, where the closed
// form of d is accurate to ~6 eps and ~12 eps). A long double with a longer mantissa (128-bit
// quad) gets smaller thresholds and loses up to ~100 eps there, still far below double's eps.
// from_quaternion() uses the series of atan(t)/t in t^2 = e.e / e0^2 by the same rule (there
// atan2(|e|, e0) / |e| does not cancel; the branch only avoids sqrt(0) at the identity; its
// threshold, t^2 = 0.08 in double, stays inside the radius of convergence t^2 < 1).
//
// Singular attitudes: G is singular where det G = 2 (1 - cos phi) / phi^2 = 0, at phi = 2 pi k,
// k >= 1 (the identity reached the long way round). singularity_distance() is the distance of
// phi to the nearest of them, 2 pi - phi for phi <= 3 pi.
//
// canonical(): the same attitude has the vectors (phi - 2 pi k) n for every integer k. canonical()
// returns v itself for phi <= pi and otherwise the equivalent vector (phi - 2 pi k) n with
// k = round(phi / (2 pi)), whose norm is <= pi (for pi < phi < 2 pi: (phi - 2 pi) n, the rotation
// the short way round). Canonical vectors are at least pi from the singularity.
//
// \warning v and canonical(v) are the SAME attitude: compare attitudes through rotation(), never
//          by comparing rotation vectors. A state [v; vdot] that is switched to canonical(v) needs
//          its rate switched too: vdot' = thetadot(canonical(v), G(v) vdot) (the same omega).
// \warning from_rotation() and from_quaternion() return phi <= pi; near phi = pi the axis sign is
//          ill-conditioned (v and -v are then nearly the same attitude).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string_view>
#include <type_traits>
#include <utility>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "tumble/core/math.hpp"
#include "tumble/core/types.hpp"
#include "tumble/orientation/concept.hpp"
#include "tumble/orientation/euler_parameters.hpp"

namespace tumble {

namespace detail::rotation_vector {

// Taylor coefficients in x = phi^2 (exact rationals: sympy series of each closed form; the
// largest denominators exceed 2^64 and are written as long double literals, rounded once).
// sin(phi) / phi
inline constexpr long double kSinc[] = {1.0L,
                                        -1.0L / 6.0L,
                                        1.0L / 120.0L,
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
                                        -1.0L / 10888869450418352160768000000.0L};
// a = (1 - cos phi) / phi^2
inline constexpr long double kA[] = {1.0L / 2.0L,
                                     -1.0L / 24.0L,
                                     1.0L / 720.0L,
                                     -1.0L / 40320.0L,
                                     1.0L / 3628800.0L,
                                     -1.0L / 479001600.0L,
                                     1.0L / 87178291200.0L,
                                     -1.0L / 20922789888000.0L,
                                     1.0L / 6402373705728000.0L,
                                     -1.0L / 2432902008176640000.0L,
                                     1.0L / 1124000727777607680000.0L,
                                     -1.0L / 620448401733239439360000.0L,
                                     1.0L / 403291461126605635584000000.0L,
                                     -1.0L / 304888344611713860501504000000.0L};
// b = (phi - sin phi) / phi^3
inline constexpr long double kB[] = {1.0L / 6.0L,
                                     -1.0L / 120.0L,
                                     1.0L / 5040.0L,
                                     -1.0L / 362880.0L,
                                     1.0L / 39916800.0L,
                                     -1.0L / 6227020800.0L,
                                     1.0L / 1307674368000.0L,
                                     -1.0L / 355687428096000.0L,
                                     1.0L / 121645100408832000.0L,
                                     -1.0L / 51090942171709440000.0L,
                                     1.0L / 25852016738884976640000.0L,
                                     -1.0L / 15511210043330985984000000.0L,
                                     1.0L / 10888869450418352160768000000.0L,
                                     -1.0L / 8841761993739701954543616000000.0L};
// d = 1/phi^2 - (1 + cos phi) / (2 phi sin phi) (Bernoulli numbers; converges for x < 4 pi^2)
inline constexpr long double kD[] = {1.0L / 12.0L,
                                     1.0L / 720.0L,
                                     1.0L / 30240.0L,
                                     1.0L / 1209600.0L,
                                     1.0L / 47900160.0L,
                                     691.0L / 1307674368000.0L,
                                     1.0L / 74724249600.0L,
                                     3617.0L / 10670622842880000.0L,
                                     43867.0L / 5109094217170944000.0L,
                                     174611.0L / 802857662698291200000.0L,
                                     77683.0L / 14101100039391805440000.0L,
                                     236364091.0L / 1693824136731743669452800000.0L,
                                     657931.0L / 186134520519971831808000000.0L,
                                     3392780147.0L / 37893265687455865519472640000000.0L};
// c1 = (phi sin phi - 2 (1 - cos phi)) / phi^4 = 2 da/dx
inline constexpr long double kC1[] = {-1.0L / 12.0L,
                                      1.0L / 180.0L,
                                      -1.0L / 6720.0L,
                                      1.0L / 453600.0L,
                                      -1.0L / 47900160.0L,
                                      1.0L / 7264857600.0L,
                                      -1.0L / 1494484992000.0L,
                                      1.0L / 400148356608000.0L,
                                      -1.0L / 135161222676480000.0L,
                                      1.0L / 56200036388880384000.0L,
                                      -1.0L / 28202200078783610880000.0L,
                                      1.0L / 16803810880275234816000000.0L,
                                      -1.0L / 11726474792758225403904000000.0L,
                                      1.0L / 9473316421863966379868160000000.0L};
// c2 = ((1 - cos phi) phi - 3 (phi - sin phi)) / phi^5 = 2 db/dx
inline constexpr long double kC2[] = {-1.0L / 60.0L,
                                      1.0L / 1260.0L,
                                      -1.0L / 60480.0L,
                                      1.0L / 4989600.0L,
                                      -1.0L / 622702080.0L,
                                      1.0L / 108972864000.0L,
                                      -1.0L / 25406244864000.0L,
                                      1.0L / 7602818775552000.0L,
                                      -1.0L / 2838385676206080000.0L,
                                      1.0L / 1292600836944248832000.0L,
                                      -1.0L / 705055001969590272000000.0L,
                                      1.0L / 453702893767431340032000000.0L,
                                      -1.0L / 340067768989988536713216000000.0L,
                                      1.0L / 293672809077782957775912960000000.0L};
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
// atan(t) / t in t^2 (radius of convergence t^2 < 1)
inline constexpr long double kAtanc[] = {1.0L,         -1.0L / 3.0L,  1.0L / 5.0L,  -1.0L / 7.0L,
                                         1.0L / 9.0L,  -1.0L / 11.0L, 1.0L / 13.0L, -1.0L / 15.0L,
                                         1.0L / 17.0L, -1.0L / 19.0L, 1.0L / 21.0L, -1.0L / 23.0L,
                                         1.0L / 25.0L, -1.0L / 27.0L};

/// The upper end, in x, of the interval on which the series c is used: the x where the last term
/// kept, c_{N-1} x^{N-1}, is eps |c_0| (see the file comment), capped at x_max.
template <class V, std::size_t N>
[[nodiscard]] V series_limit(const long double (&c)[N], long double x_max) {
  using std::fabs;
  using std::pow;
  const long double eps = static_cast<long double>(std::numeric_limits<V>::epsilon());
  const long double x = pow(eps * fabs(c[0] / c[N - 1]), 1.0L / static_cast<long double>(N - 1));
  return static_cast<V>(std::min(x, x_max));
}

/// The thresholds of every series for the value type V, computed once.
template <class V> struct Limits { V sinc, a, b, d, c1, c2, half_cos, half_sinc, atanc; };

template <class V> [[nodiscard]] const Limits<V>& limits() {
  constexpr long double x_max = 4.0L;  // phi <= 2, see the file comment
  static const Limits<V> l{series_limit<V>(kSinc, x_max),    series_limit<V>(kA, x_max),
                           series_limit<V>(kB, x_max),       series_limit<V>(kD, x_max),
                           series_limit<V>(kC1, x_max),      series_limit<V>(kC2, x_max),
                           series_limit<V>(kHalfCos, x_max), series_limit<V>(kHalfSinc, x_max),
                           series_limit<V>(kAtanc, x_max)};
  return l;
}

/// The coefficient functions of the file comment at x = phi^2 = v.v: each one is its Taylor
/// series for x below its threshold (no sqrt, so AD derivatives stay finite at v = 0) and its
/// closed form above. phi, sin phi, sin(phi/2) and cos(phi/2) are computed once, and only when a
/// closed form needs them.
template <class S> class PhiFunctions {
 public:
  using V = decltype(value(std::declval<S>()));

  explicit PhiFunctions(const S& x) : x_(x), xv_(value(x)), lim_(limits<V>()) {}

  /// sin(phi) / phi
  S sinc() {
    if (xv_ < lim_.sinc) return horner(kSinc, x_);
    trig();
    return s_ / phi_;
  }
  /// a = (1 - cos phi) / phi^2, as 2 sin^2(phi/2) / phi^2 (no cancellation).
  S a() {
    if (xv_ < lim_.a) return horner(kA, x_);
    trig();
    return S(2) * sh_ * sh_ / x_;
  }
  /// b = (phi - sin phi) / phi^3
  S b() {
    if (xv_ < lim_.b) return horner(kB, x_);
    trig();
    return (phi_ - s_) / (x_ * phi_);
  }
  /// d = 1/phi^2 - cos(phi/2) / (2 phi sin(phi/2)) (regular at phi = pi, singular at 2 pi).
  S d() {
    if (xv_ < lim_.d) return horner(kD, x_);
    trig();
    return S(1) / x_ - ch_ / (S(2) * phi_ * sh_);
  }
  /// c1 = (phi sin phi - 2 (1 - cos phi)) / phi^4
  S c1() {
    if (xv_ < lim_.c1) return horner(kC1, x_);
    trig();
    return (phi_ * s_ - S(4) * sh_ * sh_) / (x_ * x_);
  }
  /// c2 = ((1 - cos phi) phi - 3 (phi - sin phi)) / phi^5
  S c2() {
    if (xv_ < lim_.c2) return horner(kC2, x_);
    trig();
    return (S(2) * sh_ * sh_ * phi_ - S(3) * (phi_ - s_)) / (x_ * x_ * phi_);
  }
  /// cos(phi/2)
  S half_cos() {
    if (xv_ < lim_.half_cos) return horner(kHalfCos, x_);
    trig();
    return ch_;
  }
  /// sin(phi/2) / phi
  S half_sinc() {
    if (xv_ < lim_.half_sinc) return horner(kHalfSinc, x_);
    trig();
    return sh_ / phi_;
  }

 private:
  void trig() {
    if (have_trig_) return;
    using std::cos;
    using std::sin;
    using std::sqrt;
    phi_ = sqrt(x_);
    const S h = S(0.5) * phi_;
    s_ = sin(phi_);
    sh_ = sin(h);
    ch_ = cos(h);
    have_trig_ = true;
  }

  S x_;
  V xv_;
  const Limits<V>& lim_;
  bool have_trig_ = false;
  S phi_, s_, sh_, ch_;
};

}  // namespace detail::rotation_vector

struct RotationVector {
  static constexpr int size = 3;
  static constexpr bool has_constraint = false;
  static constexpr std::string_view name = "RotationVector";
  template <class S> using Coords = Vector3<S>;

  /// R = exp(S(v)) = I + (sin phi / phi) S(v) + a S(v)^2   (body -> inertial; Eq. 1.1).
  template <class S> [[nodiscard]] static Matrix3<S> rotation(const Coords<S>& v) {
    detail::rotation_vector::PhiFunctions<S> f(v.squaredNorm());
    const Matrix3<S> sk = skew(v);
    return Matrix3<S>::Identity() + f.sinc() * sk + f.a() * (sk * sk);
  }

  /// G = I - a S(v) + b S(v)^2, omega = G vdot in body components   (Eq. 1.5).
  template <class S> [[nodiscard]] static Matrix3<S> G(const Coords<S>& v) {
    detail::rotation_vector::PhiFunctions<S> f(v.squaredNorm());
    const Matrix3<S> sk = skew(v);
    return Matrix3<S>::Identity() - f.a() * sk + f.b() * (sk * sk);
  }

  /// Gdot vdot = -adot v x vdot + bdot v x (v x vdot) + b vdot x (v x vdot), with
  /// adot = (v.vdot) c1 and bdot = (v.vdot) c2   (Eq. 1.10).
  template <class S>
  [[nodiscard]] static Vector3<S> Gdot_thetadot(const Coords<S>& v, const Coords<S>& vdot) {
    detail::rotation_vector::PhiFunctions<S> f(v.squaredNorm());
    const S vvd = v.dot(vdot);
    const Vector3<S> u = v.cross(vdot);
    return (-vvd * f.c1()) * u + (vvd * f.c2()) * v.cross(u) + f.b() * vdot.cross(u);
  }

  /// vdot = G^-1 omega = omega + 1/2 v x omega + d v x (v x omega).
  /// \warning Not finite at phi = 2 pi k, k >= 1 (the singular attitudes of the chart).
  template <class S>
  [[nodiscard]] static Coords<S> thetadot(const Coords<S>& v, const Vector3<S>& omega) {
    detail::rotation_vector::PhiFunctions<S> f(v.squaredNorm());
    const Vector3<S> u = v.cross(omega);
    return omega + S(0.5) * u + f.d() * v.cross(u);
  }

  /// vddot = G^-1 (alpha - Gdot vdot)   (Eq. 1.10 solved for the parameter accelerations).
  template <class S>
  [[nodiscard]] static Coords<S> thetaddot(const Coords<S>& v, const Coords<S>& vdot,
                                           const Vector3<S>& alpha) {
    return thetadot(v, Vector3<S>(alpha - Gdot_thetadot(v, vdot)));
  }

  /// Through the quaternion of Shepperd's method (EulerParameters::from_rotation), so phi <= pi.
  template <class S> [[nodiscard]] static Coords<S> from_rotation(const Matrix3<S>& r) {
    return from_quaternion(EulerParameters::to_quaternion(EulerParameters::from_rotation(r)));
  }

  /// q = (cos(phi/2), (sin(phi/2) / phi) v).
  template <class S> [[nodiscard]] static Eigen::Quaternion<S> to_quaternion(const Coords<S>& v) {
    detail::rotation_vector::PhiFunctions<S> f(v.squaredNorm());
    const S k = f.half_sinc();
    return Eigen::Quaternion<S>(f.half_cos(), k * v(0), k * v(1), k * v(2));  // w-first
  }

  /// v = 2 atan2(|e|, e0) e / |e| for the sign of q with e0 >= 0, so phi <= pi. Independent of the
  /// norm of q, so q need not be normalized. For small t^2 = e.e / e0^2 it is evaluated as
  /// (2 / e0) (atan(t) / t) e with the series of atan(t) / t in t^2 (no sqrt of e.e, which would
  /// be 0 / 0 at the identity and give NaN AD derivatives there).
  /// \throws std::domain_error for q = 0, which is no attitude.
  template <class S> [[nodiscard]] static Coords<S> from_quaternion(const Eigen::Quaternion<S>& q) {
    using std::atan2;
    using std::sqrt;
    using V = decltype(detail::value(std::declval<S>()));
    S e0 = q.w();
    Vector3<S> e(q.x(), q.y(), q.z());
    if (detail::value(e0) < 0) {
      e0 = -e0;
      e = -e;
    }
    const S ee = e.squaredNorm();
    const S e00 = e0 * e0;
    if (!(detail::value(ee) + detail::value(e00) > 0)) {
      throw std::domain_error("RotationVector: the zero quaternion is no attitude");
    }
    if (detail::value(ee) < detail::rotation_vector::limits<V>().atanc * detail::value(e00)) {
      const S two_over_e0 = S(2) / e0;  // named: AD may need to resize its derivatives
      const S f = two_over_e0 * detail::horner(detail::rotation_vector::kAtanc, S(ee / e00));
      return f * e;
    }
    S n = sqrt(ee);
    if constexpr (!std::is_arithmetic_v<S>) {
      // Eigen's atan2 for AD scalars subtracts the derivative vectors of its arguments without
      // resizing the empty one of a constant: give both the same size (zeros where missing).
      if (n.derivatives().size() == 0) {
        n.derivatives().setZero(e0.derivatives().size());
      } else if (e0.derivatives().size() == 0) {
        e0.derivatives().setZero(n.derivatives().size());
      }
    }
    const S f = S(2) * atan2(n, e0) / n;
    return f * e;
  }

  /// The distance of phi = |v| to the nearest singular angle 2 pi k, k >= 1: 2 pi - phi for
  /// phi <= 3 pi. At v = 0 it returns 2 pi without taking sqrt(0) (whose AD derivative is not
  /// finite; the distance is not differentiable there anyway).
  template <class S> [[nodiscard]] static S singularity_distance(const Coords<S>& v) {
    using std::abs;
    using std::sqrt;
    const S two_pi = S(2) * detail::pi<S>();
    const S x = v.squaredNorm();
    if (detail::value(x) == 0) {
      return two_pi;
    }
    const S phi = sqrt(x);
    const auto k = std::max(decltype(detail::value(phi))(1),
                            std::round(detail::value(phi) / detail::value(two_pi)));
    const S singular = S(k) * two_pi;  // named: AD may need to resize its empty derivatives
    const S dist = phi - singular;
    return detail::value(dist) < 0 ? S(-dist) : dist;
  }

  /// v itself for phi <= pi; otherwise the equivalent vector (phi - 2 pi k) n, k = round(phi /
  /// (2 pi)), with norm <= pi (the same attitude; see the file comment).
  template <class S> [[nodiscard]] static Coords<S> canonical(const Coords<S>& v) {
    using std::sqrt;
    const S x = v.squaredNorm();
    const S p = detail::pi<S>();
    if (!(detail::value(x) > detail::value(p) * detail::value(p))) {
      return v;
    }
    const S phi = sqrt(x);
    const auto k = std::round(detail::value(phi) / (2 * detail::value(p)));
    const S period = S(2 * k) * p;  // named: AD may need to resize its empty derivatives
    const S f = S(1) - period / phi;
    return f * v;
  }
};

static_assert(Orientation<RotationVector>);

}  // namespace tumble
