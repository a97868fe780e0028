#pragma once
// Rodrigues parameters (the Gibbs vector): g = n tan(phi/2) for the rotation by the angle phi
// about the unit axis n.
//
// Reference: Chapter 1, "Rigid body" (the "reference chapter"), Sec. 1.1:
// R (Eq. 1.1), G with omega = G thetadot (Eq. 1.5), the product Gdot thetadot (Eq. 1.10).
//
// Conventions (docs/conventions.md): R maps body components to inertial ones, r_F = R r_f, and
// omega is the body's angular velocity in BODY components, S(omega) = R^T Rdot. With the unit
// quaternion (e0, e) = (cos(phi/2), n sin(phi/2)), g = e / e0, and with gg = g.g
//     R     = I + 2 / (1 + gg) (S(g) + S(g)^2)                                    (Eq. 1.1)
//     G     = 2 / (1 + gg) (I - S(g)),          omega = G gdot                      (Eq. 1.5)
//     G^-1  = 1/2 (I + S(g) + g g^T),           gdot  = G^-1 omega
//     Gdot gdot = -(2 g.gdot / (1 + gg)) omega                                      (Eq. 1.10)
// (from G = c (I - S(g)) with c = 2 / (1 + gg): Gdot gdot = cdot (I - S(g)) gdot - c gdot x gdot
// = (cdot / c) omega, and cdot / c = -2 g.gdot / (1 + gg)). Every formula is rational in g: no
// trigonometry, no small-angle branch, exact at g = 0.
//
// Singular attitudes: the rotations by phi = pi (180 degrees), where e0 = 0 and |g| -> infinity.
// G^-1 grows like |g|^2 there, i.e. a finite omega needs an unbounded gdot. Every attitude off
// that set has exactly one Gibbs vector (q and -q give the same g = e / e0), so canonical() is
// the identity. singularity_distance() = pi - phi with phi = 2 atan|g|, computed
// as 2 atan(1 / |g|) for |g| > 1 so that it keeps full relative accuracy close to the singularity.
//
// \warning Near 180 degrees g is huge and ill-conditioned: a rotation by 179.9999 degrees has
//          |g| ~ 1.1e6, an absolute rounding error eps in e0 is a relative error ~eps |g| in g,
//          and gdot = G^-1 omega grows like |g|^2. A scene re-centers the chart well before, at
//          phi = 90 deg, driven by singularity_distance() (include/tumble/scene/chart.hpp:
//          charts are re-centered before the singularity).
// \warning from_quaternion() and from_rotation() throw NonFiniteError (a std::domain_error)
//          for a rotation by exactly 180 degrees (e0 == 0): it has no Gibbs vector. Arbitrarily
//          close rotations give huge but finite g.

#include <cmath>
#include <string_view>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "tumble/core/errors.hpp"
#include "tumble/core/math.hpp"
#include "tumble/core/types.hpp"
#include "tumble/orientation/concept.hpp"
#include "tumble/orientation/euler_parameters.hpp"

namespace tumble {

struct RodriguesParameters {
  static constexpr int size = 3;
  static constexpr bool has_constraint = false;
  static constexpr std::string_view name = "RodriguesParameters";
  template <class S> using Coords = Vector3<S>;

  /// What R, G, Gdot gdot share (concept.hpp): g, g.g and c = 2 / (1 + g.g).
  template <class S> struct Precomputed {
    Coords<S> g;
    S gg, c;
  };
  template <class S> [[nodiscard]] static Precomputed<S> precompute(const Coords<S>& g) {
    const S gg = g.squaredNorm();
    const S c = S(2) / (S(1) + gg);
    return {g, gg, c};
  }

  /// R = I + c (S(g) + S(g)^2) = (1 - c g.g) I + c g g^T + c S(g), c = 2 / (1 + g.g)
  /// (body -> inertial; Eq. 1.1).
  template <class S> [[nodiscard]] static Matrix3<S> rotation(const Precomputed<S>& pre) {
    const S d = S(1) - pre.c * pre.gg;
    const Vector3<S> cg = pre.c * pre.g;
    Matrix3<S> r = cg * pre.g.transpose();
    r.diagonal().array() += d;
    r(0, 1) -= cg(2);
    r(1, 0) += cg(2);
    r(0, 2) += cg(1);
    r(2, 0) -= cg(1);
    r(1, 2) -= cg(0);
    r(2, 1) += cg(0);
    return r;
  }
  template <class S> [[nodiscard]] static Matrix3<S> rotation(const Coords<S>& g) {
    return rotation(precompute(g));
  }

  /// G = c (I - S(g)), omega = G gdot in body components   (Eq. 1.5).
  template <class S> [[nodiscard]] static Matrix3<S> G(const Precomputed<S>& pre) {
    return pre.c * (Matrix3<S>::Identity() - skew(pre.g));
  }
  template <class S> [[nodiscard]] static Matrix3<S> G(const Coords<S>& g) {
    return G(precompute(g));
  }

  /// omega = G gdot = c (gdot - g x gdot)   (Eq. 1.5).
  template <class S>
  [[nodiscard]] static Vector3<S> omega(const Precomputed<S>& pre, const Coords<S>& gdot) {
    const Vector3<S> u = gdot - pre.g.cross(gdot);
    return pre.c * u;
  }
  template <class S>
  [[nodiscard]] static Vector3<S> omega(const Coords<S>& g, const Coords<S>& gdot) {
    return detail::with_precomputed<RodriguesParameters>(
        [](const auto& pre, const auto& gd) { return omega(pre, gd); }, g, gdot);
  }

  /// Gdot gdot = -(2 g.gdot / (1 + g.g)) G gdot = -(c g.gdot) G gdot   (Eq. 1.10).
  template <class S>
  [[nodiscard]] static Vector3<S> Gdot_thetadot(const Precomputed<S>& pre, const Coords<S>& gdot) {
    const S f = -pre.c * pre.g.dot(gdot);
    return f * omega(pre, gdot);
  }
  template <class S>
  [[nodiscard]] static Vector3<S> Gdot_thetadot(const Coords<S>& g, const Coords<S>& gdot) {
    return detail::with_precomputed<RodriguesParameters>(
        [](const auto& pre, const auto& gd) { return Gdot_thetadot(pre, gd); }, g, gdot);
  }

  /// gdot = 1/2 (I + S(g) + g g^T) omega = G^-1 omega.
  template <class S>
  [[nodiscard]] static Coords<S> thetadot(const Precomputed<S>& pre, const Vector3<S>& omega) {
    const Vector3<S>& g = pre.g;
    const S gw = g.dot(omega);
    return S(0.5) * (omega + g.cross(omega) + gw * g);
  }
  template <class S>
  [[nodiscard]] static Coords<S> thetadot(const Coords<S>& g, const Vector3<S>& omega) {
    return detail::with_precomputed<RodriguesParameters>(
        [](const auto& pre, const auto& w) { return thetadot(pre, w); }, g, omega);
  }

  /// gddot = G^-1 (alpha - Gdot gdot)   (Eq. 1.10 solved for the parameter accelerations).
  template <class S>
  [[nodiscard]] static Coords<S> thetaddot(const Precomputed<S>& pre, const Coords<S>& gdot,
                                           const Vector3<S>& alpha) {
    return thetadot(pre, Vector3<S>(alpha - Gdot_thetadot(pre, gdot)));
  }
  template <class S>
  [[nodiscard]] static Coords<S> thetaddot(const Coords<S>& g, const Coords<S>& gdot,
                                           const Vector3<S>& alpha) {
    return detail::with_precomputed<RodriguesParameters>(
        [](const auto& pre, const auto& gd, const auto& a) { return thetaddot(pre, gd, a); }, g,
        gdot, alpha);
  }

  /// Through the quaternion of Shepperd's method (EulerParameters::from_rotation), which stays
  /// accurate near 180 degrees where vex(R - R^T) / (1 + tr R) would cancel.
  /// \throws NonFiniteError for a rotation by exactly 180 degrees.
  template <class S> [[nodiscard]] static Coords<S> from_rotation(const Matrix3<S>& r) {
    return from_quaternion(EulerParameters::to_quaternion(EulerParameters::from_rotation(r)));
  }

  /// q = (1, g) / sqrt(1 + g.g), with e0 > 0.
  template <class S> [[nodiscard]] static Eigen::Quaternion<S> to_quaternion(const Coords<S>& g) {
    using std::sqrt;
    const S f = S(1) / sqrt(S(1) + g.squaredNorm());
    return Eigen::Quaternion<S>(f, f * g(0), f * g(1), f * g(2));  // w-first constructor
  }

  /// g = e / e0. The ratio does not depend on the sign or the norm of q, so q need not be
  /// normalized.
  /// \throws NonFiniteError when e0 == 0 (a rotation by exactly 180 degrees, or q = 0), or when
  ///         g or g.g overflows (e0 tiny or q huge).
  template <class S> [[nodiscard]] static Coords<S> from_quaternion(const Eigen::Quaternion<S>& q) {
    if (detail::value(q.w()) == 0) {
      throw NonFiniteError(
          "RodriguesParameters: the quaternion has e0 = 0, a rotation by 180 degrees, where the "
          "Gibbs vector n tan(phi/2) is infinite");
    }
    const S f = S(1) / q.w();
    const Coords<S> g(f * q.x(), f * q.y(), f * q.z());
    // g.g is what rotation(), G() and thetadot() use: a g that is finite while g.g overflows
    // (|g| > ~1e154, a rotation within ~1e-154 rad of 180 degrees) would give them inf * 0.
    if (!detail::isfinite(g.squaredNorm())) {  // e0 so small (or q so large) that g overflows
      throw NonFiniteError(
          "RodriguesParameters: the rotation is so close to 180 degrees (or the quaternion so "
          "large) that its Gibbs vector n tan(phi/2), or its squared norm, overflows");
    }
    return g;
  }

  /// pi - phi with phi = 2 atan|g| in [0, pi): the angle to the nearest rotation by 180 degrees.
  /// For |g| > 1 it is evaluated as 2 atan(1 / |g|), which does not cancel near the singularity.
  /// At g = 0 it returns pi without taking sqrt(0) (whose AD derivative is not finite; the
  /// distance is not differentiable there anyway).
  template <class S> [[nodiscard]] static S singularity_distance(const Coords<S>& g) {
    using std::sqrt;
    const S gg = g.squaredNorm();
    if (detail::value(gg) == 0) {
      return detail::pi<S>();
    }
    const S n = sqrt(gg);
    if (detail::value(n) <= 1) {
      return detail::pi<S>() - S(2) * detail::atan<S>(n);
    }
    return S(2) * detail::atan<S>(S(1) / n);
  }

  /// The identity: every attitude off 180 degrees has exactly one Gibbs vector.
  template <class S> [[nodiscard]] static Coords<S> canonical(const Coords<S>& g) { return g; }
};

static_assert(Orientation<RodriguesParameters>);

}  // namespace tumble
