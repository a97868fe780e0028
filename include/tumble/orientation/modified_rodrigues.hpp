#pragma once
// Modified Rodrigues parameters (MRP): s = n tan(phi/4) for the rotation by the angle phi about
// the unit axis n, with their shadow set.
//
// Reference: Chapter 1, "Rigid body" (the "reference chapter"), Sec. 1.1:
// R (Eq. 1.1), G with omega = G thetadot (Eq. 1.5), the product Gdot thetadot (Eq. 1.10).
// The kinematics follow H. Schaub and J. L. Junkins, "Analytical Mechanics of Space Systems",
// Sec. 3.8 (their direction cosine matrix [BN] maps inertial to body components and is R^T here).
//
// Conventions (docs/conventions.md): R maps body components to inertial ones, r_F = R r_f, and
// omega is the body's angular velocity in BODY components, S(omega) = R^T Rdot. With the unit
// quaternion (e0, e) = (cos(phi/2), n sin(phi/2)), s = e / (1 + e0), and with ss = s.s
//     R     = I + (8 S(s)^2 + 4 (1 - ss) S(s)) / (1 + ss)^2                        (Eq. 1.1)
//     G     = 4 / (1 + ss)^2 [(1 - ss) I - 2 S(s) + 2 s s^T],   omega = G sdot     (Eq. 1.5)
//     G^-1  = 1/4 [(1 - ss) I + 2 S(s) + 2 s s^T]             (B = 4 G^-1 has B^T B = (1 + ss)^2 I)
//     Gdot sdot = -4 (s.sdot) / (1 + ss) omega + 8 |sdot|^2 s / (1 + ss)^2         (Eq. 1.10)
// (from G = c M, c = 4 / (1 + ss)^2, M = (1 - ss) I - 2 S(s) + 2 s s^T: cdot / c = -4 s.sdot /
// (1 + ss), and Mdot sdot = -2 (s.sdot) sdot - 2 sdot x sdot + 2 (s.sdot) sdot + 2 |sdot|^2 s).
// Every formula is rational in s: no trigonometry and no small-angle branch.
//
// The shadow set s^S = -s / (s.s) describes the same attitude (it is the MRP of the quaternion
// -q: the rotation by phi - 2 pi about n). |s| <= 1 exactly when phi <= pi, so switching to the
// shadow set whenever |s| > 1 keeps every attitude at least pi away from the singularity.
// Because s and s^S describe the same R(t), they have the same omega; the shadow set's rate is
// the time derivative of s^S(s(t)):
//     sdot^S = -sdot / (s.s) + 2 (s.sdot) s / (s.s)^2   ( = G(s^S)^-1 omega ).
//
// Singular attitudes: phi -> 2 pi (the identity reached the long way round), where |s| -> infinity
// and G -> 0. singularity_distance() = 2 pi - phi with phi = 4 atan|s|, computed as 4 atan(1/|s|)
// for |s| > 1 so that it keeps full relative accuracy near the singularity.
//
// \warning s and shadow(s) are the SAME attitude: compare attitudes through rotation() or
//          canonical(), never by comparing MRP vectors.
// \warning canonical() switches to the shadow set when |s| > 1. A state [s; sdot] that is switched
//          needs its rate switched too: use shadow_rate(s, sdot), not sdot.
// \warning from_quaternion() and from_rotation() return the set with |s| <= 1.

#include <cmath>
#include <stdexcept>
#include <string_view>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "tumble/core/math.hpp"
#include "tumble/core/types.hpp"
#include "tumble/orientation/concept.hpp"
#include "tumble/orientation/euler_parameters.hpp"

namespace tumble {

struct ModifiedRodriguesParameters {
  static constexpr int size = 3;
  static constexpr bool has_constraint = false;
  static constexpr std::string_view name = "ModifiedRodriguesParameters";
  template <class S> using Coords = Vector3<S>;

  /// What R, G, Gdot sdot share (concept.hpp): s, s.s and 1 / (1 + s.s).
  template <class S> struct Precomputed {
    Coords<S> s;
    S ss, inv;
  };
  template <class S> [[nodiscard]] static Precomputed<S> precompute(const Coords<S>& s) {
    const S ss = s.squaredNorm();
    const S inv = S(1) / (S(1) + ss);
    return {s, ss, inv};
  }

  /// R = I + (8 S(s)^2 + 4 (1 - s.s) S(s)) / (1 + s.s)^2
  ///   = (1 - 8 s.s k) I + 8 k s s^T + 4 (1 - s.s) k S(s),  k = 1 / (1 + s.s)^2
  /// (body -> inertial; Eq. 1.1).
  template <class S> [[nodiscard]] static Matrix3<S> rotation(const Precomputed<S>& pre) {
    const S k = pre.inv * pre.inv;
    const S k8 = S(8) * k;
    const S d = S(1) - k8 * pre.ss;
    const S f = S(4) * (S(1) - pre.ss) * k;
    const Vector3<S> fs = f * pre.s;
    const Vector3<S> ks = k8 * pre.s;
    Matrix3<S> r = ks * pre.s.transpose();
    r.diagonal().array() += d;
    r(0, 1) -= fs(2);
    r(1, 0) += fs(2);
    r(0, 2) += fs(1);
    r(2, 0) -= fs(1);
    r(1, 2) -= fs(0);
    r(2, 1) += fs(0);
    return r;
  }
  template <class S> [[nodiscard]] static Matrix3<S> rotation(const Coords<S>& s) {
    return rotation(precompute(s));
  }

  /// G = 4 / (1 + s.s)^2 [(1 - s.s) I - 2 S(s) + 2 s s^T], omega = G sdot   (Eq. 1.5).
  template <class S> [[nodiscard]] static Matrix3<S> G(const Precomputed<S>& pre) {
    const S c = S(4) * pre.inv * pre.inv;
    const Vector3<S>& s = pre.s;
    const Matrix3<S> m =
        (S(1) - pre.ss) * Matrix3<S>::Identity() - S(2) * skew(s) + S(2) * (s * s.transpose());
    return c * m;
  }
  template <class S> [[nodiscard]] static Matrix3<S> G(const Coords<S>& s) {
    return G(precompute(s));
  }

  /// omega = G sdot = 4 / (1 + s.s)^2 [(1 - s.s) sdot - 2 s x sdot + 2 (s.sdot) s]   (Eq. 1.5).
  template <class S>
  [[nodiscard]] static Vector3<S> omega(const Precomputed<S>& pre, const Coords<S>& sdot) {
    const Vector3<S>& s = pre.s;
    const S c = S(4) * pre.inv * pre.inv;
    const S one_minus = S(1) - pre.ss;
    const S ssd2 = S(2) * s.dot(sdot);
    const Vector3<S> m = one_minus * sdot - S(2) * s.cross(sdot) + ssd2 * s;
    return c * m;
  }
  template <class S>
  [[nodiscard]] static Vector3<S> omega(const Coords<S>& s, const Coords<S>& sdot) {
    return detail::with_precomputed<ModifiedRodriguesParameters>(
        [](const auto& pre, const auto& sd) { return omega(pre, sd); }, s, sdot);
  }

  /// Gdot sdot = -4 (s.sdot) / (1 + s.s) omega + 8 |sdot|^2 s / (1 + s.s)^2   (Eq. 1.10).
  template <class S>
  [[nodiscard]] static Vector3<S> Gdot_thetadot(const Precomputed<S>& pre, const Coords<S>& sdot) {
    // Scalars are combined from named (plain) values: for AD scalars, a product of two constants
    // kept as an expression cannot be resized to meet a variable's derivatives.
    const S f = S(-4) * pre.s.dot(sdot) * pre.inv;
    const S g = S(8) * sdot.squaredNorm() * pre.inv * pre.inv;
    return f * omega(pre, sdot) + g * pre.s;
  }
  template <class S>
  [[nodiscard]] static Vector3<S> Gdot_thetadot(const Coords<S>& s, const Coords<S>& sdot) {
    return detail::with_precomputed<ModifiedRodriguesParameters>(
        [](const auto& pre, const auto& sd) { return Gdot_thetadot(pre, sd); }, s, sdot);
  }

  /// sdot = 1/4 [(1 - s.s) I + 2 S(s) + 2 s s^T] omega = G^-1 omega.
  template <class S>
  [[nodiscard]] static Coords<S> thetadot(const Precomputed<S>& pre, const Vector3<S>& omega) {
    const Vector3<S>& s = pre.s;
    const S one_minus = S(1) - pre.ss;
    const S sw2 = S(2) * s.dot(omega);
    return S(0.25) * (one_minus * omega + S(2) * s.cross(omega) + sw2 * s);
  }
  template <class S>
  [[nodiscard]] static Coords<S> thetadot(const Coords<S>& s, const Vector3<S>& omega) {
    return detail::with_precomputed<ModifiedRodriguesParameters>(
        [](const auto& pre, const auto& w) { return thetadot(pre, w); }, s, omega);
  }

  /// sddot = G^-1 (alpha - Gdot sdot)   (Eq. 1.10 solved for the parameter accelerations).
  template <class S>
  [[nodiscard]] static Coords<S> thetaddot(const Precomputed<S>& pre, const Coords<S>& sdot,
                                           const Vector3<S>& alpha) {
    return thetadot(pre, Vector3<S>(alpha - Gdot_thetadot(pre, sdot)));
  }
  template <class S>
  [[nodiscard]] static Coords<S> thetaddot(const Coords<S>& s, const Coords<S>& sdot,
                                           const Vector3<S>& alpha) {
    return detail::with_precomputed<ModifiedRodriguesParameters>(
        [](const auto& pre, const auto& sd, const auto& a) { return thetaddot(pre, sd, a); }, s,
        sdot, alpha);
  }

  /// Through the quaternion of Shepperd's method (EulerParameters::from_rotation, e0 >= 0), so
  /// |s| <= 1.
  template <class S> [[nodiscard]] static Coords<S> from_rotation(const Matrix3<S>& r) {
    return from_quaternion(EulerParameters::to_quaternion(EulerParameters::from_rotation(r)));
  }

  /// q = (1 - s.s, 2 s) / (1 + s.s); e0 >= 0 exactly when |s| <= 1.
  template <class S> [[nodiscard]] static Eigen::Quaternion<S> to_quaternion(const Coords<S>& s) {
    const S ss = s.squaredNorm();
    const S f = S(1) / (S(1) + ss);
    const S f2 = S(2) * f;
    return Eigen::Quaternion<S>((S(1) - ss) * f, f2 * s(0), f2 * s(1), f2 * s(2));  // w-first
  }

  /// s = e / (|q| + e0) for the sign of q with e0 >= 0, so |s| <= 1 (for a unit quaternion this
  /// is e / (1 + e0); dividing by |q| makes it independent of the norm, so q need not be
  /// normalized).
  /// \throws std::domain_error for q = 0, which is no attitude.
  template <class S> [[nodiscard]] static Coords<S> from_quaternion(const Eigen::Quaternion<S>& q) {
    using std::sqrt;
    const S qq = q.coeffs().squaredNorm();
    if (!(detail::value(qq) > 0)) {
      throw std::domain_error("ModifiedRodriguesParameters: the zero quaternion is no attitude");
    }
    const S n = sqrt(qq);
    // e0 >= 0 keeps the denominator >= |q|: no cancellation, and |s| <= 1.
    S f;
    if (detail::value(q.w()) >= 0) {
      f = S(1) / (n + q.w());
    } else {
      f = S(-1) / (n - q.w());
    }
    return Coords<S>(f * q.x(), f * q.y(), f * q.z());
  }

  /// 2 pi - phi with phi = 4 atan|s| in [0, 2 pi): the angle to the nearest singular attitude.
  /// For |s| > 1 it is evaluated as 4 atan(1 / |s|), which does not cancel near the singularity.
  /// At s = 0 it returns 2 pi without taking sqrt(0) (whose AD derivative is not finite; the
  /// distance is not differentiable there anyway).
  template <class S> [[nodiscard]] static S singularity_distance(const Coords<S>& s) {
    using std::sqrt;
    const S two_pi = S(2) * detail::pi<S>();  // named: AD may need to resize its derivatives
    const S ss = s.squaredNorm();
    if (detail::value(ss) == 0) {
      return two_pi;
    }
    const S n = sqrt(ss);
    if (detail::value(n) <= 1) {
      return two_pi - S(4) * detail::atan<S>(n);
    }
    return S(4) * detail::atan<S>(S(1) / n);
  }

  /// The shadow set -s / (s.s): the same attitude (R(shadow(s)) = R(s)), the other way round.
  /// \throws std::domain_error for s = 0, whose shadow (the rotation by 2 pi) is at infinity.
  template <class S> [[nodiscard]] static Coords<S> shadow(const Coords<S>& s) {
    const S ss = s.squaredNorm();
    if (!(detail::value(ss) > 0)) {
      throw std::domain_error(
          "ModifiedRodriguesParameters: s = 0 has no shadow set (it would be at infinity)");
    }
    return (S(-1) / ss) * s;
  }

  /// The rate of the shadow set for the same angular velocity: the time derivative of
  /// -s / (s.s), sdot^S = -sdot / (s.s) + 2 (s.sdot) s / (s.s)^2. Equal to
  /// thetadot(shadow(s), G(s) sdot).
  /// \throws std::domain_error for s = 0.
  template <class S>
  [[nodiscard]] static Coords<S> shadow_rate(const Coords<S>& s, const Coords<S>& sdot) {
    const S ss = s.squaredNorm();
    if (!(detail::value(ss) > 0)) {
      throw std::domain_error(
          "ModifiedRodriguesParameters: s = 0 has no shadow set (it would be at infinity)");
    }
    const S inv = S(1) / ss;
    return (S(2) * s.dot(sdot) * inv * inv) * s - inv * sdot;
  }

  /// The set with |s| <= 1 (phi <= pi): s itself, or its shadow set when |s| > 1. At |s| = 1
  /// (phi = pi) both sets have norm 1 and s is kept.
  template <class S> [[nodiscard]] static Coords<S> canonical(const Coords<S>& s) {
    if (detail::value(s.squaredNorm()) > 1) {
      return shadow(s);
    }
    return s;
  }
};

static_assert(Orientation<ModifiedRodriguesParameters>);

}  // namespace tumble
