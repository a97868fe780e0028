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
// origin, which makes AD derivatives NaN there. So below a threshold x_s every coefficient comes
// from two series (exact rational coefficients, alternating, no sqrt),
//     A2 = (1/2 - a) / x = sum_k (-x)^k / (2k+4)!,    B2 = (1/6 - b) / x = sum_k (-x)^k / (2k+5)!,
// by algebra that does not cancel (class PhiFunctions, detail/rotation_vector_functions.hpp):
//     a = 1/2 - x A2,  b = 1/6 - x B2,  sin phi / phi = 1 - x b,  c1 = 2 A2 - b,  c2 = 3 B2 - A2,
//     d = (b - 2 A2) / (2 a) = -c1 / (2 a)
// (d: (phi/2) cot(phi/2) = (sin phi / phi) / (2 a), so d = (2 a - sin phi / phi) / (2 a x), and
// 2 a - sin phi / phi = x (b - 2 A2); regular through phi = pi, where a = 2 / pi^2): one branch
// and two series per attitude, shared by R, G, Gdot vdot and G^-1 (Precomputed), and no sqrt,
// sine, cosine or division but d's. Each series keeps its terms up to the first below eps |c_0|
// at the cap x = 12.25 (double: 14 of A2 and 13 of B2, float: 9 and 8, x86 long double: 16 and
// 15; both are summed to the longer's count, in one packed evaluation for float and double) and
// is used for
//     x < x_s = min(12.25, (eps |c_0 / c_{n-1}|)^(1/(n-1)))      (n terms kept),
// where the last term kept is eps times the first, so the truncation error (the next term, a
// further factor x / ((2n + 4)(2n + 5)) smaller) is below eps. The cap, phi = 3.5, takes every
// canonical vector (phi <= pi, see canonical(): a scene leaves the chart at phi = pi) and the
// stages of a step past pi. The series cancel little there (the sum of their terms' magnitudes
// is at most 2.3 times the value), and the derived coefficients add a few roundings: against
// long double closed forms on 20,000 points of [2, 12.25], double's series are within 3.7 eps
// (a), 1.5 (b), 5.0 (d), 3.8 (c1) and 6.7 eps (c2), where the closed forms on [2, 12.25] give
// 1.6, 2.0, 4.1, 4.1 and 12.2 eps (c2's phi - sin phi cancels); sin phi / phi is known to an
// absolute 2 eps near pi in either form (it vanishes there), which is what R needs. The series are
// summed by Estrin's scheme (depth log2(n), not Horner's n - 1: their latency is most of the
// branch's). This gives phi_s = 3.5 in float, double and x86 long double. A long double with a
// longer mantissa (128-bit quad) gets a smaller x_s (its sixteen terms reach its eps sooner) and
// the closed forms above it, where it loses up to ~1000 eps (~1e-31), still far below double's eps.
// cos(phi/2) and sin(phi/2) / phi (to_quaternion) have series of their own by the same rule with
// the cap x = 4 (phi = 2), where their closed forms are accurate again.
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
#include <stdexcept>
#include <string_view>
#include <type_traits>
#include <utility>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "tumble/core/math.hpp"
#include "tumble/core/types.hpp"
#include "tumble/orientation/concept.hpp"
#include "tumble/orientation/detail/rotation_vector_functions.hpp"
#include "tumble/orientation/euler_parameters.hpp"

namespace tumble {

struct RotationVector {
  static constexpr int size = 3;
  static constexpr bool has_constraint = false;
  static constexpr std::string_view name = "RotationVector";
  template <class S> using Coords = Vector3<S>;

  /// What R, G, Gdot vdot and G^-1 share (concept.hpp): v, x = v.v and the coefficient
  /// functions of the file comment (sinc, a, b, c1, c2, d), each evaluated once (from the series,
  /// or one sqrt, sine and cosine at most).
  template <class S> struct Precomputed : detail::rotation_vector::Coefficients<S> {
    Coords<S> v;
    S x;
  };
  template <class S>
  [[nodiscard, gnu::always_inline]] static Precomputed<S> precompute(const Coords<S>& v) {
    Precomputed<S> p;
    p.v = v;
    p.x = v.squaredNorm();
    detail::rotation_vector::Coefficients<S>& c = p;
    if constexpr (std::is_floating_point_v<S>) {
      // Inline for double and float, the series of every canonical v (phi <= pi, and a margin);
      // the closed forms of the rare non-canonical v out of line. AD scalars take the general
      // path, not forced inline (their code is many times larger).
      if (p.x < detail::rotation_vector::limits<S>().series) [[likely]] {
        S a2, b2;
        detail::rotation_vector::remainders(p.x, a2, b2);
        c = detail::rotation_vector::from_remainders(p.x, a2, b2);
      } else {
        c = closed_forms(p.x);
      }
    } else {
      c = detail::rotation_vector::PhiFunctions<S>(p.x).all();
    }
    return p;
  }

 private:
  template <class S>
  [[gnu::noinline, gnu::cold]] static detail::rotation_vector::Coefficients<S> closed_forms(
      const S& x) {
    return detail::rotation_vector::PhiFunctions<S>(x).all();
  }

 public:
  /// R = exp(S(v)) = I + (sin phi / phi) S(v) + a S(v)^2 = (1 - a v.v) I + a v v^T +
  /// (sin phi / phi) S(v)   (body -> inertial; Eq. 1.1).
  template <class S> [[nodiscard]] static Matrix3<S> rotation(const Precomputed<S>& pre) {
    const S diag = S(1) - pre.a * pre.x;
    const Vector3<S> av = pre.a * pre.v;
    const Vector3<S> sv = pre.sinc * pre.v;
    Matrix3<S> r = av * pre.v.transpose();
    r.diagonal().array() += diag;
    r(0, 1) -= sv(2);
    r(1, 0) += sv(2);
    r(0, 2) += sv(1);
    r(2, 0) -= sv(1);
    r(1, 2) -= sv(0);
    r(2, 1) += sv(0);
    return r;
  }
  template <class S> [[nodiscard]] static Matrix3<S> rotation(const Coords<S>& v) {
    return rotation(precompute(v));
  }

  /// G = I - a S(v) + b S(v)^2 = (1 - b v.v) I + b v v^T - a S(v), omega = G vdot in body
  /// components   (Eq. 1.5).
  template <class S> [[nodiscard]] static Matrix3<S> G(const Precomputed<S>& pre) {
    const S diag = S(1) - pre.b * pre.x;
    const Vector3<S> bv = pre.b * pre.v;
    const Vector3<S> av = pre.a * pre.v;
    Matrix3<S> g = bv * pre.v.transpose();
    g.diagonal().array() += diag;
    g(0, 1) += av(2);
    g(1, 0) -= av(2);
    g(0, 2) -= av(1);
    g(2, 0) += av(1);
    g(1, 2) += av(0);
    g(2, 1) -= av(0);
    return g;
  }
  template <class S> [[nodiscard]] static Matrix3<S> G(const Coords<S>& v) {
    return G(precompute(v));
  }

  /// omega = G vdot = vdot - a v x vdot + b v x (v x vdot)   (Eq. 1.5).
  template <class S>
  [[nodiscard, gnu::always_inline]] static Vector3<S> omega(const Precomputed<S>& pre,
                                                            const Coords<S>& vdot) {
    const Vector3<S> u = pre.v.cross(vdot);
    const Vector3<S> vu = pre.v.cross(u);
    return vdot - pre.a * u + pre.b * vu;
  }
  template <class S>
  [[nodiscard]] static Vector3<S> omega(const Coords<S>& v, const Coords<S>& vdot) {
    return detail::with_precomputed<RotationVector>(
        [](const auto& pre, const auto& vd) { return omega(pre, vd); }, v, vdot);
  }

  /// Gdot vdot = -adot v x vdot + bdot v x (v x vdot) + b vdot x (v x vdot), with
  /// adot = (v.vdot) c1 and bdot = (v.vdot) c2   (Eq. 1.10).
  template <class S>
  [[nodiscard, gnu::always_inline]] static Vector3<S> Gdot_thetadot(const Precomputed<S>& pre,
                                                                    const Coords<S>& vdot) {
    const S vvd = pre.v.dot(vdot);
    const S k1 = -vvd * pre.c1;
    const S k2 = vvd * pre.c2;
    const Vector3<S> u = pre.v.cross(vdot);
    const Vector3<S> vu = pre.v.cross(u);
    const Vector3<S> du = vdot.cross(u);
    return k1 * u + k2 * vu + pre.b * du;
  }
  template <class S>
  [[nodiscard]] static Vector3<S> Gdot_thetadot(const Coords<S>& v, const Coords<S>& vdot) {
    return detail::with_precomputed<RotationVector>(
        [](const auto& pre, const auto& vd) { return Gdot_thetadot(pre, vd); }, v, vdot);
  }

  /// vdot = G^-1 omega = omega + 1/2 v x omega + d v x (v x omega).
  /// \warning Not finite at phi = 2 pi k, k >= 1 (the singular attitudes of the chart).
  template <class S>
  [[nodiscard, gnu::always_inline]] static Coords<S> thetadot(const Precomputed<S>& pre,
                                                              const Vector3<S>& omega) {
    const Vector3<S> u = pre.v.cross(omega);
    const Vector3<S> vu = pre.v.cross(u);
    return omega + S(0.5) * u + pre.d * vu;
  }
  template <class S>
  [[nodiscard]] static Coords<S> thetadot(const Coords<S>& v, const Vector3<S>& omega) {
    return detail::with_precomputed<RotationVector>(
        [](const auto& pre, const auto& w) { return thetadot(pre, w); }, v, omega);
  }

  /// vddot = G^-1 (alpha - Gdot vdot)   (Eq. 1.10 solved for the parameter accelerations).
  template <class S>
  [[nodiscard, gnu::always_inline]] static Coords<S> thetaddot(const Precomputed<S>& pre,
                                                               const Coords<S>& vdot,
                                                               const Vector3<S>& alpha) {
    return thetadot(pre, Vector3<S>(alpha - Gdot_thetadot(pre, vdot)));
  }
  template <class S>
  [[nodiscard]] static Coords<S> thetaddot(const Coords<S>& v, const Coords<S>& vdot,
                                           const Vector3<S>& alpha) {
    return detail::with_precomputed<RotationVector>(
        [](const auto& pre, const auto& vd, const auto& a) { return thetaddot(pre, vd, a); }, v,
        vdot, alpha);
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
