#pragma once
// Euler parameters: the unit quaternion p = (e0, e1, e2, e3), scalar first, Hamilton product.
//
// Reference chapter, Sec. 1.1 (R, G of Eq. 1.5, Gdot thetadot of Eq. 1.10). With
//   L(p) = [ -e | e0 I - S(e) ]   (3 x 4, e = (e1, e2, e3)),
// the body angular velocity is omega = 2 L(p) pdot, so G = 2 L(p). Gdot pdot = 2 L(pdot) pdot is
// identically zero, which is why this set is the cheapest to evaluate. The four coordinates obey
// |p| = 1, hence p.pdot = 0 and p.pddot = -|pdot|^2; G^T I G is singular with null vector p, and
// the accelerations come from the constrained system, never from G^T I G alone.
//
// \warning Scalar first: (e0, e1, e2, e3). Eigen::Quaternion's constructor is also w-first, but
//          its storage (coeffs()) is (x, y, z, w).
// \warning Every function assumes |p| = 1 (the constraint). canonical() normalizes.

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string_view>

#include "tumble/core/math.hpp"
#include "tumble/core/types.hpp"
#include "tumble/orientation/concept.hpp"

namespace tumble {

struct EulerParameters {
  static constexpr int size = 4;
  static constexpr bool has_constraint = true;
  static constexpr std::string_view name = "EulerParameters";
  template <class S> using Coords = Vector4<S>;

  /// L(p) = [-e | e0 I - S(e)], so that omega = 2 L(p) pdot and pdot = 1/2 L(p)^T omega.
  template <class S> [[nodiscard]] static Matrix<S, 3, 4> L(const Coords<S>& p) {
    Matrix<S, 3, 4> l;
    l << -p(1), p(0), p(3), -p(2),  //
        -p(2), -p(3), p(0), p(1),   //
        -p(3), p(2), -p(1), p(0);
    return l;
  }

  /// L(p) v for a 4-vector v, written out: the hot paths (omega = 2 L(p) pdot) then hold no
  /// 3 x 4 matrix in memory (GCC 12 spilled the formed L(p) to the stack before the product).
  template <class S, class V>
  [[nodiscard]] static Vector3<S> L_times(const Coords<S>& p, const V& v) {
    return Vector3<S>(-p(1) * v(0) + p(0) * v(1) + p(3) * v(2) - p(2) * v(3),
                      -p(2) * v(0) - p(3) * v(1) + p(0) * v(2) + p(1) * v(3),
                      -p(3) * v(0) + p(2) * v(1) - p(1) * v(2) + p(0) * v(3));
  }

  /// L(p)^T w for a 3-vector w, written out (see L_times).
  template <class S, class W>
  [[nodiscard]] static Coords<S> Lt_times(const Coords<S>& p, const W& w) {
    return Coords<S>(
        -p(1) * w(0) - p(2) * w(1) - p(3) * w(2), p(0) * w(0) - p(3) * w(1) + p(2) * w(2),
        p(3) * w(0) + p(0) * w(1) - p(1) * w(2), -p(2) * w(0) + p(1) * w(1) + p(0) * w(2));
  }

  /// What the functions of p share (concept.hpp): nothing beyond p, whose products are all
  /// polynomial. The overloads of Precomputed<S> exist so that generic code treats every
  /// parameterization alike.
  template <class S> struct Precomputed { Coords<S> p; };
  template <class S> [[nodiscard]] static Precomputed<S> precompute(const Coords<S>& p) {
    return {p};
  }
  template <class S> [[nodiscard]] static Matrix3<S> rotation(const Precomputed<S>& pre) {
    return rotation(pre.p);
  }
  template <class S> [[nodiscard]] static Matrix<S, 3, 4> G(const Precomputed<S>& pre) {
    return G(pre.p);
  }
  template <class S>
  [[nodiscard]] static Vector3<S> omega(const Precomputed<S>& pre, const Coords<S>& pdot) {
    return omega(pre.p, pdot);
  }
  template <class S>
  [[nodiscard]] static Vector3<S> Gdot_thetadot(const Precomputed<S>& /*pre*/,
                                                const Coords<S>& /*pdot*/) {
    return Vector3<S>::Zero();
  }
  template <class S>
  [[nodiscard]] static Coords<S> thetadot(const Precomputed<S>& pre, const Vector3<S>& omega) {
    return thetadot(pre.p, omega);
  }
  template <class S>
  [[nodiscard]] static Coords<S> thetaddot(const Precomputed<S>& pre, const Coords<S>& pdot,
                                           const Vector3<S>& alpha) {
    return thetaddot(pre.p, pdot, alpha);
  }

  /// R = (e0^2 - e.e) I + 2 e e^T + 2 e0 S(e)   (body -> inertial; Eq. 1.1).
  template <class S> [[nodiscard]] static Matrix3<S> rotation(const Coords<S>& p) {
    const S e0 = p(0), e1 = p(1), e2 = p(2), e3 = p(3);
    const S e00 = e0 * e0, e11 = e1 * e1, e22 = e2 * e2, e33 = e3 * e3;
    const S e01 = e0 * e1, e02 = e0 * e2, e03 = e0 * e3;
    const S e12 = e1 * e2, e13 = e1 * e3, e23 = e2 * e3;
    Matrix3<S> r;
    r << e00 + e11 - e22 - e33, S(2) * (e12 - e03), S(2) * (e13 + e02),  //
        S(2) * (e12 + e03), e00 - e11 + e22 - e33, S(2) * (e23 - e01),   //
        S(2) * (e13 - e02), S(2) * (e23 + e01), e00 - e11 - e22 + e33;
    return r;
  }

  /// G = 2 L(p)   (Eq. 1.5).
  template <class S> [[nodiscard]] static Matrix<S, 3, 4> G(const Coords<S>& p) {
    return S(2) * L(p);
  }

  /// omega = G pdot = 2 L(p) pdot (Eq. 1.5), without forming G.
  template <class S>
  [[nodiscard]] static Vector3<S> omega(const Coords<S>& p, const Coords<S>& pdot) {
    return S(2) * L_times(p, pdot);
  }

  /// Gdot pdot = 2 L(pdot) pdot = 0 for every pdot (Eq. 1.10): callers that know the type skip
  /// it at compile time (see `gdot_vanishes`).
  template <class S>
  [[nodiscard]] static Vector3<S> Gdot_thetadot(const Coords<S>& /*p*/, const Coords<S>& /*pdot*/) {
    return Vector3<S>::Zero();
  }
  static constexpr bool gdot_vanishes = true;

  /// pdot = 1/2 L(p)^T omega: the rate tangent to |p| = 1 (p.pdot = 0).
  template <class S>
  [[nodiscard]] static Coords<S> thetadot(const Coords<S>& p, const Vector3<S>& omega) {
    return S(0.5) * Lt_times(p, omega);
  }

  /// pddot = 1/2 L(p)^T alpha - |pdot|^2 p: the solution of the constrained system
  /// [G^T I G, p; p^T, 0] [pddot; lambda] = [...; -|pdot|^2] for the angular acceleration alpha
  /// (Eq. 1.10 with Gdot pdot = 0, plus the second derivative of p.p = 1).
  template <class S>
  [[nodiscard]] static Coords<S> thetaddot(const Coords<S>& p, const Coords<S>& pdot,
                                           const Vector3<S>& alpha) {
    return S(0.5) * Lt_times(p, alpha) - pdot.squaredNorm() * p;
  }

  /// Shepperd's method (S. W. Shepperd, "Quaternion from rotation matrix", J. Guidance and
  /// Control 1(3), 1978): pivot on the largest of e0^2..e3^2 so the square root never cancels.
  /// Returns e0 >= 0.
  template <class S> [[nodiscard]] static Coords<S> from_rotation(const Matrix3<S>& r) {
    using std::sqrt;
    const S tr = r.trace();
    Coords<S> p;
    // 4 e_k^2 = 1 + 2 R_kk - tr for k = 1..3, and 4 e0^2 = 1 + tr.
    if (tr >= r(0, 0) && tr >= r(1, 1) && tr >= r(2, 2)) {
      const S e0 = S(0.5) * sqrt(S(1) + tr);
      const S f = S(0.25) / e0;
      p << e0, (r(2, 1) - r(1, 2)) * f, (r(0, 2) - r(2, 0)) * f, (r(1, 0) - r(0, 1)) * f;
    } else if (r(0, 0) >= r(1, 1) && r(0, 0) >= r(2, 2)) {
      const S e1 = S(0.5) * sqrt(S(1) + S(2) * r(0, 0) - tr);
      const S f = S(0.25) / e1;
      p << (r(2, 1) - r(1, 2)) * f, e1, (r(0, 1) + r(1, 0)) * f, (r(0, 2) + r(2, 0)) * f;
    } else if (r(1, 1) >= r(2, 2)) {
      const S e2 = S(0.5) * sqrt(S(1) + S(2) * r(1, 1) - tr);
      const S f = S(0.25) / e2;
      p << (r(0, 2) - r(2, 0)) * f, (r(0, 1) + r(1, 0)) * f, e2, (r(1, 2) + r(2, 1)) * f;
    } else {
      const S e3 = S(0.5) * sqrt(S(1) + S(2) * r(2, 2) - tr);
      const S f = S(0.25) / e3;
      p << (r(1, 0) - r(0, 1)) * f, (r(0, 2) + r(2, 0)) * f, (r(1, 2) + r(2, 1)) * f, e3;
    }
    if (p(0) < S(0)) {
      p = -p;
    }
    return p;
  }

  template <class S> [[nodiscard]] static Eigen::Quaternion<S> to_quaternion(const Coords<S>& p) {
    return Eigen::Quaternion<S>(p(0), p(1), p(2), p(3));  // w-first constructor
  }

  template <class S> [[nodiscard]] static Coords<S> from_quaternion(const Eigen::Quaternion<S>& q) {
    return Coords<S>(q.w(), q.x(), q.y(), q.z());
  }

  /// Euler parameters have no singular attitude.
  template <class S> [[nodiscard]] static S singularity_distance(const Coords<S>& /*p*/) {
    return S(std::numeric_limits<decltype(detail::value(S()))>::infinity());
  }

  /// p / |p|. Throws std::domain_error for a zero or non-finite p: there is no attitude to
  /// recover from it.
  template <class S> [[nodiscard]] static Coords<S> canonical(const Coords<S>& p) {
    using std::abs;
    using std::sqrt;
    // Divide by the largest |e_i| first: |p|^2 of a quaternion of norm 1e-170 or 1e170 would
    // underflow or overflow (found by fuzz/orientation.fuzz.cpp). The scale is a constant, so an
    // AD scalar's derivatives are those of p / |p|.
    using V = decltype(detail::value(p(0)));
    V scale = 0;
    for (int i = 0; i < 4; ++i) {
      scale = std::max(scale, V(abs(detail::value(p(i)))));
    }
    if (!(scale > 0) || !std::isfinite(scale)) {
      throw std::domain_error("EulerParameters: cannot normalize a quaternion of zero or "
                              "non-finite norm");
    }
    const Coords<S> q = p / S(scale);
    return q / sqrt(q.squaredNorm());
  }

  /// The holonomic constraint |p|^2 - 1 = 0.
  template <class S> [[nodiscard]] static S constraint(const Coords<S>& p) {
    return p.squaredNorm() - S(1);
  }
};

static_assert(Orientation<EulerParameters>);

}  // namespace tumble
