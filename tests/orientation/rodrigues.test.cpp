// Tests of include/tumble/orientation/rodrigues.hpp: the Gibbs vector g = n tan(phi/2).
//
// Every expected value comes from an independent source: Eigen::AngleAxis for R and the
// quaternion (the Gibbs vector is built from (phi, n) by its definition), central finite
// differences in long double for R^T Rdot and Gdot gdot, Eigen's AutoDiffScalar, the identities
// G G^-1 = I and G gddot = alpha - Gdot gdot (Eq. 1.10), and closed-form angles for the distance
// to the singularity. Reference chapter: Chapter 1, "Rigid body", Eqs. (1.1),
// (1.5), (1.10).

#include "tumble/orientation/rodrigues.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <unsupported/Eigen/AutoDiff>

#include "support/axis_angle_sample.hpp"
#include "support/catch.hpp"
#include "support/finite_difference.hpp"
#include "support/numeric.hpp"
#include "support/random.hpp"
#include "tumble/core/errors.hpp"
#include "tumble/core/math.hpp"

namespace {

using P = tumble::RodriguesParameters;
using tumble::Matrix3;
using tumble::Vector3;
using AD = Eigen::AutoDiffScalar<Eigen::VectorXd>;
using LD = long double;
using tumble::test::ad_derivative;
using tumble::test::ad_derivatives;
using tumble::test::along;
using tumble::test::eps;
using tumble::test::five_point_derivative;
using tumble::test::kFivePointTol;
using tumble::test::rel_err;
using Vector3ld = Vector3<LD>;
using Matrix3ld = Matrix3<LD>;

const LD kPi = std::acos(-1.0L);
const double kPid = std::acos(-1.0);

/// The Gibbs vector by its definition g = n tan(phi/2), and the angle of a given g.
struct GibbsDefinition {
  static LD magnitude(LD phi) { return std::tan(phi / 2); }
  static LD angle(LD norm) { return 2 * std::atan(norm); }
};
template <class S> using Sample = tumble::test::AxisAngleSample<S, GibbsDefinition>;

/// Random attitudes with phi up to phi_max, plus a few fixed ones.
template <class S> std::vector<Sample<S>> samples(LD phi_max, int count) {
  return tumble::test::axis_angle_samples<Sample<S>>(
      4711,
      {{0.3L, Vector3ld(1, 0, 0)}, {1.2L, Vector3ld(0, 1, 0)}, {phi_max, Vector3ld(1, -2, 3)}},
      phi_max, count);
}

}  // namespace

TEMPLATE_TEST_CASE("Gibbs R matches Eigen::AngleAxis and is a rotation", "[orientation][rodrigues]",
                   float, double, long double) {
  using S = TestType;
  // g from (phi, n) is exact in LD; R has a few roundings of size eps (1 + |g|^2) / (1 + |g|^2).
  for (const auto& s : samples<S>(0.95L * kPi, 40)) {
    const Matrix3<S> r = P::rotation(s.coords);
    CHECK(rel_err(r, s.reference_rotation()) < 16 * eps<S>());
    const Matrix3ld rl = r.template cast<LD>();
    CHECK((rl.transpose() * rl - Matrix3ld::Identity()).norm() < 16 * eps<S>());
    CHECK(std::abs(rl.determinant() - 1) < 16 * eps<S>());
  }
}

TEMPLATE_TEST_CASE("Gibbs G, Gdot gdot and the inverse map against finite differences",
                   "[orientation][rodrigues]", float, double) {
  using S = TestType;
  tumble::test::Random rnd(17);
  for (const auto& s : samples<S>(0.8L * kPi, 30)) {
    const Vector3<S> gd = rnd.vector().cast<S>();
    const Vector3ld gl = s.coords.template cast<LD>(), gdl = gd.template cast<LD>();
    // Condition of the map near 180 deg: G ~ 1 / (1 + |g|^2), G^-1 ~ (1 + |g|^2).
    const LD kappa = 1 + gl.squaredNorm();
    const LD tol = 64 * kappa * eps<S>() + kFivePointTol;

    // S(G gdot) = R^T Rdot, Rdot by finite differences of R (Eq. 1.5).
    const Matrix3ld rdot = five_point_derivative(
        [&](LD t) { return Matrix3ld(P::rotation(Vector3ld(gl + t * gdl))); });
    const Matrix3ld wx = P::rotation(gl).transpose() * rdot;
    const Vector3ld omega_fd(wx(2, 1), wx(0, 2), wx(1, 0));
    const Vector3<S> omega = P::G(s.coords) * gd;
    CHECK(rel_err(omega, omega_fd) < tol);
    CHECK((wx + wx.transpose()).norm() < kFivePointTol);  // R^T Rdot is skew

    // Gdot gdot by finite differences of G (Eq. 1.10).
    const Vector3ld gdot_fd =
        five_point_derivative([&](LD t) { return Vector3ld(P::G(Vector3ld(gl + t * gdl)) * gdl); });
    CHECK(rel_err(P::Gdot_thetadot(s.coords, gd), gdot_fd) < tol);

    // The inverse map, both ways, and the accelerations: G gddot + Gdot gdot = alpha.
    const Vector3<S> w = rnd.vector().cast<S>();
    const Vector3<S> alpha = rnd.vector().cast<S>();
    CHECK(rel_err(P::G(s.coords) * P::thetadot(s.coords, w), w) < 16 * kappa * eps<S>());
    CHECK(rel_err(P::thetadot(s.coords, omega), gd) < 16 * kappa * eps<S>());
    const Vector3<S> gdd = P::thetaddot(s.coords, gd, alpha);
    CHECK(rel_err(Vector3<S>(P::G(s.coords) * gdd + P::Gdot_thetadot(s.coords, gd)), alpha) <
          64 * kappa * eps<S>());
  }
}

TEST_CASE("Gibbs AD derivatives of R and G gdot", "[orientation][rodrigues]") {
  tumble::test::Random rnd(23);
  std::vector<Eigen::Vector3d> points{Eigen::Vector3d::Zero(), Eigen::Vector3d(1e-8, -2e-8, 0)};
  for (const auto& s : samples<double>(0.9L * kPi, 20)) {
    points.push_back(s.coords);
  }
  for (const auto& g : points) {
    const Eigen::Vector3d gd = rnd.vector();
    const Vector3<AD> ga = along(g, gd);
    // d/dt R(g + t gdot) = R S(G gdot)  (S(omega) = R^T Rdot, Eq. 1.5).
    const Matrix3<AD> ra = P::rotation(ga);
    Eigen::Matrix3d rdot;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        rdot(i, j) = ad_derivative(ra(i, j));
      }
    }
    const Eigen::Vector3d omega = P::G(g) * gd;
    const Eigen::Matrix3d expected = P::rotation(g) * tumble::skew(omega);
    const double scale = 1 + g.squaredNorm();
    CHECK(rel_err(rdot, expected) < 64 * eps<double>());
    // d/dt (G(g + t gdot) gdot) = Gdot gdot.
    const Vector3<AD> wa = P::G(ga) * gd.cast<AD>();
    const Eigen::Vector3d gdot_ad(ad_derivative(wa(0)), ad_derivative(wa(1)), ad_derivative(wa(2)));
    CHECK(rel_err(P::Gdot_thetadot(g, gd), gdot_ad) < 64 * scale * eps<double>());
    // The AD instantiation gives the same values as double.
    const Vector3<AD> gdd_a = P::Gdot_thetadot(ga, along(gd, gd));
    const Eigen::Vector3d gdd_v(gdd_a(0).value(), gdd_a(1).value(), gdd_a(2).value());
    CHECK(rel_err(gdd_v, P::Gdot_thetadot(g, gd)) < 4 * eps<double>());
  }
}

TEMPLATE_TEST_CASE("Gibbs round trips through R and the quaternion", "[orientation][rodrigues]",
                   float, double, long double) {
  using S = TestType;
  for (const auto& s : samples<S>(0.9L * kPi, 40)) {
    // e0 = cos(phi/2) >= 0.16: an absolute error eps in e0 is a relative eps / e0 in g.
    const LD tol = 32 * eps<S>() * std::sqrt(1 + s.coords.template cast<LD>().squaredNorm());
    CHECK(rel_err(P::from_rotation(P::rotation(s.coords)), s.coords) < tol);
    const Eigen::Quaternion<S> q = P::to_quaternion(s.coords);
    CHECK(rel_err(P::from_quaternion(q), s.coords) < tol);
    // Against Eigen: the same rotation, q with e0 > 0.
    const Eigen::Quaternion<LD> qe(Eigen::AngleAxis<LD>(s.phi, s.n));
    CHECK(rel_err(q.coeffs(), qe.coeffs()) < 8 * eps<S>());
    CHECK(q.w() > S(0));
    // g does not depend on the sign or the norm of q.
    const Eigen::Quaternion<S> q2(S(-2.5) * q.w(), S(-2.5) * q.x(), S(-2.5) * q.y(),
                                  S(-2.5) * q.z());
    CHECK(rel_err(P::from_quaternion(q2), s.coords) < tol);
    // The identity is the only canonical choice.
    CHECK(P::canonical(s.coords) == s.coords);
  }
}

TEMPLATE_TEST_CASE("Gibbs at and near zero", "[orientation][rodrigues]", float, double) {
  using S = TestType;
  const Vector3<S> zero = Vector3<S>::Zero();
  CHECK(P::rotation(zero) == Matrix3<S>::Identity());
  CHECK(P::G(zero) == S(2) * Matrix3<S>::Identity());
  CHECK(P::thetadot(zero, Vector3<S>(S(1), S(2), S(3))) == Vector3<S>(S(0.5), S(1), S(1.5)));
  CHECK(P::from_quaternion(Eigen::Quaternion<S>::Identity()) == zero);
  CHECK(static_cast<LD>(P::singularity_distance(zero)) == Approx(static_cast<double>(kPi)));

  // phi = 2e-8: R = I + 2 S(g) + O(g^2) and the distance is pi - 2 |g| to rounding.
  const Vector3<S> g(S(1e-8), S(0), S(0));
  const Matrix3ld expected =
      Eigen::AngleAxis<LD>(2 * std::atan(1e-8L), Vector3ld::UnitX()).toRotationMatrix();
  CHECK(rel_err(P::rotation(g), expected) < 4 * eps<S>());
  CHECK(std::abs(static_cast<LD>(P::singularity_distance(g)) - (kPi - 2e-8L)) < 4 * eps<S>() * kPi);
  CHECK(rel_err(P::from_quaternion(P::to_quaternion(g)), g) < 4 * eps<S>());
}

TEMPLATE_TEST_CASE("Gibbs near the 180 degree singularity", "[orientation][rodrigues]", float,
                   double, long double) {
  using S = TestType;
  // 179.9999 degrees about a skew axis: |g| = tan(89.99995 deg) ~ 1.1e6.
  const LD phi0 = (179.9999L / 180) * kPi;
  const Sample<S> s(phi0, Vector3ld(2, -3, 6));
  const LD gn = s.coords.template cast<LD>().norm();

  // R is still accurate to a few eps: it depends on g only through g/|g| and 1/(1+|g|^2).
  CHECK(rel_err(P::rotation(s.coords), s.reference_rotation()) < 16 * eps<S>());
  // The distance, pi - phi = 2 atan(1 / |g|), keeps full relative accuracy.
  const LD dist = 2 * std::atan(1 / gn);
  CHECK(std::abs(static_cast<LD>(P::singularity_distance(s.coords)) - dist) < 8 * eps<S>() * dist);
  CHECK(dist == Approx(static_cast<double>(kPi - phi0)).epsilon(1e-3));
  // The maps are huge (G ~ 2 / |g|^2 off the axis) but still mutually inverse, up to the
  // condition number of G, sqrt(1 + |g|^2) (the rounding of gdot ~ |g|^2 omega is amplified by
  // the factor |g| of I - S(g) in G).
  const Vector3<S> w(S(0.3), S(-0.1), S(0.2));
  CHECK(rel_err(P::G(s.coords) * P::thetadot(s.coords, w), w) <
        16 * eps<S>() * std::sqrt(1 + gn * gn));
  // A rotation by exactly 180 degrees has no Gibbs vector.
  const Eigen::Quaternion<S> half_turn(S(0), S(0), S(0.6), S(0.8));
  CHECK_THROWS_AS(P::from_quaternion(half_turn), tumble::NonFiniteError);
  CHECK_THROWS_AS(P::from_quaternion(half_turn), std::domain_error);
  Matrix3<S> flip = Matrix3<S>::Identity();
  flip(1, 1) = S(-1);
  flip(2, 2) = S(-1);
  CHECK_THROWS_AS(P::from_rotation(flip), tumble::NonFiniteError);
}

TEST_CASE("Gibbs vector whose squared norm overflows is refused", "[orientation][rodrigues]") {
  // Found by fuzz/orientation.fuzz.cpp: e0 = 8.8e-156 gives a finite g with |g| = 1.1e155, but
  // g.g = 1.3e310 overflows and R = I + 2 / (1 + g.g) (...) evaluates 0 * inf = NaN. Such a
  // rotation lies within 1e-155 rad of 180 degrees: it is refused like the half turn itself.
  const Eigen::Quaterniond q(8.8144233770370566e-156, 0.99999999999999933, 4.0097670121626394e-08,
                             0);
  CHECK_THROWS_AS(P::from_quaternion(q), tumble::NonFiniteError);
  const Eigen::Vector4d p(q.w(), q.x(), q.y(), q.z());
  CHECK_THROWS_AS((tumble::convert<P, tumble::EulerParameters>(p)), tumble::NonFiniteError);
  // Just inside the representable range (|g| = 1e150, g.g = 1e300) the rotation is still exact:
  // the half turn about x, to rounding.
  const Eigen::Quaterniond near(1e-150, 1, 0, 0);
  const Eigen::Vector3d g = P::from_quaternion(near);
  const Eigen::Matrix3d r = P::rotation(g);
  CHECK(r.allFinite());
  CHECK((r - Eigen::Vector3d(1, -1, -1).asDiagonal().toDenseMatrix()).cwiseAbs().maxCoeff() <
        4e-16);
}

TEST_CASE("Gibbs distance to the singularity is continuous and monotone",
          "[orientation][rodrigues]") {
  // pi - phi for phi = 2 atan|g|, switching formulas at |g| = 1.
  for (double phi : {0.0, 0.1, 1.0, kPid / 2 - 1e-12, kPid / 2, 2.0, 3.0, 3.1415}) {
    const Eigen::Vector3d g = std::tan(phi / 2) * Eigen::Vector3d(0, 0.6, -0.8);
    CHECK(P::singularity_distance(g) == Approx(kPid - phi).epsilon(1e-13).margin(1e-15));
  }
}

TEST_CASE("Gibbs AD with constant and variable arguments mixed", "[orientation][rodrigues]") {
  // Eigen's AutoDiffScalar gives constants empty derivative vectors; every function must accept
  // any mix of constant and variable arguments (9 derivatives: theta, thetadot, omega).
  const auto make = [](const Eigen::Vector3d& x, bool variable, int first) {
    Vector3<AD> r;
    for (int i = 0; i < 3; ++i) {
      r(i) = variable ? AD(x(i), 9, first + i) : AD(x(i));
    }
    return r;
  };
  for (const double scale : {0.0, 1e-8, 1.0, 5.0}) {
    for (int mask = 0; mask < 8; ++mask) {
      INFO("scale = " << scale << ", mask = " << mask);
      const Eigen::Vector3d th_d = scale * Eigen::Vector3d(0.3, 0.1, -0.1);
      const Vector3<AD> th = make(th_d, (mask & 1) != 0, 0);
      const Vector3<AD> thd = make(Eigen::Vector3d(0.1, 0.4, 0.7), (mask & 2) != 0, 3);
      const Vector3<AD> w = make(Eigen::Vector3d(1, 2, 3), (mask & 4) != 0, 6);
      const Vector3<AD> omega = P::G(th) * thd;
      const Vector3<AD> values[] = {omega,
                                    P::Gdot_thetadot(th, thd),
                                    P::thetadot(th, w),
                                    P::thetaddot(th, thd, w),
                                    P::from_rotation(P::rotation(th)),
                                    P::from_quaternion(P::to_quaternion(th)),
                                    P::canonical(th)};
      const Eigen::Vector3d omega_d = P::G(th_d) * Eigen::Vector3d(0.1, 0.4, 0.7);
      CHECK(rel_err(Eigen::Vector3d(omega(0).value(), omega(1).value(), omega(2).value()),
                    omega_d) < 4 * eps<double>());
      for (const auto& v : values) {
        for (int i = 0; i < 3; ++i) {
          CHECK(std::isfinite(v(i).value()));
          CHECK(tumble::detail::all_finite(v(i).derivatives()));
        }
      }
      CHECK(std::isfinite(P::singularity_distance(th).value()));
    }
  }
}

TEST_CASE("Gibbs AD derivative of the distance to the singularity", "[orientation][rodrigues]") {
  // d/dt of the distance along thetadot, against central differences in long double.
  tumble::test::Random rnd(77);
  for (const double phi : {0.5, 1.5, 2.5, 3.0}) {
    const Eigen::Vector3d n = rnd.vector().normalized();
    const Eigen::Vector3d th = (std::tan(phi / 2)) * n;
    const Eigen::Vector3d thd = rnd.vector();
    const AD dist = P::singularity_distance(along(th, thd));
    const Vector3ld thl = th.cast<LD>(), thdl = thd.cast<LD>();
    const LD fd = five_point_derivative(
        [&](LD t) {
          return Eigen::Matrix<LD, 1, 1>(P::singularity_distance(Vector3ld(thl + t * thdl)));
        },
        1e-4L * std::min(1.0L, thl.norm() / thdl.norm()))(0);  // |.| varies on the scale |theta|
    INFO("phi = " << phi);
    CHECK(std::abs(ad_derivative(dist) - fd) <
          64 * eps<double>() * std::max(1.0L, std::abs(fd)) + kFivePointTol);
  }
}
