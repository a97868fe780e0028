// Tests of include/tumble/orientation/modified_rodrigues.hpp: modified Rodrigues parameters
// s = n tan(phi/4) and their shadow set.
//
// Every expected value comes from an independent source: Eigen::AngleAxis for R and the
// quaternion (s is built from (phi, n) by its definition), central finite differences in long
// double for R^T Rdot, Gdot sdot and the rate of the shadow set, Eigen's AutoDiffScalar, the
// identities G G^-1 = I and G sddot = alpha - Gdot sdot (Eq. 1.10), and closed-form angles.
// Reference chapter: Chapter 1, "Rigid body", Eqs. (1.1), (1.5), (1.10).

#include "tumble/orientation/modified_rodrigues.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <unsupported/Eigen/AutoDiff>

#include "support/axis_angle_sample.hpp"
#include "support/catch.hpp"
#include "support/finite_difference.hpp"
#include "support/numeric.hpp"
#include "support/random.hpp"
#include "tumble/core/math.hpp"

namespace {

using P = tumble::ModifiedRodriguesParameters;
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

/// The MRP vector by its definition s = n tan(phi/4) (|s| > 1 beyond pi), and the angle of a
/// given s.
struct MrpDefinition {
  static LD magnitude(LD phi) { return std::tan(phi / 4); }
  static LD angle(LD norm) { return 4 * std::atan(norm); }
};
template <class S> using Sample = tumble::test::AxisAngleSample<S, MrpDefinition>;

/// Random attitudes with phi up to phi_max (|s| > 1 beyond pi), plus a few fixed ones.
template <class S> std::vector<Sample<S>> samples(LD phi_max, int count) {
  return tumble::test::axis_angle_samples<Sample<S>>(
      815, {{0.3L, Vector3ld(1, 0, 0)}, {2.0L, Vector3ld(0, 1, 0)}, {phi_max, Vector3ld(1, -2, 3)}},
      phi_max, count);
}

}  // namespace

TEMPLATE_TEST_CASE("MRP R matches Eigen::AngleAxis and is a rotation",
                   "[orientation][modified_rodrigues]", float, double, long double) {
  using S = TestType;
  for (const auto& s : samples<S>(1.95L * kPi, 40)) {
    const Matrix3<S> r = P::rotation(s.coords);
    CHECK(rel_err(r, s.reference_rotation()) < 16 * eps<S>());
    const Matrix3ld rl = r.template cast<LD>();
    CHECK((rl.transpose() * rl - Matrix3ld::Identity()).norm() < 16 * eps<S>());
    CHECK(std::abs(rl.determinant() - 1) < 16 * eps<S>());
  }
}

TEMPLATE_TEST_CASE("MRP G, Gdot sdot and the inverse map against finite differences",
                   "[orientation][modified_rodrigues]", float, double) {
  using S = TestType;
  tumble::test::Random rnd(99);
  // Both sides of |s| = 1: phi up to 1.6 pi, |s| up to tan(0.4 pi) = 3.1.
  for (const auto& s : samples<S>(1.6L * kPi, 30)) {
    const Vector3<S> sd = rnd.vector().cast<S>();
    const Vector3ld sl = s.coords.template cast<LD>(), sdl = sd.template cast<LD>();
    // G = 4 / (1 + s.s)^2 M with M^T M = (1 + s.s)^2 I: a scaled rotation, condition number 1.
    const LD scale = 1 + sl.squaredNorm();
    const LD tol = 64 * scale * eps<S>() + kFivePointTol;

    // S(G sdot) = R^T Rdot, Rdot by finite differences of R (Eq. 1.5).
    const Matrix3ld rdot = five_point_derivative(
        [&](LD t) { return Matrix3ld(P::rotation(Vector3ld(sl + t * sdl))); });
    const Matrix3ld wx = P::rotation(sl).transpose() * rdot;
    const Vector3ld omega_fd(wx(2, 1), wx(0, 2), wx(1, 0));
    const Vector3<S> omega = P::G(s.coords) * sd;
    CHECK(rel_err(omega, omega_fd) < tol);
    CHECK((wx + wx.transpose()).norm() < kFivePointTol);  // R^T Rdot is skew

    // Gdot sdot by finite differences of G (Eq. 1.10).
    const Vector3ld gdot_fd =
        five_point_derivative([&](LD t) { return Vector3ld(P::G(Vector3ld(sl + t * sdl)) * sdl); });
    CHECK(rel_err(P::Gdot_thetadot(s.coords, sd), gdot_fd) < tol);

    // The inverse map, both ways, and the accelerations: G sddot + Gdot sdot = alpha.
    const Vector3<S> w = rnd.vector().cast<S>();
    const Vector3<S> alpha = rnd.vector().cast<S>();
    CHECK(rel_err(P::G(s.coords) * P::thetadot(s.coords, w), w) < 16 * eps<S>());
    CHECK(rel_err(P::thetadot(s.coords, omega), sd) < 16 * eps<S>());
    const Vector3<S> sdd = P::thetaddot(s.coords, sd, alpha);
    CHECK(rel_err(Vector3<S>(P::G(s.coords) * sdd + P::Gdot_thetadot(s.coords, sd)), alpha) <
          64 * eps<S>());
  }
}

TEST_CASE("MRP AD derivatives of R and G sdot", "[orientation][modified_rodrigues]") {
  tumble::test::Random rnd(5);
  std::vector<Eigen::Vector3d> points{Eigen::Vector3d::Zero(), Eigen::Vector3d(1e-8, -2e-8, 0)};
  for (const auto& s : samples<double>(1.8L * kPi, 20)) {
    points.push_back(s.coords);
  }
  for (const auto& s : points) {
    const Eigen::Vector3d sd = rnd.vector();
    const Vector3<AD> sa = along(s, sd);
    // d/dt R(s + t sdot) = R S(G sdot)  (S(omega) = R^T Rdot, Eq. 1.5).
    const Matrix3<AD> ra = P::rotation(sa);
    Eigen::Matrix3d rdot;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        rdot(i, j) = ad_derivative(ra(i, j));
      }
    }
    const Eigen::Vector3d omega = P::G(s) * sd;
    const double scale = 1 + s.squaredNorm();
    CHECK(rel_err(rdot, Eigen::Matrix3d(P::rotation(s) * tumble::skew(omega))) <
          64 * eps<double>());
    // d/dt (G(s + t sdot) sdot) = Gdot sdot.
    const Vector3<AD> wa = P::G(sa) * sd.cast<AD>();
    const Eigen::Vector3d gdot_ad(ad_derivative(wa(0)), ad_derivative(wa(1)), ad_derivative(wa(2)));
    CHECK(rel_err(P::Gdot_thetadot(s, sd), gdot_ad) < 64 * scale * eps<double>());
    // The shadow rate is the derivative of the shadow set along sdot.
    if (s.squaredNorm() > 0) {
      const Vector3<AD> sha = P::shadow(sa);
      const Eigen::Vector3d shd(ad_derivative(sha(0)), ad_derivative(sha(1)),
                                ad_derivative(sha(2)));
      CHECK(rel_err(P::shadow_rate(s, sd), shd) < 16 * eps<double>());
    }
  }
}

TEMPLATE_TEST_CASE("MRP round trips through R and the quaternion",
                   "[orientation][modified_rodrigues]", float, double, long double) {
  using S = TestType;
  for (const auto& s : samples<S>(1.9L * kPi, 40)) {
    const Vector3<S> c = P::canonical(s.coords);  // the set with |s| <= 1
    CHECK(c.template cast<LD>().norm() <= 1);
    CHECK(rel_err(P::from_rotation(P::rotation(s.coords)), c) < 32 * eps<S>());
    const Eigen::Quaternion<S> q = P::to_quaternion(s.coords);
    CHECK(rel_err(P::from_quaternion(q), c) < 32 * eps<S>());
    // Against Eigen: q = (cos(phi/2), n sin(phi/2)), e0 < 0 beyond phi = pi (|s| > 1).
    const Eigen::Quaternion<LD> qe(Eigen::AngleAxis<LD>(s.phi, s.n));
    CHECK(rel_err(q.coeffs(), qe.coeffs()) < 8 * eps<S>());
    // s from q does not depend on the sign or the norm of q.
    const Eigen::Quaternion<S> q2(S(-0.4) * q.w(), S(-0.4) * q.x(), S(-0.4) * q.y(),
                                  S(-0.4) * q.z());
    CHECK(rel_err(P::from_quaternion(q2), c) < 32 * eps<S>());
  }
  CHECK_THROWS_AS(P::from_quaternion(Eigen::Quaternion<S>(S(0), S(0), S(0), S(0))),
                  std::domain_error);
}

TEMPLATE_TEST_CASE("MRP shadow set: same attitude, same angular velocity",
                   "[orientation][modified_rodrigues]", float, double) {
  using S = TestType;
  tumble::test::Random rnd(31);
  for (const auto& s : samples<S>(1.9L * kPi, 40)) {
    if (s.phi < 1e-3L) {
      continue;  // the shadow of a near-identity is near infinity; tested below
    }
    const Vector3<S> sh = P::shadow(s.coords);
    const Vector3ld sl = s.coords.template cast<LD>();
    // -s / |s|^2 is the rotation by phi - 2 pi about n: |shadow| = 1 / |s|, opposite direction.
    CHECK(rel_err(sh, Vector3ld(-sl / sl.squaredNorm())) < 4 * eps<S>());
    CHECK(rel_err(P::rotation(sh), s.reference_rotation()) < 16 * eps<S>());
    CHECK(rel_err(P::shadow(sh), s.coords) < 8 * eps<S>());

    // Same omega: G(s^S) sdot^S = G(s) sdot, and sdot^S = G(s^S)^-1 omega. G is a scaled
    // rotation (condition number 1), so both hold to a few roundings relative to their size.
    const Vector3<S> sd = rnd.vector().cast<S>();
    const Vector3<S> shd = P::shadow_rate(s.coords, sd);
    const Vector3<S> omega = P::G(s.coords) * sd;
    CHECK(rel_err(Vector3<S>(P::G(sh) * shd), omega) < 32 * eps<S>());
    CHECK(rel_err(shd, P::thetadot(sh, omega)) < 32 * eps<S>());
    // And it is the time derivative of the shadow set (finite differences, with the step scaled
    // to |s| since -s / |s|^2 varies on that length scale).
    const Vector3ld shd_fd = five_point_derivative(
        [&](LD t) { return Vector3ld(P::shadow(Vector3ld(sl + t * sd.template cast<LD>()))); },
        1e-4L * std::min(1.0L, sl.norm()));
    CHECK(rel_err(shd, shd_fd) < 32 * eps<S>() + kFivePointTol);
  }
  CHECK_THROWS_AS(P::shadow(Vector3<S>(Vector3<S>::Zero())), std::domain_error);
  CHECK_THROWS_AS(P::shadow_rate(Vector3<S>(Vector3<S>::Zero()), Vector3<S>(Vector3<S>::UnitX())),
                  std::domain_error);
}

TEMPLATE_TEST_CASE("MRP canonical() switches to the shadow set beyond |s| = 1",
                   "[orientation][modified_rodrigues]", float, double) {
  using S = TestType;
  const Vector3<S> n = Vector3<S>(S(2), S(-3), S(6)) / S(7);
  // Just inside, exactly on and just outside the unit sphere (phi = pi -+ ~4 sqrt(eps)).
  const S d = S(16) * std::sqrt(std::numeric_limits<S>::epsilon());
  const Vector3<S> inside = (S(1) - d) * n, outside = (S(1) + d) * n;
  CHECK(P::canonical(inside) == inside);
  CHECK(P::canonical(Vector3<S>(Vector3<S>::UnitY())) == Vector3<S>::UnitY());  // |s| = 1 is kept
  const Vector3<S> c = P::canonical(outside);
  CHECK(c.norm() < S(1));
  CHECK(rel_err(c, Vector3<S>(-n / (S(1) + d))) < 8 * eps<S>());  // |n|^2 = 1 + O(eps)
  CHECK(rel_err(P::rotation(c), P::rotation(outside)) < 16 * eps<S>());
  // Canonical sets are at least pi from the singularity.
  CHECK(P::singularity_distance(c) >= S(3.14159));
  CHECK(P::singularity_distance(outside) < S(3.1416));
  CHECK(P::singularity_distance(P::canonical(Vector3<S>(S(50), S(0), S(0)))) > S(3.1));
}

TEMPLATE_TEST_CASE("MRP at and near zero", "[orientation][modified_rodrigues]", float, double) {
  using S = TestType;
  const Vector3<S> zero = Vector3<S>::Zero();
  CHECK(P::rotation(zero) == Matrix3<S>::Identity());
  CHECK(P::G(zero) == S(4) * Matrix3<S>::Identity());
  CHECK(P::thetadot(zero, Vector3<S>(S(4), S(8), S(-4))) == Vector3<S>(S(1), S(2), S(-1)));
  CHECK(P::from_quaternion(Eigen::Quaternion<S>::Identity()) == zero);
  CHECK(P::canonical(zero) == zero);
  CHECK(static_cast<double>(P::singularity_distance(zero)) ==
        Approx(2 * std::acos(-1.0)).epsilon(4 * static_cast<double>(eps<S>())));

  // phi = 4e-8: R = I + 4 S(s) + O(s^2).
  const Vector3<S> s(S(0), S(1e-8), S(0));
  const Matrix3ld expected =
      Eigen::AngleAxis<LD>(4 * std::atan(static_cast<LD>(s(1))), Vector3ld::UnitY())
          .toRotationMatrix();
  CHECK(rel_err(P::rotation(s), expected) < 4 * eps<S>());
  CHECK(rel_err(P::from_quaternion(P::to_quaternion(s)), s) < 4 * eps<S>());
  CHECK(std::abs(static_cast<LD>(P::singularity_distance(s)) -
                 (2 * kPi - 4 * static_cast<LD>(s(1)))) < 8 * eps<S>());
}

TEMPLATE_TEST_CASE("MRP near the 360 degree singularity", "[orientation][modified_rodrigues]",
                   float, double, long double) {
  using S = TestType;
  // phi = 2 pi - 1e-5 rad: |s| = cot(2.5e-6) ~ 4e5.
  const Sample<S> s(2 * kPi - 1e-5L, Vector3ld(2, -3, 6));
  const LD sn = s.coords.template cast<LD>().norm();
  CHECK(rel_err(P::rotation(s.coords), s.reference_rotation()) < 16 * eps<S>());
  // 2 pi - phi = 4 atan(1 / |s|), to full relative accuracy.
  const LD dist = 4 * std::atan(1 / sn);
  CHECK(std::abs(static_cast<LD>(P::singularity_distance(s.coords)) - dist) < 8 * eps<S>() * dist);
  CHECK(static_cast<double>(dist) == Approx(1e-5).epsilon(1e-3));
  // The shadow set is a near-identity set with the same R, far from the singularity.
  const Vector3<S> c = P::canonical(s.coords);
  CHECK(static_cast<LD>(c.norm()) < 1e-5L);
  CHECK(rel_err(P::rotation(c), s.reference_rotation()) < 16 * eps<S>());
  CHECK(P::singularity_distance(c) > S(6.28));
  // The maps stay mutually inverse (G is a scaled rotation).
  const Vector3<S> w(S(0.3), S(-0.1), S(0.2));
  CHECK(rel_err(P::G(s.coords) * P::thetadot(s.coords, w), w) < 16 * eps<S>());
}

TEST_CASE("MRP AD with constant and variable arguments mixed",
          "[orientation][modified_rodrigues]") {
  // Eigen's AutoDiffScalar gives constants empty derivative vectors; every function must accept
  // any mix of constant and variable arguments (9 derivatives: theta, thetadot, omega).
  const auto make = [](const Eigen::Vector3d& x, bool variable, int first) {
    Vector3<AD> r;
    for (int i = 0; i < 3; ++i) {
      r(i) = variable ? AD(x(i), 9, first + i) : AD(x(i));
    }
    return r;
  };
  for (const double scale : {0.0, 1e-8, 1.0, 20.0}) {
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

TEST_CASE("MRP AD derivative of the distance to the singularity",
          "[orientation][modified_rodrigues]") {
  // d/dt of the distance along thetadot, against central differences in long double.
  tumble::test::Random rnd(77);
  for (const double phi : {0.5, 1.5, 2.5, 3.5, 5.0, 6.0}) {
    const Eigen::Vector3d n = rnd.vector().normalized();
    const Eigen::Vector3d th = (std::tan(phi / 4)) * n;
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
