#pragma once
// Euler angles: the 12 intrinsic (body-fixed) rotation sequences, 6 Tait-Bryan (three different
// axes) and 6 proper Euler (first axis repeated).
//
// Reference: Chapter 1, "Rigid body" (the "reference chapter"), Sec. 1.1:
// R (Eq. 1.1), G with omega = G thetadot (Eq. 1.5), the product Gdot thetadot (Eq. 1.10).
//
// Conventions (docs/conventions.md). Axes are numbered 0 = x, 1 = y, 2 = z; R_a(t) is the active
// rotation by the angle t about the coordinate axis a (R_x(t) = [1 0 0; 0 c -s; 0 s c]).
// EulerAngles<a1, a2, a3> with theta = (t1, t2, t3) is
//     R = R_a1(t1) R_a2(t2) R_a3(t3)                         (body -> inertial, r_F = R r_f),
// i.e. rotate about a1, then about the *new* a2, then about the newest a3. The same R is the
// extrinsic (space-fixed) sequence a3, a2, a1 with the angles (t3, t2, t1). The common aerospace
// yaw-pitch-roll angles are EulerZYX with t1 = yaw, t2 = pitch, t3 = roll.
//
// Body angular velocity (Eq. 1.5): S(omega) = R^T Rdot gives
//     omega = t1dot c1 + t2dot c2 + t3dot c3,   G = [c1 c2 c3],   with
//     c3 = e_a3,   c2 = R_a3(t3)^T e_a2,   c1 = R_a3(t3)^T R_a2(t2)^T e_a1,
// so G depends on t2 and t3 only. Since dc1/dt = t2dot c1 x c2 + t3dot c1 x c3 and
// dc2/dt = t3dot c2 x c3 (and c3 is constant),
//     Gdot thetadot = t1dot t2dot c1 x c2 + t1dot t3dot c1 x c3 + t2dot t3dot c2 x c3  (Eq. 1.10),
// and G^{-1} has the rows (c2 x c3, c3 x c1, c1 x c2) / det G with det G = c1 . (c2 x c3).
// The functions below evaluate these expressions in closed form. With i = a1, j = a2, k the
// remaining axis, eps = +1 when (i, j, k) is an even permutation of (0, 1, 2) and -1 otherwise,
// ctN = cos tN, stN = sin tN, and vector components listed in the order (i, j, k):
//   Tait-Bryan (a3 = k):  c1 = (ct2 ct3, -eps ct2 st3, eps st2),  c2 = (eps st3, ct3, 0),
//                         c3 = e_k,  det G = eps ct2;
//   proper     (a3 = i):  c1 = (ct2, st2 st3, eps st2 ct3),  c2 = (0, ct3, -eps st3),
//                         c3 = e_i,  det G = -st2.
// Every entry is a single product of sines and cosines, and the rows of G^{-1} need no
// subtraction, so G and G^{-1} keep full relative accuracy up to the singularity.
//
// Singular attitudes (G not invertible; t1 and t3 then rotate about the same axis):
//   Tait-Bryan (EulerXYZ, EulerXZY, EulerYXZ, EulerYZX, EulerZXY, EulerZYX):
//       t2 = +-pi/2 (mod 2 pi);
//   proper (EulerXYX, EulerXZX, EulerYXY, EulerYZY, EulerZXZ, EulerZYZ):
//       t2 = 0 or pi (mod 2 pi).
// singularity_distance() measures the distance to that set; thetadot() and thetaddot() divide by
// cos t2 (sin t2), are large but accurate near it and not finite exactly at it. A scene never
// gets there: it re-centers the chart, R = R0 R(theta), 45 deg before (include/tumble/scene/
// chart.hpp: charts are re-centered before the singularity, found by CVODE's root finding).
//
// \warning The sequences are INTRINSIC: EulerAngles<2, 1, 0> (EulerZYX) is R_z(t1) R_y(t2) R_x(t3).
//          A library or paper that calls the same product "XYZ" is using the extrinsic reading;
//          convert with (t1, t2, t3) -> (t3, t2, t1) and the reversed axis order.
// \warning The angles are not wrapped anywhere: canonical() is the identity, so that coordinates
//          integrated in time stay continuous. from_rotation() returns the principal values.

#include <cmath>
#include <string_view>
#include <type_traits>
#include <utility>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "tumble/core/math.hpp"
#include "tumble/core/types.hpp"
#include "tumble/orientation/concept.hpp"

namespace tumble {

namespace detail {

[[nodiscard]] constexpr char euler_axis_letter(int axis) {
  return axis == 0 ? 'X' : (axis == 1 ? 'Y' : 'Z');
}

/// "EulerXYZ" etc., built at compile time (8 letters and a terminating zero).
template <int a1, int a2, int a3>
inline constexpr char euler_angles_name[] = {
    'E', 'u', 'l', 'e', 'r', euler_axis_letter(a1), euler_axis_letter(a2), euler_axis_letter(a3),
    '\0'};

/// A zero with zero derivatives sized like those of x (AD scalars: Eigen's atan2 does not
/// resize an empty derivative vector to match its other argument).
template <class S> [[nodiscard]] S euler_zero_like(const S& x) {
  if constexpr (std::is_arithmetic_v<S>) {
    return S(0);
  } else {
    return S(x * S(0));
  }
}

/// sqrt(x^2 + y^2). std::hypot for arithmetic types; for AD scalars (no hypot) the plain formula,
/// with an exact-zero branch because the derivative of sqrt at 0 is infinite (0 * inf = NaN in
/// the AD derivatives); the norm is not differentiable there anyway, and a zero with zero
/// derivatives keeps the callers' derivatives finite.
template <class S> [[nodiscard]] S euler_hypot(const S& x, const S& y) {
  if constexpr (std::is_arithmetic_v<S>) {
    using std::hypot;
    return hypot(x, y);
  } else {
    using std::sqrt;
    const S n2 = x * x + y * y;
    if (value(n2) == 0) {
      return euler_zero_like(n2);
    }
    return S(sqrt(n2));
  }
}

}  // namespace detail

/// Intrinsic Euler angles R = R_a1(t1) R_a2(t2) R_a3(t3), axes 0 = x, 1 = y, 2 = z.
/// See the file comment for the conventions, the closed forms and the singular attitudes.
/// \warning Intrinsic (body-fixed) sequences; angles in radians.
template <int a1, int a2, int a3> struct EulerAngles {
  static_assert(0 <= a1 && a1 <= 2 && 0 <= a2 && a2 <= 2 && 0 <= a3 && a3 <= 2,
                "EulerAngles: axes are 0 (x), 1 (y) or 2 (z)");
  static_assert(a1 != a2 && a2 != a3,
                "EulerAngles: consecutive axes must differ (a rotation about the same axis twice "
                "is one rotation)");

  static constexpr int size = 3;
  static constexpr bool has_constraint = false;
  static constexpr std::string_view name{detail::euler_angles_name<a1, a2, a3>, 8};
  template <class S> using Coords = Vector3<S>;

  /// The three axes of the sequence.
  static constexpr int axis1 = a1;
  static constexpr int axis2 = a2;
  static constexpr int axis3 = a3;
  /// Tait-Bryan (three different axes) or proper Euler (a3 == a1).
  static constexpr bool is_tait_bryan = (a1 != a3);
  /// Gdot thetadot is not identically zero (compare EulerParameters::gdot_vanishes).
  static constexpr bool gdot_vanishes = false;

 private:
  // i = a1, j = a2, k = the remaining axis; eps = +1 when (i, j, k) is an even permutation.
  static constexpr int kI = a1;
  static constexpr int kJ = a2;
  static constexpr int kK = 3 - a1 - a2;
  static constexpr bool kEven = ((kJ - kI + 3) % 3) == 1;

  /// eps * x, without a multiplication.
  template <class S> [[nodiscard]] static S pm(const S& x) {
    if constexpr (kEven) {
      return x;
    } else {
      return -x;
    }
  }

  /// Left-multiplies m by the elementary rotation R_axis(t) given by c = cos t, s = sin t: only
  /// the two rows other than `axis` change.
  template <int axis, class S> static void rotate_rows(Matrix3<S>& m, const S& c, const S& s) {
    constexpr int b = (axis + 1) % 3;
    constexpr int d = (axis + 2) % 3;
    for (int col = 0; col < 3; ++col) {
      const S mb = m(b, col);
      const S md = m(d, col);
      m(b, col) = c * mb - s * md;
      m(d, col) = s * mb + c * md;
    }
  }

 public:
  /// What R, G, Gdot thetadot and G^{-1} share (concept.hpp): cos and sin of t2 and t3, all that
  /// G, Gdot thetadot and G^{-1} need, and t1, whose cosine and sine only R needs (rotation()
  /// evaluates them, once).
  template <class S> struct Precomputed { S t1, c2, s2, c3, s3; };
  template <class S> [[nodiscard]] static Precomputed<S> precompute(const Coords<S>& theta) {
    using std::cos;
    using std::sin;
    return {theta(0), S(cos(theta(1))), S(sin(theta(1))), S(cos(theta(2))), S(sin(theta(2)))};
  }

 private:
  /// G^{-1} omega (the rows (c2 x c3, c3 x c1, c1 x c2) / det G in closed form).
  template <class S>
  [[nodiscard]] static Coords<S> solve(const Precomputed<S>& t, const Vector3<S>& w) {
    Coords<S> td;
    if constexpr (is_tait_bryan) {
      // G^{-1} rows (cN = cos tN, sN = sin tN, components (i, j, k)):
      //   (c3, -eps s3, 0) / c2,  (eps s3, c3, 0),  (-eps s2 c3, s2 s3, c2) / c2.
      const S u = (t.c3 * w(kI) - pm<S>(t.s3 * w(kJ))) / t.c2;
      td(0) = u;
      td(1) = pm<S>(t.s3 * w(kI)) + t.c3 * w(kJ);
      td(2) = w(kK) - pm<S>(t.s2 * u);
    } else {
      // G^{-1} rows (cN = cos tN, sN = sin tN, components (i, j, k)):
      //   (0, s3, eps c3) / s2,  (0, c3, -eps s3),  (s2, -c2 s3, -eps c2 c3) / s2.
      const S u = (t.s3 * w(kJ) + pm<S>(t.c3 * w(kK))) / t.s2;
      td(0) = u;
      td(1) = t.c3 * w(kJ) - pm<S>(t.s3 * w(kK));
      td(2) = w(kI) - t.c2 * u;
    }
    return td;
  }

  /// Gdot thetadot = t1dot dc1/dt + t2dot dc2/dt (Eq. 1.10), the closed form of
  /// t1dot t2dot c1 x c2 + t1dot t3dot c1 x c3 + t2dot t3dot c2 x c3.
  template <class S>
  [[nodiscard]] static Vector3<S> gdot_td(const Precomputed<S>& t, const Coords<S>& td) {
    const S& d1 = td(0);
    const S& d2 = td(1);
    const S& d3 = td(2);
    Vector3<S> g;
    if constexpr (is_tait_bryan) {
      g(kI) = pm<S>(d2 * d3 * t.c3) - d1 * (d2 * t.s2 * t.c3 + d3 * t.c2 * t.s3);
      g(kJ) = pm<S>(d1 * (d2 * t.s2 * t.s3 - d3 * t.c2 * t.c3)) - d2 * d3 * t.s3;
      g(kK) = pm<S>(d1 * d2 * t.c2);
    } else {
      g(kI) = -(d1 * d2 * t.s2);
      g(kJ) = d1 * (d2 * t.c2 * t.s3 + d3 * t.s2 * t.c3) - d2 * d3 * t.s3;
      g(kK) = pm<S>(d1 * (d2 * t.c2 * t.c3 - d3 * t.s2 * t.s3) - d2 * d3 * t.c3);
    }
    return g;
  }

 public:
  /// R = R_a1(t1) R_a2(t2) R_a3(t3) (Eq. 1.1): R_a3 is written down, then R_a2 and R_a1 are
  /// applied from the left, each touching two rows (no 3 x 3 products with zeros).
  template <class S> [[nodiscard]] static Matrix3<S> rotation(const Precomputed<S>& pre) {
    using std::cos;
    using std::sin;
    Matrix3<S> r = Matrix3<S>::Identity();
    {
      constexpr int b = (a3 + 1) % 3;
      constexpr int d = (a3 + 2) % 3;
      r(b, b) = pre.c3;
      r(b, d) = -pre.s3;
      r(d, b) = pre.s3;
      r(d, d) = pre.c3;
    }
    rotate_rows<a2>(r, pre.c2, pre.s2);
    rotate_rows<a1>(r, S(cos(pre.t1)), S(sin(pre.t1)));
    return r;
  }
  template <class S> [[nodiscard]] static Matrix3<S> rotation(const Coords<S>& theta) {
    return rotation(precompute(theta));
  }

  /// G = [c1 c2 c3] with omega = G thetadot (Eq. 1.5); depends on t2 and t3 only.
  template <class S> [[nodiscard]] static Matrix3<S> G(const Precomputed<S>& t) {
    Matrix3<S> g;
    if constexpr (is_tait_bryan) {
      g(kI, 0) = t.c2 * t.c3;
      g(kJ, 0) = -pm<S>(t.c2 * t.s3);
      g(kK, 0) = pm<S>(t.s2);
      g(kI, 1) = pm<S>(t.s3);
      g(kJ, 1) = t.c3;
      g(kK, 1) = S(0);
      g(kI, 2) = S(0);
      g(kJ, 2) = S(0);
      g(kK, 2) = S(1);
    } else {
      g(kI, 0) = t.c2;
      g(kJ, 0) = t.s2 * t.s3;
      g(kK, 0) = pm<S>(t.s2 * t.c3);
      g(kI, 1) = S(0);
      g(kJ, 1) = t.c3;
      g(kK, 1) = -pm<S>(t.s3);
      g(kI, 2) = S(1);
      g(kJ, 2) = S(0);
      g(kK, 2) = S(0);
    }
    return g;
  }
  template <class S> [[nodiscard]] static Matrix3<S> G(const Coords<S>& theta) {
    return G(precompute(theta));
  }

  /// omega = G thetadot = t1dot c1 + t2dot c2 + t3dot c3 (Eq. 1.5), without the zeros of G.
  template <class S>
  [[nodiscard]] static Vector3<S> omega(const Precomputed<S>& t, const Coords<S>& td) {
    Vector3<S> w;
    if constexpr (is_tait_bryan) {
      const S u = t.c2 * td(0);
      w(kI) = t.c3 * u + pm<S>(t.s3 * td(1));
      w(kJ) = t.c3 * td(1) - pm<S>(t.s3 * u);
      w(kK) = pm<S>(t.s2 * td(0)) + td(2);
    } else {
      const S u = t.s2 * td(0);
      w(kI) = t.c2 * td(0) + td(2);
      w(kJ) = t.s3 * u + t.c3 * td(1);
      w(kK) = pm<S>(t.c3 * u - t.s3 * td(1));
    }
    return w;
  }
  template <class S>
  [[nodiscard]] static Vector3<S> omega(const Coords<S>& theta, const Coords<S>& td) {
    return detail::with_precomputed<EulerAngles>(
        [](const auto& pre, const auto& t) { return omega(pre, t); }, theta, td);
  }

  /// Gdot thetadot (Eq. 1.10).
  template <class S>
  [[nodiscard]] static Vector3<S> Gdot_thetadot(const Precomputed<S>& pre, const Coords<S>& td) {
    return gdot_td(pre, td);
  }
  template <class S>
  [[nodiscard]] static Vector3<S> Gdot_thetadot(const Coords<S>& theta, const Coords<S>& td) {
    return detail::with_precomputed<EulerAngles>(
        [](const auto& pre, const auto& t) { return gdot_td(pre, t); }, theta, td);
  }

  /// thetadot = G^{-1} omega. Divides by cos t2 (Tait-Bryan) or sin t2 (proper): large but
  /// accurate near the singularity, not finite exactly at it.
  template <class S>
  [[nodiscard]] static Coords<S> thetadot(const Precomputed<S>& pre, const Vector3<S>& omega) {
    return solve(pre, omega);
  }
  template <class S>
  [[nodiscard]] static Coords<S> thetadot(const Coords<S>& theta, const Vector3<S>& omega) {
    return detail::with_precomputed<EulerAngles>(
        [](const auto& pre, const auto& w) { return solve(pre, w); }, theta, omega);
  }

  /// thetaddot = G^{-1} (alpha - Gdot thetadot), from G thetaddot = alpha - Gdot thetadot
  /// (Eq. 1.10).
  template <class S>
  [[nodiscard]] static Coords<S> thetaddot(const Precomputed<S>& pre, const Coords<S>& td,
                                           const Vector3<S>& alpha) {
    const Vector3<S> rhs = alpha - gdot_td(pre, td);
    return solve(pre, rhs);
  }
  template <class S>
  [[nodiscard]] static Coords<S> thetaddot(const Coords<S>& theta, const Coords<S>& td,
                                           const Vector3<S>& alpha) {
    return detail::with_precomputed<EulerAngles>(
        [](const auto& pre, const auto& t, const auto& a) { return thetaddot(pre, t, a); }, theta,
        td, alpha);
  }

  /// The principal angles of R, t1, t3 in [-pi, pi] and t2 in [-pi/2, pi/2] (Tait-Bryan) or
  /// [0, pi] (proper). The middle angle comes from row i; the first from column k (Tait-Bryan)
  /// or i (proper); the third from row j of R_i(t1)^T R, which makes the result reproduce R even
  /// at and near gimbal lock, where t1 and t3 are not unique (there t1 is fixed by the rounding
  /// errors of R, and t3 absorbs the rest; exactly at lock, t1 = 0).
  template <class S> [[nodiscard]] static Coords<S> from_rotation(const Matrix3<S>& r) {
    using std::atan2;
    using std::cos;
    using std::sin;
    S x1, y1;  // t1 = atan2(y1, x1)
    Coords<S> theta;
    if constexpr (is_tait_bryan) {
      // With cN = cos tN, sN = sin tN and components (i, j, k):
      // row i = (c2 c3, -eps c2 s3, eps s2), column k = (eps s2, -eps c2 s1, c1 c2).
      theta(1) = atan2(pm<S>(r(kI, kK)), detail::euler_hypot(r(kI, kI), r(kI, kJ)));
      y1 = -pm<S>(r(kJ, kK));
      x1 = r(kK, kK);
    } else {
      // row i = (c2, s2 s3, eps s2 c3), column i = (c2, s1 s2, -eps c1 s2).
      theta(1) = atan2(detail::euler_hypot(r(kI, kJ), r(kI, kK)), r(kI, kI));
      y1 = r(kJ, kI);
      x1 = -pm<S>(r(kK, kI));
    }
    // Exactly at gimbal lock both are exact zeros: atan2 would return 0 or +-pi depending on
    // the signs of the zeros, and its AD derivative would be 0/0. Any t1 reproduces R there.
    if (detail::value(x1) == 0 && detail::value(y1) == 0) {
      theta(0) = detail::euler_zero_like(x1);
    } else {
      theta(0) = atan2(y1, x1);
    }
    // Row j of N = R_i(t1)^T R = R_j(t2) R_a3(t3): (eps s3, c3, 0) (Tait-Bryan) or (0, c3, -eps s3)
    // (proper), in (i, j, k) components.
    const S c1 = cos(theta(0));
    const S s1 = sin(theta(0));
    const S nj_j = c1 * r(kJ, kJ) + pm<S>(s1 * r(kK, kJ));
    if constexpr (is_tait_bryan) {
      const S nj_i = c1 * r(kJ, kI) + pm<S>(s1 * r(kK, kI));
      theta(2) = atan2(pm<S>(nj_i), nj_j);
    } else {
      const S nj_k = c1 * r(kJ, kK) + pm<S>(s1 * r(kK, kK));
      theta(2) = atan2(-pm<S>(nj_k), nj_j);
    }
    return theta;
  }

  /// q = q_a1(t1) q_a2(t2) q_a3(t3) with q_a(t) = (cos t/2, sin t/2 e_a), multiplied out in
  /// closed form. With hN = tN / 2, chN = cos hN, shN = sin hN and the vector part in (i, j, k)
  /// components as in the file comment:
  ///   Tait-Bryan: w = ch1 ch2 ch3 - eps sh1 sh2 sh3,
  ///               v = (sh1 ch2 ch3 + eps ch1 sh2 sh3, ch1 sh2 ch3 - eps sh1 ch2 sh3,
  ///                    ch1 ch2 sh3 + eps sh1 sh2 ch3);
  ///   proper:     w = ch2 cos(h1 + h3),
  ///               v = (ch2 sin(h1 + h3), sh2 cos(h1 - h3), eps sh2 sin(h1 - h3)).
  /// Exact (no matrix in between); not sign-normalized (w may be negative).
  template <class S>
  [[nodiscard]] static Eigen::Quaternion<S> to_quaternion(const Coords<S>& theta) {
    using std::cos;
    using std::sin;
    const S half = S(0.5);
    Vector3<S> v;
    S w;
    if constexpr (is_tait_bryan) {
      const S h1 = half * theta(0), h2 = half * theta(1), h3 = half * theta(2);
      const S c1 = cos(h1), s1 = sin(h1), c2 = cos(h2), s2 = sin(h2), c3 = cos(h3), s3 = sin(h3);
      w = c1 * c2 * c3 - pm<S>(s1 * s2 * s3);
      v(kI) = s1 * c2 * c3 + pm<S>(c1 * s2 * s3);
      v(kJ) = c1 * s2 * c3 - pm<S>(s1 * c2 * s3);
      v(kK) = c1 * c2 * s3 + pm<S>(s1 * s2 * c3);
    } else {
      const S h2 = half * theta(1);
      const S p = half * (theta(0) + theta(2));
      const S m = half * (theta(0) - theta(2));
      const S c2 = cos(h2), s2 = sin(h2);
      w = c2 * cos(p);
      v(kI) = c2 * sin(p);
      v(kJ) = s2 * cos(m);
      v(kK) = pm<S>(s2 * sin(m));
    }
    return Eigen::Quaternion<S>(w, v(0), v(1), v(2));  // w-first constructor
  }

  /// Through the rotation matrix. Assumes |q| = 1.
  template <class S> [[nodiscard]] static Coords<S> from_quaternion(const Eigen::Quaternion<S>& q) {
    return from_rotation(Matrix3<S>(q.toRotationMatrix()));
  }

  /// Distance in rad from the middle angle, wrapped to (-pi, pi], to the nearest singular value:
  /// | |t2| - pi/2 | (Tait-Bryan), min(|t2|, pi - |t2|) (proper). In [0, pi/2].
  template <class S> [[nodiscard]] static S singularity_distance(const Coords<S>& theta) {
    using std::abs;
    using std::ceil;
    using V = decltype(detail::value(std::declval<S>()));
    const V pi_v = detail::pi<V>();
    // Wrap to (-pi, pi] with an integer multiple of 2 pi computed on the value (AD scalars have
    // no ceil), so the derivative of the wrapped angle is that of t2.
    const V turns = ceil((detail::value(theta(1)) - pi_v) / (V(2) * pi_v));
    const S w = abs(theta(1) - S(turns * (V(2) * pi_v)));
    if constexpr (is_tait_bryan) {
      return abs(w - S(pi_v / V(2)));
    } else {
      const S other = S(pi_v) - w;
      return detail::value(other) < detail::value(w) ? other : w;
    }
  }

  /// The identity: Euler angles have no redundancy to remove, and wrapping the angles would make
  /// integrated coordinates jump.
  template <class S> [[nodiscard]] static Coords<S> canonical(const Coords<S>& theta) {
    return theta;
  }
};

// Tait-Bryan sequences (three different axes); singular at t2 = +-pi/2.
using EulerXYZ = EulerAngles<0, 1, 2>;
using EulerXZY = EulerAngles<0, 2, 1>;
using EulerYXZ = EulerAngles<1, 0, 2>;
using EulerYZX = EulerAngles<1, 2, 0>;
using EulerZXY = EulerAngles<2, 0, 1>;
using EulerZYX = EulerAngles<2, 1, 0>;
// Proper Euler sequences (first axis repeated); singular at t2 = 0 and pi.
using EulerXYX = EulerAngles<0, 1, 0>;
using EulerXZX = EulerAngles<0, 2, 0>;
using EulerYXY = EulerAngles<1, 0, 1>;
using EulerYZY = EulerAngles<1, 2, 1>;
using EulerZXZ = EulerAngles<2, 0, 2>;
using EulerZYZ = EulerAngles<2, 1, 2>;

static_assert(Orientation<EulerXYZ>);
static_assert(Orientation<EulerXZY>);
static_assert(Orientation<EulerYXZ>);
static_assert(Orientation<EulerYZX>);
static_assert(Orientation<EulerZXY>);
static_assert(Orientation<EulerXYX>);
static_assert(Orientation<EulerXZX>);
static_assert(Orientation<EulerYXY>);
static_assert(Orientation<EulerYZY>);
static_assert(Orientation<EulerZXZ>);
static_assert(Orientation<EulerZYX>);
static_assert(Orientation<EulerZYZ>);
static_assert(EulerZYX::name == "EulerZYX" && EulerXYX::name == "EulerXYX");

}  // namespace tumble
