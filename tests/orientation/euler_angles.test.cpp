// Tests of include/tumble/orientation/euler_angles.hpp: the 12 intrinsic Euler angle sequences.
//
// Every expected value comes from an independent source: products of Eigen::AngleAxis rotations
// (R, and the columns c1, c2, c3 of G as R_a3^T R_a2^T e_a1, R_a3^T e_a2, e_a3), the cross-product
// forms of Gdot thetadot and G^{-1} (evaluated in long double from the AngleAxis columns), central
// finite differences with Richardson extrapolation, Eigen's AutoDiffScalar, and closed-form
// values of the distance to gimbal lock. Reference chapter: Chapter 1, "Rigid
// body", Eqs. (1.1), (1.5), (1.10).

#include "tumble/orientation/euler_angles.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <unsupported/Eigen/AutoDiff>

#include "support/catch.hpp"

// Explicit instantiation of every sequence (members no test calls still compile).
template struct tumble::EulerAngles<0, 1, 2>;
template struct tumble::EulerAngles<0, 2, 1>;
template struct tumble::EulerAngles<1, 0, 2>;
template struct tumble::EulerAngles<1, 2, 0>;
template struct tumble::EulerAngles<2, 0, 1>;
template struct tumble::EulerAngles<2, 1, 0>;
template struct tumble::EulerAngles<0, 1, 0>;
template struct tumble::EulerAngles<0, 2, 0>;
template struct tumble::EulerAngles<1, 0, 1>;
template struct tumble::EulerAngles<1, 2, 1>;
template struct tumble::EulerAngles<2, 0, 2>;
template struct tumble::EulerAngles<2, 1, 2>;

namespace {

using tumble::Matrix3;
using tumble::Vector3;
using AD = Eigen::AutoDiffScalar<Eigen::VectorXd>;
using Vector3ld = Eigen::Matrix<long double, 3, 1>;
using Matrix3ld = Eigen::Matrix<long double, 3, 3>;

using AllEulerAngles =
    std::tuple<tumble::EulerXYZ, tumble::EulerXZY, tumble::EulerYXZ, tumble::EulerYZX,
               tumble::EulerZXY, tumble::EulerZYX, tumble::EulerXYX, tumble::EulerXZX,
               tumble::EulerYXY, tumble::EulerYZY, tumble::EulerZXZ, tumble::EulerZYZ>;

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr float kEpsF = std::numeric_limits<float>::epsilon();
const double kPi = std::acos(-1.0);

// ---- independent references ---------------------------------------------------------------------

template <class T> Matrix3<T> axis_rotation(int axis, T angle) {
  return Eigen::AngleAxis<T>(angle, Vector3<T>::Unit(axis)).toRotationMatrix();
}

/// R_a1(t1) R_a2(t2) R_a3(t3) from three Eigen::AngleAxis rotations.
template <class P, class T> Matrix3<T> reference_rotation(const Vector3<T>& th) {
  return axis_rotation<T>(P::axis1, th(0)) * axis_rotation<T>(P::axis2, th(1)) *
         axis_rotation<T>(P::axis3, th(2));
}

/// c1 = R_a3^T R_a2^T e_a1, c2 = R_a3^T e_a2, c3 = e_a3 (from S(omega) = R^T Rdot).
template <class P, class T> struct ReferenceFrame {
  Vector3<T> c1, c2, c3;
  explicit ReferenceFrame(const Vector3<T>& th) {
    const Matrix3<T> r3t = axis_rotation<T>(P::axis3, th(2)).transpose();
    const Matrix3<T> r2t = axis_rotation<T>(P::axis2, th(1)).transpose();
    c3 = Vector3<T>::Unit(P::axis3);
    c2 = r3t * Vector3<T>::Unit(P::axis2);
    c1 = r3t * (r2t * Vector3<T>::Unit(P::axis1));
  }
  Matrix3<T> G() const {
    Matrix3<T> g;
    g << c1, c2, c3;
    return g;
  }
  /// t1d t2d c1 x c2 + t1d t3d c1 x c3 + t2d t3d c2 x c3.
  Vector3<T> gdot_td(const Vector3<T>& td) const {
    return td(0) * td(1) * c1.cross(c2) + td(0) * td(2) * c1.cross(c3) +
           td(1) * td(2) * c2.cross(c3);
  }
  /// Rows (c2 x c3, c3 x c1, c1 x c2) / (c1 . (c2 x c3)).
  Matrix3<T> G_inverse() const {
    const T det = c1.dot(c2.cross(c3));
    Matrix3<T> gi;
    gi.row(0) = c2.cross(c3).transpose() / det;
    gi.row(1) = c3.cross(c1).transpose() / det;
    gi.row(2) = c1.cross(c2).transpose() / det;
    return gi;
  }
};

template <class Derived> double max_abs(const Eigen::MatrixBase<Derived>& m) {
  return static_cast<double>(m.cwiseAbs().maxCoeff());
}

/// The middle angle(s) where the sequence is singular, and the sign choice of a nearby one.
template <class P> std::vector<double> lock_angles() {
  if constexpr (P::is_tait_bryan) {
    return {kPi / 2, -kPi / 2};
  } else {
    return {0.0, kPi};
  }
}

struct Random {
  std::mt19937_64 gen{20240611u};
  double uniform(double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(gen);
  }
  Eigen::Vector3d vector(double lo, double hi) {
    const double x = uniform(lo, hi);
    const double y = uniform(lo, hi);
    const double z = uniform(lo, hi);
    return Eigen::Vector3d(x, y, z);
  }
  /// Angles with the middle one in the principal range, at least `margin` from the singularity.
  template <class P> Eigen::Vector3d principal_angles(double margin) {
    const double t1 = uniform(-kPi, kPi);
    const double t3 = uniform(-kPi, kPi);
    const double t2 = P::is_tait_bryan ? uniform(-kPi / 2 + margin, kPi / 2 - margin)
                                       : uniform(margin, kPi - margin);
    return Eigen::Vector3d(t1, t2, t3);
  }
  Eigen::Quaterniond unit_quaternion() {
    Eigen::Vector4d v;
    do {
      v << uniform(-1, 1), uniform(-1, 1), uniform(-1, 1), uniform(-1, 1);
    } while (v.norm() < 0.1 || v.norm() > 1.0);
    v.normalize();
    return Eigen::Quaterniond(v(0), v(1), v(2), v(3));
  }
};

/// Richardson-extrapolated central difference of f along the direction d at x:
/// (4 D(h/2) - D(h)) / 3 with D(h) = (f(x + h d) - f(x - h d)) / (2 h); truncation error
/// O(h^4 |d|^5 |f^(5)|), rounding error about 3 eps |f| / h.
template <class F>
auto richardson(const F& f, const Eigen::Vector3d& x, const Eigen::Vector3d& d, double h) {
  const auto central = [&](double step) {
    const Eigen::Vector3d xp = x + step * d;
    const Eigen::Vector3d xm = x - step * d;
    return ((f(xp) - f(xm)) / (2 * step)).eval();
  };
  return ((4 * central(h / 2) - central(h)) / 3).eval();
}

/// Derivative of an AD scalar with respect to seed k (an empty derivative vector means zero).
double derivative(const AD& x, Eigen::Index k) {
  return x.derivatives().size() == 0 ? 0.0 : x.derivatives()(k);
}

Eigen::Matrix<AD, 3, 1> seeded(const Eigen::Vector3d& th) {
  Eigen::Matrix<AD, 3, 1> t;
  for (Eigen::Index k = 0; k < 3; ++k) {
    t(k) = AD(th(k), 3, static_cast<int>(k));
  }
  return t;
}

template <class Derived> Eigen::Matrix3d values(const Eigen::MatrixBase<Derived>& m) {
  Eigen::Matrix3d v;
  for (Eigen::Index r = 0; r < 3; ++r) {
    for (Eigen::Index c = 0; c < 3; ++c) {
      v(r, c) = m(r, c).value();
    }
  }
  return v;
}

/// d m / dt = sum_k (d m / d theta_k) td_k from an AD-evaluated matrix.
template <class Derived>
Eigen::Matrix3d directional(const Eigen::MatrixBase<Derived>& m, const Eigen::Vector3d& td) {
  Eigen::Matrix3d d = Eigen::Matrix3d::Zero();
  for (Eigen::Index r = 0; r < 3; ++r) {
    for (Eigen::Index c = 0; c < 3; ++c) {
      for (Eigen::Index k = 0; k < 3; ++k) {
        d(r, c) += derivative(m(r, c), k) * td(k);
      }
    }
  }
  return d;
}

constexpr int kSamples = 200;

}  // namespace

// ---- names and traits ---------------------------------------------------------------------------

TEST_CASE("EulerAngles: names and traits of the 12 sequences", "[orientation][euler_angles]") {
  static_assert(tumble::EulerXYZ::name == "EulerXYZ");
  static_assert(tumble::EulerXZY::name == "EulerXZY");
  static_assert(tumble::EulerYXZ::name == "EulerYXZ");
  static_assert(tumble::EulerYZX::name == "EulerYZX");
  static_assert(tumble::EulerZXY::name == "EulerZXY");
  static_assert(tumble::EulerZYX::name == "EulerZYX");
  static_assert(tumble::EulerXYX::name == "EulerXYX");
  static_assert(tumble::EulerXZX::name == "EulerXZX");
  static_assert(tumble::EulerYXY::name == "EulerYXY");
  static_assert(tumble::EulerYZY::name == "EulerYZY");
  static_assert(tumble::EulerZXZ::name == "EulerZXZ");
  static_assert(tumble::EulerZYZ::name == "EulerZYZ");
  // (compared as std::string: Catch2 v2 prints std::string_view only when its main was built
  // as C++17 or later)
  CHECK(std::string(tumble::EulerZYX::name) == "EulerZYX");
  CHECK(std::string(tumble::EulerAngles<1, 2, 1>::name) == "EulerYZY");
  static_assert(tumble::EulerZYX::is_tait_bryan && !tumble::EulerZXZ::is_tait_bryan);
  static_assert(std::is_same_v<tumble::EulerZYX, tumble::EulerAngles<2, 1, 0>>);
}

TEMPLATE_LIST_TEST_CASE("EulerAngles: interface", "[orientation][euler_angles]", AllEulerAngles) {
  using P = TestType;
  static_assert(tumble::Orientation<P>);
  static_assert(P::size == 3 && !P::has_constraint);
  STATIC_REQUIRE(P::name.size() == 8);
  CHECK(std::string(P::name.substr(0, 5)) == "Euler");
  const Eigen::Vector3d th(0.3, -1.1, 2.5);
  CHECK(P::canonical(th) == th);  // the identity, by design
}

// ---- R ------------------------------------------------------------------------------------------

TEMPLATE_LIST_TEST_CASE("EulerAngles: R is the product of the three AngleAxis rotations",
                        "[orientation][euler_angles]", AllEulerAngles) {
  using P = TestType;
  Random rng;
  double err = 0, orth = 0, det = 0;
  std::vector<Eigen::Vector3d> cases = {Eigen::Vector3d::Zero(),
                                        {kPi, kPi, kPi},
                                        {kPi / 2, kPi / 2, kPi / 2},
                                        {-kPi / 2, 0, kPi / 2},
                                        {10.0, -7.0, 25.0}};
  for (int n = 0; n < kSamples; ++n) {
    cases.push_back(rng.vector(-kPi, kPi));
  }
  for (const auto& th : cases) {
    const Eigen::Matrix3d r = P::rotation(th);
    err = std::max(err, max_abs(r - reference_rotation<P>(th)));
    orth = std::max(orth, max_abs(r.transpose() * r - Eigen::Matrix3d::Identity()));
    det = std::max(det, std::abs(r.determinant() - 1));
  }
  // Each entry is a sum of at most 4 products of 3 unit-bounded factors in both computations
  // (rounding <= 4 eps each); the Gram matrix and det add one more such sum.
  CHECK(err <= 8 * kEps);
  CHECK(orth <= 8 * kEps);
  CHECK(det <= 8 * kEps);
}

TEMPLATE_LIST_TEST_CASE("EulerAngles: elementary rotations about each axis",
                        "[orientation][euler_angles]", AllEulerAngles) {
  using P = TestType;
  // Only one nonzero angle: R is the AngleAxis rotation about that axis.
  const double t = 0.7;
  CHECK(max_abs(P::rotation(Eigen::Vector3d(t, 0, 0)) - axis_rotation(P::axis1, t)) <= 2 * kEps);
  CHECK(max_abs(P::rotation(Eigen::Vector3d(0, t, 0)) - axis_rotation(P::axis2, t)) <= 2 * kEps);
  CHECK(max_abs(P::rotation(Eigen::Vector3d(0, 0, t)) - axis_rotation(P::axis3, t)) <= 2 * kEps);
  // Active rotation: R_x(pi/2) maps e_y to e_z (and cyclically).
  const int a = P::axis1;
  const Eigen::Vector3d mapped =
      P::rotation(Eigen::Vector3d(kPi / 2, 0, 0)) * Eigen::Vector3d::Unit((a + 1) % 3);
  CHECK(max_abs(mapped - Eigen::Vector3d::Unit((a + 2) % 3)) <= 2 * kEps);
}

// ---- G ------------------------------------------------------------------------------------------

TEMPLATE_LIST_TEST_CASE("EulerAngles: G = [c1 c2 c3] from AngleAxis, and S(G td) = R^T Rdot",
                        "[orientation][euler_angles]", AllEulerAngles) {
  using P = TestType;
  Random rng;
  double err_g = 0, err_fd = 0;
  for (int n = 0; n < kSamples; ++n) {
    const Eigen::Vector3d th = rng.vector(-kPi, kPi);
    const Eigen::Vector3d td = rng.vector(-1, 1);
    const Eigen::Matrix3d g = P::G(th);
    err_g = std::max(err_g, max_abs(g - ReferenceFrame<P, double>(th).G()));
    // Rdot by Richardson-extrapolated central differences along td, h = 1e-3: truncation
    // h^4 |R^(5)| / 480 <= h^4 |td|_1^5 / 480 <= 5e-13 (|td|_1 <= 3: each derivative of
    // R_a1 R_a2 R_a3 along td is bounded by |td|_1 times the previous one); rounding
    // 3 e_R / h ~ 1.3e-12 per entry with e_R ~ 2 eps the error of R's entries, up to 4e-12 after
    // the three products of R^T Rdot.
    const auto rot = [](const Eigen::Vector3d& x) { return P::rotation(x); };
    const Eigen::Matrix3d rdot = richardson(rot, th, td, 1e-3);
    const Eigen::Matrix3d r = P::rotation(th);
    err_fd =
        std::max(err_fd, max_abs(tumble::skew(Eigen::Vector3d(g * td)) - r.transpose() * rdot));
  }
  // Entries of G are single products of sines and cosines; AngleAxis adds one more rounding.
  CHECK(err_g <= 4 * kEps);
  CHECK(err_fd <= 1e-11);
}

TEMPLATE_LIST_TEST_CASE("EulerAngles: Gdot thetadot against the cross products and FD of G",
                        "[orientation][euler_angles]", AllEulerAngles) {
  using P = TestType;
  Random rng;
  double err_cross = 0, err_fd = 0;
  for (int n = 0; n < kSamples; ++n) {
    const Eigen::Vector3d th = rng.vector(-kPi, kPi);
    const Eigen::Vector3d td = rng.vector(-1, 1);
    const Eigen::Vector3d gd = P::Gdot_thetadot(th, td);
    const Eigen::Vector3d ref = ReferenceFrame<P, double>(th).gdot_td(td);
    // Terms of size |td|^2 <= 4; a few roundings each.
    err_cross = std::max(err_cross, max_abs(gd - ref));
    const auto g_of = [](const Eigen::Vector3d& x) { return P::G(x); };
    const Eigen::Matrix3d gdot = richardson(g_of, th, td, 1e-3);
    err_fd = std::max(err_fd, max_abs(gd - gdot * td));
  }
  CHECK(err_cross <= 64 * kEps);
  CHECK(err_fd <= 2e-11);  // the FD error bound of R's test, times |td|_1 <= 3
}

TEMPLATE_LIST_TEST_CASE("EulerAngles: AD derivatives of R and G agree with G and Gdot thetadot",
                        "[orientation][euler_angles]", AllEulerAngles) {
  using P = TestType;
  Random rng;
  double err_r = 0, err_g = 0, err_val = 0;
  for (int n = 0; n < 50; ++n) {
    const Eigen::Vector3d th = rng.vector(-kPi, kPi);
    const Eigen::Vector3d td = rng.vector(-2, 2);
    const auto t = seeded(th);
    const Eigen::Matrix<AD, 3, 3> r_ad = P::rotation(t);
    const Eigen::Matrix3d r = P::rotation(th);
    err_val = std::max(err_val, max_abs(values(r_ad) - r));
    // Rdot = R S(G td)   (Eq. 1.5 with S(omega) = R^T Rdot)
    const Eigen::Matrix3d rdot = directional(r_ad, td);
    err_r = std::max(err_r, max_abs(rdot - r * tumble::skew(Eigen::Vector3d(P::G(th) * td))));
    // (d G / dt) td = Gdot thetadot   (Eq. 1.10)
    const Eigen::Matrix<AD, 3, 3> g_ad = P::G(t);
    err_val = std::max(err_val, max_abs(values(g_ad) - P::G(th)));
    const Eigen::Vector3d gd = directional(g_ad, td) * td;
    err_g = std::max(err_g, max_abs(gd - P::Gdot_thetadot(th, td)));
  }
  CHECK(err_val == 0.0);
  CHECK(err_r <= 32 * kEps);
  CHECK(err_g <= 64 * kEps);
}

// ---- inverse map and accelerations --------------------------------------------------------------

TEMPLATE_LIST_TEST_CASE("EulerAngles: thetadot inverts G, thetaddot inverts Eq. (1.10)",
                        "[orientation][euler_angles]", AllEulerAngles) {
  using P = TestType;
  Random rng;
  double err_w = 0, err_td = 0, err_ref = 0, err_tdd = 0, err_traj = 0;
  for (int n = 0; n < kSamples; ++n) {
    // At least 0.3 rad from the singularity: |G^{-1}| <= 1 + 1 / sin(0.3) < 4.5.
    const Eigen::Vector3d th = rng.template principal_angles<P>(0.3) + Eigen::Vector3d(0, 0, 0);
    const Eigen::Vector3d w = rng.vector(-2, 2);
    const Eigen::Vector3d td = rng.vector(-1, 1);
    const Eigen::Vector3d tdd = rng.vector(-1, 1);
    const Eigen::Matrix3d g = P::G(th);
    const Eigen::Vector3d x = P::thetadot(th, w);
    err_w = std::max(err_w, max_abs(g * x - w));
    err_td = std::max(err_td, max_abs(P::thetadot(th, Eigen::Vector3d(g * td)) - td));
    err_ref = std::max(err_ref, max_abs(x - ReferenceFrame<P, double>(th).G_inverse() * w));
    // alpha = Gdot td + G tdd  ->  thetaddot(theta, td, alpha) = tdd
    const Eigen::Vector3d alpha = P::Gdot_thetadot(th, td) + g * tdd;
    err_tdd = std::max(err_tdd, max_abs(P::thetaddot(th, td, alpha) - tdd));
    // Along theta(t) = th + td t + tdd t^2 / 2, alpha = d/dt (G(theta(t)) thetadot(t)) by
    // Richardson central differences (h = 1e-3): thetaddot must return tdd.
    const auto omega_at = [&](double s) {
      const Eigen::Vector3d tt = th + s * td + 0.5 * s * s * tdd;
      const Eigen::Vector3d vv = td + s * tdd;
      return Eigen::Vector3d(P::G(tt) * vv);
    };
    const double h = 1e-3;
    const Eigen::Vector3d d1 = (omega_at(h) - omega_at(-h)) / (2 * h);
    const Eigen::Vector3d d2 = (omega_at(h / 2) - omega_at(-h / 2)) / h;
    const Eigen::Vector3d alpha_fd = (4 * d2 - d1) / 3;
    err_traj = std::max(err_traj, max_abs(P::thetaddot(th, td, alpha_fd) - tdd));
  }
  CHECK(err_w <= 32 * kEps);
  CHECK(err_td <= 32 * kEps);
  CHECK(err_ref <= 32 * kEps);
  CHECK(err_tdd <= 128 * kEps);
  CHECK(err_traj <= 1e-10);  // FD error ~1e-12 in alpha, times |G^{-1}| < 4.5
}

// ---- conversions --------------------------------------------------------------------------------

TEMPLATE_LIST_TEST_CASE("EulerAngles: rotation -> angles -> rotation, and quaternions",
                        "[orientation][euler_angles]", AllEulerAngles) {
  using P = TestType;
  Random rng;
  double err_angles = 0, err_r = 0, err_rq = 0, err_q = 0, err_qr = 0, err_qprod = 0;
  for (int n = 0; n < kSamples; ++n) {
    // Principal angles 0.05 rad from lock come back unchanged (t1 is conditioned by
    // 1 / cos t2 or 1 / sin t2 < 21).
    const Eigen::Vector3d th = rng.template principal_angles<P>(0.05);
    const Eigen::Vector3d back = P::from_rotation(reference_rotation<P>(th));
    err_angles = std::max(err_angles, max_abs(back - th));
    // Any angles: the matrix comes back.
    const Eigen::Vector3d any = rng.vector(-3 * kPi, 3 * kPi);
    const Eigen::Matrix3d r = reference_rotation<P>(any);
    err_r = std::max(err_r, max_abs(P::rotation(P::from_rotation(r)) - r));
    // Any rotation matrix (from a random unit quaternion).
    const Eigen::Quaterniond q = rng.unit_quaternion();
    const Eigen::Matrix3d rq = q.toRotationMatrix();
    err_rq = std::max(err_rq, max_abs(P::rotation(P::from_rotation(rq)) - rq));
    // Quaternion round trip (up to the sign of q).
    const Eigen::Quaterniond q2 = P::to_quaternion(P::from_quaternion(q));
    err_q = std::max(err_q, std::min((q2.coeffs() - q.coeffs()).cwiseAbs().maxCoeff(),
                                     (q2.coeffs() + q.coeffs()).cwiseAbs().maxCoeff()));
    // to_quaternion describes the same rotation as rotation().
    err_qr = std::max(err_qr, max_abs(P::to_quaternion(any).toRotationMatrix() - P::rotation(any)));
    // ... and is the product of the three AngleAxis quaternions, sign included.
    const Eigen::Quaterniond qref =
        Eigen::Quaterniond(Eigen::AngleAxisd(any(0), Eigen::Vector3d::Unit(P::axis1))) *
        Eigen::Quaterniond(Eigen::AngleAxisd(any(1), Eigen::Vector3d::Unit(P::axis2))) *
        Eigen::Quaterniond(Eigen::AngleAxisd(any(2), Eigen::Vector3d::Unit(P::axis3)));
    err_qprod = std::max(err_qprod, max_abs(P::to_quaternion(any).coeffs() - qref.coeffs()));
  }
  CHECK(err_angles <= 1e-13);
  CHECK(err_r <= 16 * kEps);
  CHECK(err_rq <= 16 * kEps);
  CHECK(err_q <= 16 * kEps);
  CHECK(err_qr <= 16 * kEps);
  CHECK(err_qprod <= 8 * kEps);
}

TEMPLATE_LIST_TEST_CASE("EulerAngles: principal ranges of from_rotation",
                        "[orientation][euler_angles]", AllEulerAngles) {
  using P = TestType;
  Random rng;
  for (int n = 0; n < kSamples; ++n) {
    const Eigen::Vector3d th = P::from_rotation(rng.unit_quaternion().toRotationMatrix());
    CHECK(std::abs(th(0)) <= kPi);
    CHECK(std::abs(th(2)) <= kPi);
    if constexpr (P::is_tait_bryan) {
      CHECK(std::abs(th(1)) <= kPi / 2);
    } else {
      CHECK((th(1) >= 0 && th(1) <= kPi));
    }
  }
  CHECK(P::from_rotation(Eigen::Matrix3d(Eigen::Matrix3d::Identity())) == Eigen::Vector3d::Zero());
}

// ---- gimbal lock --------------------------------------------------------------------------------

TEMPLATE_LIST_TEST_CASE("EulerAngles: near gimbal lock (1e-6 and 1e-9 rad)",
                        "[orientation][euler_angles]", AllEulerAngles) {
  using P = TestType;
  Random rng;
  double err_g = 0, err_gd = 0, err_inv = 0, err_res = 0, err_r = 0, err_dist = 0;
  for (const double lock : lock_angles<P>()) {
    for (const double delta : {1e-6, -1e-6, 1e-9, -1e-9}) {
      for (int n = 0; n < 20; ++n) {
        const Eigen::Vector3d th(rng.uniform(-kPi, kPi), lock + delta, rng.uniform(-kPi, kPi));
        const Eigen::Vector3d td = rng.vector(-2, 2);
        const Eigen::Vector3d w = rng.vector(-2, 2);
        // G and Gdot td stay accurate (single products of sines and cosines).
        const Eigen::Matrix3d g = P::G(th);
        err_g = std::max(err_g, max_abs(g - ReferenceFrame<P, double>(th).G()));
        err_gd = std::max(
            err_gd, max_abs(P::Gdot_thetadot(th, td) - ReferenceFrame<P, double>(th).gdot_td(td)));
        // thetadot is large (~1/delta) but accurate: against G^{-1} w from the cross products
        // in long double, within a few eps of (|G^{-1}| |w|), the error of evaluating G^{-1} w
        // from exactly rounded entries of G^{-1}.
        const Eigen::Vector3d x = P::thetadot(th, w);
        REQUIRE(tumble::detail::all_finite(x));
        const ReferenceFrame<P, long double> ref(th.cast<long double>());
        const Matrix3ld gi = ref.G_inverse();
        const Vector3ld xref = gi * w.cast<long double>();
        const Vector3ld scale = gi.cwiseAbs() * w.cast<long double>().cwiseAbs();
        const Vector3ld rel = (x.cast<long double>() - xref).cwiseQuotient(scale);
        err_inv = std::max(err_inv, max_abs(rel) / kEps);
        // Backward error: G x = w up to eps |G| |x|.
        err_res = std::max(err_res, max_abs(g * x - w) / (kEps * x.cwiseAbs().maxCoeff()));
        // from_rotation reproduces R.
        const Eigen::Matrix3d r = reference_rotation<P>(th);
        const Eigen::Vector3d back = P::from_rotation(r);
        REQUIRE(tumble::detail::all_finite(back));
        err_r = std::max(err_r, max_abs(P::rotation(back) - r));
        err_dist = std::max(err_dist, std::abs(P::singularity_distance(th) - std::abs(delta)));
      }
    }
  }
  CHECK(err_g <= 4 * kEps);
  CHECK(err_gd <= 64 * kEps);
  CHECK(err_inv <= 8);  // in units of eps
  CHECK(err_res <= 8);  // in units of eps |x|
  CHECK(err_r <= 16 * kEps);
  CHECK(err_dist <= 4 * kEps);
}

TEMPLATE_LIST_TEST_CASE("EulerAngles: exactly at gimbal lock", "[orientation][euler_angles]",
                        AllEulerAngles) {
  using P = TestType;
  Random rng;
  // The middle rotation at lock, with exact zeros: R_j(+-pi/2) (Tait-Bryan) or I, R_j(pi)
  // (proper), written down from its definition.
  std::vector<Eigen::Matrix3d> middles;
  const int j = P::axis2;
  const int b = (j + 1) % 3;
  const int d = (j + 2) % 3;
  if constexpr (P::is_tait_bryan) {
    for (const double s : {1.0, -1.0}) {
      Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
      m(j, j) = 1;
      m(b, d) = -s;
      m(d, b) = s;
      middles.push_back(m);
    }
  } else {
    middles.push_back(Eigen::Matrix3d::Identity());
    Eigen::Matrix3d m = -Eigen::Matrix3d::Identity();
    m(j, j) = 1;
    middles.push_back(m);
  }
  double err_r = 0, err_t2 = 0, err_dist = 0;
  for (const auto& m : middles) {
    for (int n = 0; n < 50; ++n) {
      const double t1 = rng.uniform(-kPi, kPi);
      const double t3 = rng.uniform(-kPi, kPi);
      const Eigen::Matrix3d r = axis_rotation(P::axis1, t1) * m * axis_rotation(P::axis3, t3);
      const Eigen::Vector3d th = P::from_rotation(r);
      REQUIRE(tumble::detail::all_finite(th));
      err_r = std::max(err_r, max_abs(P::rotation(th) - r));
      // The middle angle is the lock angle (to rounding) and the distance is ~0.
      double nearest = kPi;
      for (const double lock : lock_angles<P>()) {
        nearest = std::min(nearest, std::abs(th(1) - lock));
      }
      err_t2 = std::max(err_t2, nearest);
      err_dist = std::max(err_dist, P::singularity_distance(th));
    }
    // Exact zeros where t1 is read: t1 = 0 by convention, t3 carries the rotation.
    const Eigen::Matrix3d r0 = m * axis_rotation(P::axis3, 0.4);
    const Eigen::Vector3d th0 = P::from_rotation(r0);
    CHECK(th0(0) == 0.0);
    CHECK(max_abs(P::rotation(th0) - r0) <= 4 * kEps);
  }
  // Angles whose middle value is the double closest to the lock angle.
  for (const double lock : lock_angles<P>()) {
    const Eigen::Vector3d th(0.8, lock, -2.1);
    const Eigen::Matrix3d r = P::rotation(th);
    const Eigen::Vector3d back = P::from_rotation(r);
    REQUIRE(tumble::detail::all_finite(back));
    err_r = std::max(err_r, max_abs(P::rotation(back) - r));
    REQUIRE(tumble::detail::all_finite(P::G(th)));
    REQUIRE(tumble::detail::all_finite(P::Gdot_thetadot(th, Eigen::Vector3d(1, 2, 3))));
  }
  CHECK(err_r <= 16 * kEps);
  CHECK(err_t2 <= 2 * kEps);
  CHECK(err_dist <= 4 * kEps);
}

// ---- singularity distance -----------------------------------------------------------------------

TEMPLATE_LIST_TEST_CASE("EulerAngles: singularity_distance", "[orientation][euler_angles]",
                        AllEulerAngles) {
  using P = TestType;
  const auto dist = [](double t2) {
    return P::singularity_distance(Eigen::Vector3d(1.3, t2, -0.4));
  };
  // (middle angle, distance by hand)
  std::vector<std::pair<double, double>> known;
  if constexpr (P::is_tait_bryan) {
    known = {{0.0, kPi / 2},
             {1.0, kPi / 2 - 1.0},
             {-1.2, kPi / 2 - 1.2},
             {kPi / 2, 0.0},
             {-kPi / 2, 0.0},
             {kPi, kPi / 2},
             {2.0, 2.0 - kPi / 2},
             {-2.5, 2.5 - kPi / 2},
             {2 * kPi + 0.3, kPi / 2 - 0.3},
             {-4 * kPi + 1.5, kPi / 2 - 1.5}};
  } else {
    known = {{0.0, 0.0},          {kPi / 2, kPi / 2},   {0.3, 0.3},
             {-0.4, 0.4},         {kPi, 0.0},           {kPi - 0.2, 0.2},
             {-kPi + 0.25, 0.25}, {4 * kPi + 0.1, 0.1}, {-6 * kPi - 1.0, 1.0}};
  }
  for (const auto& [t2, expected] : known) {
    CAPTURE(t2);
    // Wrapping by k turns costs k roundings of 2 pi.
    CHECK(std::abs(dist(t2) - expected) <= 8 * kEps * (1 + std::abs(t2)));
  }
  // Independently, |det G| = sin(distance) (det G = +-cos t2 or +-sin t2).
  Random rng;
  double err = 0;
  for (int n = 0; n < kSamples; ++n) {
    const Eigen::Vector3d th = rng.vector(-10, 10);
    err = std::max(
        err, std::abs(std::abs(P::G(th).determinant()) - std::sin(P::singularity_distance(th))));
  }
  CHECK(err <= 1e-14);
}

// ---- other scalar types -------------------------------------------------------------------------

TEMPLATE_LIST_TEST_CASE("EulerAngles: float", "[orientation][euler_angles]", AllEulerAngles) {
  using P = TestType;
  Random rng;
  double orth = 0, err_r = 0, err_g = 0, err_gd = 0, err_fd = 0, err_w = 0, err_conv = 0;
  for (int n = 0; n < 50; ++n) {
    const Eigen::Vector3d thd = rng.template principal_angles<P>(0.3);
    const Eigen::Vector3f th = thd.cast<float>();
    const Eigen::Vector3f td = rng.vector(-1, 1).cast<float>();
    const Eigen::Vector3f w = rng.vector(-2, 2).cast<float>();
    const Eigen::Matrix3f r = P::rotation(th);
    orth = std::max(orth, max_abs(r.transpose() * r - Eigen::Matrix3f::Identity()));
    // Against double evaluated at the same (float) angles.
    const Eigen::Vector3d th2 = th.cast<double>();
    err_r = std::max(err_r, max_abs(r.cast<double>() - P::rotation(th2)));
    err_g = std::max(err_g, max_abs(P::G(th).template cast<double>() - P::G(th2)));
    err_gd = std::max(err_gd, max_abs(P::Gdot_thetadot(th, td).template cast<double>() -
                                      P::Gdot_thetadot(th2, Eigen::Vector3d(td.cast<double>()))));
    // S(G td) = R^T Rdot with Richardson differences of the float R, h = 0.05 (about the
    // optimal eps_f^(1/5)): rounding 3 e_R / h ~ 1.4e-5 per entry (e_R ~ 2 eps_f), up to 4.3e-5
    // after R^T Rdot; truncation h^4 |td|_1^5 / 480 <= 3e-6 (|td|_1 <= 3).
    const float h = 0.05f;
    const auto central = [&](float step) {
      const Eigen::Vector3f xp = th + step * td;
      const Eigen::Vector3f xm = th - step * td;
      return Eigen::Matrix3f((P::rotation(xp) - P::rotation(xm)) / (2 * step));
    };
    const Eigen::Matrix3f rdot = (4 * central(h / 2) - central(h)) / 3;
    err_fd = std::max(err_fd,
                      max_abs(tumble::skew(Eigen::Vector3f(P::G(th) * td)) - r.transpose() * rdot));
    err_w = std::max(err_w, max_abs(P::G(th) * P::thetadot(th, w) - w));
    err_conv = std::max(err_conv, max_abs(P::rotation(P::from_rotation(r)) - r));
    err_conv = std::max(err_conv, max_abs(P::to_quaternion(th).toRotationMatrix() - r));
  }
  CHECK(orth <= 8 * kEpsF);
  CHECK(err_r <= 8 * kEpsF);
  CHECK(err_g <= 4 * kEpsF);
  CHECK(err_gd <= 64 * kEpsF);
  CHECK(err_fd <= 5e-5);
  CHECK(err_w <= 32 * kEpsF);
  CHECK(err_conv <= 16 * kEpsF);
}

TEMPLATE_LIST_TEST_CASE("EulerAngles: long double agrees with double",
                        "[orientation][euler_angles]", AllEulerAngles) {
  using P = TestType;
  Random rng;
  double err = 0;
  for (int n = 0; n < 20; ++n) {
    const Eigen::Vector3d th = rng.template principal_angles<P>(0.3);
    const Eigen::Vector3d td = rng.vector(-2, 2);
    const Vector3ld thl = th.cast<long double>();
    const Vector3ld tdl = td.cast<long double>();
    err = std::max(err, max_abs(P::rotation(thl).template cast<double>() - P::rotation(th)));
    err = std::max(err, max_abs(P::G(thl).template cast<double>() - P::G(th)));
    err = std::max(err, max_abs(P::Gdot_thetadot(thl, tdl).template cast<double>() -
                                P::Gdot_thetadot(th, td)) /
                            16);
    err = std::max(
        err, max_abs(P::thetadot(thl, tdl).template cast<double>() - P::thetadot(th, td)) / 16);
    err = std::max(err, max_abs(P::thetaddot(thl, tdl, tdl).template cast<double>() -
                                P::thetaddot(th, td, td)) /
                            64);
    err = std::max(err, max_abs(P::from_rotation(P::rotation(thl)).template cast<double>() - th));
    const Eigen::Quaternion<long double> ql = P::to_quaternion(thl);
    err = std::max(err, max_abs(P::from_quaternion(ql).template cast<double>() - th));
    err = std::max(err, std::abs(static_cast<double>(P::singularity_distance(thl)) -
                                 P::singularity_distance(th)));
    CHECK(P::canonical(thl) == thl);
  }
  CHECK(err <= 64 * kEps);
}

TEMPLATE_LIST_TEST_CASE("EulerAngles: AutoDiffScalar", "[orientation][euler_angles]",
                        AllEulerAngles) {
  using P = TestType;
  Random rng;
  double orth = 0, orth_d = 0, err_g = 0, err_inv = 0, err_conv = 0;
  for (int n = 0; n < 30; ++n) {
    const Eigen::Vector3d th = rng.template principal_angles<P>(0.3);
    const auto t = seeded(th);
    const Eigen::Matrix<AD, 3, 3> r = P::rotation(t);
    const Eigen::Matrix<AD, 3, 3> rtr = r.transpose() * r;
    orth = std::max(orth, max_abs(values(rtr) - Eigen::Matrix3d::Identity()));
    // d(R^T R)/d theta_k = 0, and R^T dR/dtheta_k = S(G e_k): column k of G (Eq. 1.5).
    for (Eigen::Index k = 0; k < 3; ++k) {
      const Eigen::Vector3d ek = Eigen::Vector3d::Unit(k);
      orth_d = std::max(orth_d, max_abs(directional(rtr, ek)));
      const Eigen::Matrix3d rk = directional(r, ek);
      err_g = std::max(err_g, max_abs(values(r).transpose() * rk -
                                      tumble::skew(Eigen::Vector3d(P::G(th).col(k)))));
    }
    // Derivatives of the inverse map: d/dtheta of G(theta) thetadot(theta, w) = 0 for fixed w.
    Eigen::Matrix<AD, 3, 1> w;
    w << AD(0.3), AD(-1.2), AD(0.7);
    const Eigen::Matrix<AD, 3, 1> gx = P::G(t) * P::thetadot(t, w);
    for (Eigen::Index i = 0; i < 3; ++i) {
      err_inv = std::max(err_inv, std::abs(gx(i).value() - w(i).value()));
      for (Eigen::Index k = 0; k < 3; ++k) {
        err_inv = std::max(err_inv, std::abs(derivative(gx(i), k)));
      }
    }
    // from_rotation(R(theta)) = theta: its AD Jacobian with respect to theta is the identity.
    const Eigen::Matrix<AD, 3, 1> back = P::from_rotation(r);
    for (Eigen::Index i = 0; i < 3; ++i) {
      err_conv = std::max(err_conv, std::abs(back(i).value() - th(i)));
      for (Eigen::Index k = 0; k < 3; ++k) {
        err_conv = std::max(err_conv, std::abs(derivative(back(i), k) - (i == k ? 1.0 : 0.0)));
      }
    }
    const Eigen::Matrix<AD, 3, 1> backq = P::from_quaternion(P::to_quaternion(t));
    for (Eigen::Index i = 0; i < 3; ++i) {
      for (Eigen::Index k = 0; k < 3; ++k) {
        err_conv = std::max(err_conv, std::abs(derivative(backq(i), k) - (i == k ? 1.0 : 0.0)));
      }
    }
    // The remaining functions compile and return finite values for AD.
    const Eigen::Matrix<AD, 3, 1> tdd = P::thetaddot(t, t, w);
    REQUIRE(std::isfinite(tdd(0).value()));
    REQUIRE(std::isfinite(P::singularity_distance(t).value()));
    REQUIRE(std::isfinite(P::Gdot_thetadot(t, t)(2).value()));
    REQUIRE(std::isfinite(P::canonical(t)(1).value()));
  }
  CHECK(orth <= 8 * kEps);
  CHECK(orth_d <= 8 * kEps);
  CHECK(err_g <= 8 * kEps);
  CHECK(err_inv <= 64 * kEps);
  CHECK(err_conv <= 1e-13);  // conditioned by 1 / sin(0.3) at worst
}

TEMPLATE_LIST_TEST_CASE("EulerAngles: AD from_rotation exactly at gimbal lock is finite",
                        "[orientation][euler_angles]", AllEulerAngles) {
  using P = TestType;
  // The identity for proper sequences (t2 = 0), R_j(pi/2) with exact zeros for Tait-Bryan.
  Eigen::Matrix<AD, 3, 3> r = Eigen::Matrix<AD, 3, 3>::Identity();
  if constexpr (P::is_tait_bryan) {
    const int j = P::axis2;
    const int b = (j + 1) % 3;
    const int d = (j + 2) % 3;
    r(b, b) = AD(0.0);
    r(d, d) = AD(0.0);
    r(b, d) = AD(-1.0);
    r(d, b) = AD(1.0);
  }
  // Seed every entry so the derivatives have somewhere to go.
  for (Eigen::Index k = 0; k < 9; ++k) {
    r(k % 3, k / 3).derivatives() = Eigen::VectorXd::Unit(9, k);
  }
  const Eigen::Matrix<AD, 3, 1> th = P::from_rotation(r);
  for (Eigen::Index i = 0; i < 3; ++i) {
    CHECK(std::isfinite(th(i).value()));
    CHECK(th(i).derivatives().allFinite());
  }
  CHECK(max_abs(P::rotation(Eigen::Vector3d(th(0).value(), th(1).value(), th(2).value())) -
                values(r)) <= 2 * kEps);
}
