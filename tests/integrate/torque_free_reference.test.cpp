// Tests of the analytic torque-free reference (tests/support/torque_free.hpp), each against an
// independent expectation:
//  - Jacobi elliptic functions: two algorithms against each other, the identities sn^2 + cn^2 = 1
//  and dn^2 + m sn^2 = 1, the
//    derivatives d sn/du = cn dn, d cn/du = -sn dn, d dn/du = -m sn cn (Richardson finite
//    differences), the limits m = 0 (sin, cos, 1) and m -> 1 (tanh, sech, sech), K(0) = pi/2,
//    K(1/2) = Gamma(1/4)^2 / (4 sqrt(pi)), F(pi/2|m) = K(m), am(F(phi|m)) = phi, and values from
//    Python's mpmath at 50 digits;
//  - omega(t): omega(0) = omega0, conservation of 2T and H^2, the Euler equations by finite
//    differences, the half-period symmetry (w_a, w_b, w_c) -> (-w_a, -w_b, w_c), and a classical
//    RK4 integration of the Euler equations in long double;
//  - R(t): R(0) = R0, orthogonality, S(omega) = R^T Rdot by finite differences, R I omega = h
//    constant, RK4 of the quaternion kinematics qdot = 1/2 q (x) (0, omega) with the closed-form
//    omega, RK4 of the full Euler + quaternion system, and (key case) mpmath's Taylor-series ODE
//    solver at 30 digits.
// The [.report] test prints the key case's numbers (run: test_integrate "[report]").

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <type_traits>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "support/catch.hpp"
#include "support/random.hpp"
#include "support/torque_free.hpp"

namespace {

using tumble::test::TorqueFreeBody;
using Vec3L = TorqueFreeBody::Vec3L;
using Mat3L = TorqueFreeBody::Mat3L;
using Vec4L = Eigen::Matrix<long double, 4, 1>;

constexpr long double kEpsLd = std::numeric_limits<long double>::epsilon();
constexpr double kEps = std::numeric_limits<double>::epsilon();

// ---- quaternion helpers (scalar first, Hamilton), independent of the reference ---------------

Mat3L rotation_of(const Vec4L& q) {
  const long double e0 = q(0), e1 = q(1), e2 = q(2), e3 = q(3);
  Mat3L r;
  r << e0 * e0 + e1 * e1 - e2 * e2 - e3 * e3, 2 * (e1 * e2 - e0 * e3), 2 * (e1 * e3 + e0 * e2),  //
      2 * (e1 * e2 + e0 * e3), e0 * e0 - e1 * e1 + e2 * e2 - e3 * e3, 2 * (e2 * e3 - e0 * e1),   //
      2 * (e1 * e3 - e0 * e2), 2 * (e2 * e3 + e0 * e1), e0 * e0 - e1 * e1 - e2 * e2 + e3 * e3;
  return r;
}

/// qdot = 1/2 q (x) (0, w).
Vec4L quaternion_rate(const Vec4L& q, const Vec3L& w) {
  const Vec3L v = q.tail<3>();
  Vec4L d;
  d(0) = -v.dot(w);
  d.tail<3>() = q(0) * w + v.cross(w);
  return 0.5L * d;
}

Mat3L skew(const Vec3L& a) {
  Mat3L s;
  s << 0, -a(2), a(1),  //
      a(2), 0, -a(0),   //
      -a(1), a(0), 0;
  return s;
}

long double max_abs(const Mat3L& m) { return m.cwiseAbs().maxCoeff(); }

/// The geodesic angle between two rotations, in long double.
long double angle_between(const Mat3L& a, const Mat3L& b) {
  const Mat3L d = a.transpose() * b;
  const Vec3L ax(d(2, 1) - d(1, 2), d(0, 2) - d(2, 0), d(1, 0) - d(0, 1));
  return std::atan2(0.5L * ax.norm(), 0.5L * (d.trace() - 1.0L));
}

/// A double quaternion as a unit quaternion in long double (normalized in long double, so that
/// rotation_of() is orthogonal to long double precision).
Vec4L to_ld(const Eigen::Quaterniond& q) {
  const Vec4L v(q.w(), q.x(), q.y(), q.z());
  return v / v.norm();
}

/// Classical RK4 in long double of qdot = 1/2 q (x) (0, omega(t)) with the closed-form omega.
Vec4L rk4_kinematics(const TorqueFreeBody& body, Vec4L q, long double t_end, int steps) {
  const long double h = t_end / steps;
  Vec3L w_start = body.omega_ld(0.0L);
  for (int n = 0; n < steps; ++n) {
    const long double t = h * n;
    const Vec3L w_mid = body.omega_ld(t + 0.5L * h);
    const Vec3L w_end = body.omega_ld(t + h);
    const Vec4L k1 = quaternion_rate(q, w_start);
    const Vec4L k2 = quaternion_rate(q + 0.5L * h * k1, w_mid);
    const Vec4L k3 = quaternion_rate(q + 0.5L * h * k2, w_mid);
    const Vec4L k4 = quaternion_rate(q + h * k3, w_end);
    q += h / 6.0L * (k1 + 2.0L * k2 + 2.0L * k3 + k4);
    w_start = w_end;
  }
  return q / q.norm();
}

struct FullState {
  Vec3L w;
  Vec4L q;
};

/// Classical RK4 in long double of the Euler equations I wdot = (I w) x w with the quaternion
/// kinematics: uses no part of the reference.
FullState rk4_full(const Vec3L& inertia, FullState y, long double t_end, int steps) {
  const long double h = t_end / steps;
  const auto f = [&](const FullState& s) {
    const Vec3L iw = inertia.cwiseProduct(s.w);
    return FullState{iw.cross(s.w).cwiseQuotient(inertia), quaternion_rate(s.q, s.w)};
  };
  const auto axpy = [](const FullState& s, long double a, const FullState& d) {
    return FullState{s.w + a * d.w, s.q + a * d.q};
  };
  for (int n = 0; n < steps; ++n) {
    const FullState k1 = f(y);
    const FullState k2 = f(axpy(y, 0.5L * h, k1));
    const FullState k3 = f(axpy(y, 0.5L * h, k2));
    const FullState k4 = f(axpy(y, h, k3));
    y.w += h / 6.0L * (k1.w + 2.0L * k2.w + 2.0L * k3.w + k4.w);
    y.q += h / 6.0L * (k1.q + 2.0L * k2.q + 2.0L * k3.q + k4.q);
  }
  y.q /= y.q.norm();
  return y;
}

// ---- finite differences ----------------------------------------------------------------------

/// A derivative and a bound on its error (max-abs over the entries).
template <class M> struct Derivative {
  M value;
  long double error;
};

template <class M> long double max_abs_any(const M& m) {
  if constexpr (std::is_arithmetic_v<M>) {
    return std::fabs(static_cast<long double>(m));
  } else {
    return m.cwiseAbs().maxCoeff();
  }
}

/// d/dh f(h) at h = 0, f: long double -> fixed-size long double matrix, by central differences
/// D(h) = (f(h) - f(-h)) / (2h) at h0, h0/2, ..., h0/16 and Neville's scheme on them (D is even
/// in h: T[i][j] = T[i][j-1] + (T[i][j-1] - T[i-1][j-1]) / (4^j - 1)). error = the size of the
/// last correction (the truncation left) + the rounding of f, 3 eps_ld max|f| / (h0/16) (the
/// weights sum to < 3).
template <class F> auto richardson_derivative(F&& f, long double h0) {
  using M = std::decay_t<decltype(f(0.0L))>;
  constexpr int kLevels = 5;
  M t[kLevels][kLevels];
  long double f_scale = 0;
  long double h = h0;
  for (int i = 0; i < kLevels; ++i, h /= 2) {
    const M fp = f(h), fm = f(-h);
    f_scale = std::max({f_scale, max_abs_any(fp), max_abs_any(fm)});
    t[i][0] = (fp - fm) / (2 * h);
    long double factor = 1;
    for (int j = 1; j <= i; ++j) {
      factor *= 4;
      t[i][j] = t[i][j - 1] + (t[i][j - 1] - t[i - 1][j - 1]) / (factor - 1);
    }
  }
  const int n = kLevels - 1;
  const long double rounding =
      3 * std::numeric_limits<long double>::epsilon() * f_scale / (h0 / 16);
  return Derivative<M>{t[n][n], max_abs_any(M(t[n][n] - t[n][n - 1])) + rounding};
}

/// First step of the Richardson differences below (h0 ~ 1/4 of the time on which the functions
/// vary; steps h0 ... h0 / 16).
constexpr long double kH0 = 0.1L;

/// The part of a Richardson derivative's error that comes from rounding the ARGUMENT:
/// richardson_derivative() bounds the rounding of f relative to |f|; a function of a large argument
/// x (here u or t, and the reduction modulo the period) is moreover shifted by ~eps_ld |x| along
/// its slope, |f(x)| noise ~ 2 eps_ld |x| |f'|, which the quotients (weights < 3) divide by the
/// smallest step h0 / 16.
long double argument_noise(long double x_scale, long double slope) {
  return 3 * 2 * kEpsLd * x_scale * slope / (kH0 / 16);
}

/// The argument scale of omega(t) or R(t): |t| plus, in u = u0 + lambda t, |u0| / lambda and the
/// period (reduction of u modulo 4K), in time units.
long double time_scale(const tumble::test::TorqueFreeBody& body, long double t) {
  const long double lam = body.frequency_lambda();
  long double s = std::fabs(t);
  if (lam > 0) s += std::fabs(body.initial_argument_u0()) / lam;
  if (std::isfinite(body.period_ld())) s += body.period_ld();
  return s;
}

struct Case {
  const char* name;
  Vec3L inertia;
  Vec3L omega0;
};

/// The motions every property is checked on: both elliptic regimes, every order of the moments,
/// sign patterns, the near-separatrix key case, nearly pure spins, an axisymmetric body, and the
/// exact separatrix (I = (1, 5, 9), w1 = 3 w3 makes H^2 = 2 T I_mid exactly in binary).
std::vector<Case> cases() {
  return {
      {"key case: minor-axis regime near the separatrix", Vec3L(1, 2, 3), Vec3L(0.1L, 2.0L, 0.05L)},
      {"key case mirrored: negative components", Vec3L(1, 2, 3), Vec3L(-0.1L, 2.0L, -0.05L)},
      {"major-axis regime", Vec3L(1, 2, 3), Vec3L(0.4L, -0.7L, 1.1L)},
      {"minor-axis regime, moments (3, 1, 2)", Vec3L(3, 1, 2), Vec3L(-0.3L, 1.2L, 0.5L)},
      {"major-axis regime, moments (2, 3, 1)", Vec3L(2, 3, 1), Vec3L(0.6L, 0.9L, -0.4L)},
      {"minor-axis regime, moments (3, 2, 1)", Vec3L(3, 2, 1), Vec3L(0.2L, -0.5L, -1.5L)},
      {"major-axis regime, moments (1.5, 0.4, 0.9)", Vec3L(1.5L, 0.4L, 0.9L),
       Vec3L(-1.0L, 0.3L, 0.8L)},
      {"nearly pure spin about the major axis", Vec3L(1, 2, 3), Vec3L(1e-4L, -2e-4L, 1.5L)},
      {"nearly pure spin about the minor axis", Vec3L(1, 2, 3), Vec3L(-1.5L, 1e-4L, 1e-4L)},
      {"intermediate component zero", Vec3L(1, 2, 3), Vec3L(0.5L, 0, -0.5L)},
      {"minor-axis component zero", Vec3L(1, 2, 3), Vec3L(0, 1.0L, 0.5L)},
      {"axisymmetric (I1 = I2)", Vec3L(2, 2, 1), Vec3L(0.5L, -0.3L, 1.2L)},
      {"axisymmetric (I1 = I3), prolate", Vec3L(1, 0.2L, 1), Vec3L(0.7L, 1.1L, -0.2L)},
      {"exact separatrix", Vec3L(1, 5, 9), Vec3L(0.375L, 0.5L, 0.125L)},
  };
}

struct KeyCaseReference {
  long double t;
  Vec3L w;
  Mat3L r;
};

/// The key case, I = diag(1, 2, 3), omega0 = (0.1, 2.0, 0.05) (the double values), R0 = I, at
/// t = 10 and 50 s: the Euler equations and qdot = 1/2 q (x) (0, omega) integrated by mpmath's
/// Taylor-series ODE solver, mp.odefun(f, 0, y0, tol=1e-28, degree=30) at mp.mp.dps = 30 (76 s),
/// q normalized at the end; printed with 25 digits.
std::vector<KeyCaseReference> key_case_mpmath() {
  std::vector<KeyCaseReference> refs(2);
  refs[0].t = 10;
  refs[0].w << 0.05020076040766744799486521L, -2.001869097532226748347562L,
      0.00258948807733828102304279L;
  refs[0].r << 0.9921862490795175689509848L, -0.01277696853108752683041759L,
      -0.1241096136996369878977681L,  //
      -0.00758441000318885809790647L, -0.9990794987542527537597126L,
      0.04222122563183829501201897L,  //
      -0.1245348299168592065292448L, -0.04095002129555819040884946L, -0.9913698461691641949694115L;
  refs[1].t = 50;
  refs[1].w << 1.650904600046258680380823L, 1.133364019874507338176781L,
      0.9527129680468469646112172L;
  refs[1].r << 0.9000533996465422205605871L, -0.06882941471809660784447909L,
      -0.4303096436919186897419751L,  //
      0.3823870434857255829373885L, 0.5983383115004304018325621L,
      0.7041103705847966900578395L,  //
      0.2090072409246807989238376L, -0.7982817652059817544208457L, 0.5648559078036400017454616L;
  return refs;
}

void check_jacobi_identities(long double m, long double m1) {
  for (long double u = -60.0L; u <= 60.0L; u += 0.731L) {
    const auto f = tumble::test::jacobi_sn_cn_dn(u, m, m1);
    INFO("m = " << static_cast<double>(m) << ", u = " << static_cast<double>(u));
    CHECK(std::fabs(f.sn * f.sn + f.cn * f.cn - 1.0L) < 8 * kEpsLd);
    CHECK(std::fabs(f.dn * f.dn + m * f.sn * f.sn - 1.0L) < 8 * kEpsLd);
    CHECK(f.dn > 0.0L);
  }
}

}  // namespace

// ==== Elliptic functions =======================================================================

TEST_CASE("Jacobi sn, cn, dn satisfy sn^2 + cn^2 = 1 and dn^2 + m sn^2 = 1",
          "[integrate][reference]") {
  for (const long double m : {0.0L, 1e-12L, 0.1L, 0.5L, 0.9L, 0.999L})
    check_jacobi_identities(m, 1 - m);
  // m near 1 with the complementary parameter given exactly.
  for (const long double m1 : {1e-3L, 1e-9L, 1e-15L, 0.0L}) check_jacobi_identities(1 - m1, m1);
  // The double interface.
  const auto f = tumble::test::jacobi_sn_cn_dn(3.7, 0.8);
  CHECK(std::fabs(f.sn * f.sn + f.cn * f.cn - 1.0) < 4 * kEps);
  CHECK(std::fabs(f.dn * f.dn + 0.8 * f.sn * f.sn - 1.0) < 4 * kEps);
}

TEST_CASE("Jacobi sn, cn, dn: Bulirsch's and the amplitude recursion (A&S 16.4.3) agree",
          "[integrate][reference]") {
  for (const long double m1 : {1.0L, 0.9L, 0.5L, 0.1L, 1e-3L, 1e-9L, 1e-15L, 1e-25L}) {
    const long double m = 1 - m1;
    const tumble::test::JacobiElliptic jacobi(m, m1);
    CHECK(jacobi.k() == tumble::test::elliptic_k(m, m1));
    for (long double u = -60.0L; u <= 60.0L; u += 0.377L) {
      const auto f = jacobi(u);
      const auto g = jacobi.by_amplitude(u);
      INFO("m1 = " << static_cast<double>(m1) << ", u = " << static_cast<double>(u));
      // Both reduce u (explicitly or inside sin and cos): a few ulps of |u|.
      const long double tol = 16 * kEpsLd * (1 + std::fabs(u));
      CHECK(std::fabs(f.sn - g.sn) < tol);
      CHECK(std::fabs(f.cn - g.cn) < tol);
      CHECK(std::fabs(f.dn - g.dn) < tol);
    }
  }
}

TEST_CASE("Jacobi sn, cn, dn have the derivatives cn dn, -sn dn, -m sn cn",
          "[integrate][reference]") {
  for (const long double m : {0.3L, 0.9L, 0.999L, 1.0L - 1e-10L}) {
    const long double m1 = 1 - m;
    for (const long double u : {-7.3L, 0.2L, 1.9L, 4.4L, 33.3L}) {
      const auto v = [&](long double h) {
        const auto f = tumble::test::jacobi_sn_cn_dn(u + h, m, m1);
        return Vec3L(f.sn, f.cn, f.dn);
      };
      const auto d = richardson_derivative(v, kH0);
      const auto f = tumble::test::jacobi_sn_cn_dn(u, m, m1);
      const Vec3L expected(f.cn * f.dn, -f.sn * f.dn, -m * f.sn * f.cn);
      const long double noise =
          argument_noise(std::fabs(u) + 4 * tumble::test::elliptic_k(m, m1), 1.0L);
      INFO("m = " << static_cast<double>(m) << ", u = " << static_cast<double>(u)
                  << ", fd error bound " << static_cast<double>(d.error) << ", argument noise "
                  << static_cast<double>(noise));
      CHECK(d.error < 1e-15L);
      CHECK((d.value - expected).cwiseAbs().maxCoeff() < d.error + noise + 16 * kEpsLd);
    }
  }
}

TEST_CASE("Jacobi functions and K at the limits m = 0 and m -> 1", "[integrate][reference]") {
  using tumble::test::elliptic_k;
  using tumble::test::jacobi_sn_cn_dn;
  for (long double u = -20.0L; u <= 20.0L; u += 0.37L) {
    const auto z = jacobi_sn_cn_dn(u, 0.0L, 1.0L);
    CHECK(z.sn == std::sin(u));
    CHECK(z.cn == std::cos(u));
    CHECK(z.dn == 1.0L);
    // m = 1e-30: the AGM branch; sn = sin u - m/4 (u - sin u cos u) cos u + O(m^2) (A&S 16.13).
    const auto s = jacobi_sn_cn_dn(u, 1e-30L, 1.0L);
    // (plus the reduction of u modulo 4K ~ 2 pi: a few ulps of |u|)
    CHECK(std::fabs(s.sn - std::sin(u)) < 4 * kEpsLd * (1 + std::fabs(u)) + 1e-29L * std::fabs(u));
    CHECK(std::fabs(s.cn - std::cos(u)) < 4 * kEpsLd * (1 + std::fabs(u)) + 1e-29L * std::fabs(u));
    // m1 = 1e-30: sn = tanh u + m1/4 (sinh u cosh u - u) sech^2 u + O(m1^2) (A&S 16.15).
    const auto t = jacobi_sn_cn_dn(u, 1.0L, 1e-30L);
    const long double sech = 1.0L / std::cosh(u);
    CHECK(std::fabs(t.sn - std::tanh(u)) < 8 * kEpsLd);
    CHECK(std::fabs(t.cn - sech) < 8 * kEpsLd);
    CHECK(std::fabs(t.dn - sech) < 8 * kEpsLd);
  }
  const long double pi = std::numbers::pi_v<long double>;
  CHECK(elliptic_k(0.0L, 1.0L) == pi / 2);
  CHECK(std::fabs(elliptic_k(0.0) - std::numbers::pi / 2) <= kEps);
  // K(1/2) = Gamma(1/4)^2 / (4 sqrt(pi)) (A&S 17.3.? lemniscatic case; DLMF 19.20.2).
  const long double g = std::tgamma(0.25L);
  CHECK(std::fabs(elliptic_k(0.5L, 0.5L) - g * g / (4 * std::sqrt(pi))) < 8 * kEpsLd);
  // K -> ln(4 / sqrt(m1)) + m1/4 (ln(4 / sqrt(m1)) - 1) as m1 -> 0 (A&S 17.3.26).
  for (const long double m1 : {1e-12L, 1e-16L, 1e-24L}) {
    const long double l = std::log(4.0L / std::sqrt(m1));
    CHECK(std::fabs(elliptic_k(1 - m1, m1) - (l + m1 / 4 * (l - 1))) < 32 * kEpsLd);
  }
  CHECK(std::isinf(elliptic_k(1.0L, 0.0L)));
}

TEST_CASE("F is the inverse of the amplitude and F(pi/2|m) = K(m)", "[integrate][reference]") {
  using tumble::test::elliptic_f;
  using tumble::test::elliptic_k;
  using tumble::test::jacobi_argument;
  using tumble::test::jacobi_sn_cn_dn;
  const long double pi = std::numbers::pi_v<long double>;
  for (const long double m1 : {0.7L, 0.2L, 1e-3L, 1e-12L}) {
    const long double m = 1 - m1;
    const long double k = elliptic_k(m, m1);
    // pi / 2 in long double is off by up to eps_ld, and dF/dphi = 1 / sqrt(m1) there.
    CHECK(std::fabs(elliptic_f(pi / 2, m, m1) - k) < 16 * kEpsLd * k + kEpsLd / std::sqrt(m1));
    CHECK(std::fabs(elliptic_f(-pi, m, m1) + 2 * k) < 16 * kEpsLd * k);
    for (long double phi = -9.0L; phi <= 9.0L; phi += 0.173L) {
      const long double u = elliptic_f(phi, m, m1);
      const auto f = jacobi_sn_cn_dn(u, m, m1);
      INFO("m1 = " << static_cast<double>(m1) << ", phi = " << static_cast<double>(phi));
      CHECK(std::fabs(f.sn - std::sin(phi)) < 64 * kEpsLd);
      CHECK(std::fabs(f.cn - std::cos(phi)) < 64 * kEpsLd);
      // jacobi_argument returns the same u reduced to (-2K, 2K].
      const long double v = jacobi_argument(std::sin(phi), std::cos(phi), m, m1);
      CHECK(v > -2 * k);
      CHECK(v <= 2 * k);
      const long double reduced = u - 4 * k * std::nearbyint(u / (4 * k));
      CHECK(std::fabs(v - reduced) < 64 * kEpsLd * k);
    }
  }
  // m = 0: F(phi|0) = phi; m = 1: F(phi|1) = atanh(sin phi) for |phi| < pi/2.
  CHECK(std::fabs(elliptic_f(5.0L, 0.0L, 1.0L) - 5.0L) < 8 * kEpsLd);
  CHECK(std::fabs(elliptic_f(1.2L, 1.0L, 0.0L) - std::atanh(std::sin(1.2L))) < 8 * kEpsLd);
}

TEST_CASE("Elliptic functions agree with mpmath", "[integrate][reference]") {
  // Reference values from Python's mpmath at 50 digits (mp.mp.dps = 50) for the double arguments
  // shown, passed exactly (mp.mpf(float)): mp.ellipfun('sn'|'cn'|'dn', u, m=m), mp.ellipk(m),
  // mp.ellipf(phi, m); printed with 22 digits.
  struct Snd {
    double u, m;
    long double sn, cn, dn;
  };
  const Snd snd[] = {
      {0.75, 0.3, 0.6677972623907641837955L, 0.7443432113906869318125L, 0.9307062076203318525331L},
      {2.5, 0.5, 0.8906151882260943559474L, -0.4547577228602044547066L, 0.7767897355465629867958L},
      {7.25, 0.875, -0.9981619673208867570264L, -0.06060269791104186263886L,
       0.3580692686057194618794L},
      {50.0, 0.999, -0.9201146914624828523378L, -0.3916490196016070525139L,
       0.3927283610847898593737L},
      {-3.0, 0.999999, -0.995054995047900579304L, 0.09932550946369494256981L,
       0.09933049362942757392334L},
      {10.0, 0.9993765586034913, 0.1529073326622148063091L, -0.9882405312564986964739L,
       0.9882479061878648963937L},
      {1000.0, 0.25, 0.9539475637558884112775L, -0.2999734081617989264005L,
       0.8789175225247539139473L},
  };
  for (const auto& r : snd) {
    INFO("u = " << r.u << ", m = " << r.m);
    const long double m = r.m;
    const tumble::test::JacobiElliptic jacobi(m, 1 - m);
    // long double: a few ulps times the size of the argument (the reduction modulo 4K).
    const long double tol = 64 * kEpsLd * std::max(1.0L, std::fabs(static_cast<long double>(r.u)));
    for (const auto& f : {jacobi(r.u), jacobi.by_amplitude(r.u)}) {
      CHECK(std::fabs(f.sn - r.sn) < tol);
      CHECK(std::fabs(f.cn - r.cn) < tol);
      CHECK(std::fabs(f.dn - r.dn) < tol);
    }
    const auto d = tumble::test::jacobi_sn_cn_dn(r.u, r.m);  // double: correctly rounded or 1 ulp
    CHECK(std::fabs(d.sn - static_cast<double>(r.sn)) <= kEps);
    CHECK(std::fabs(d.cn - static_cast<double>(r.cn)) <= kEps);
    CHECK(std::fabs(d.dn - static_cast<double>(r.dn)) <= kEps);
  }
  struct Kv {
    double m;
    long double k;
  };
  const Kv ks[] = {{0.3, 1.713889448178791055546L},
                   {0.5, 1.854074677301371918434L},
                   {0.875, 2.473596173751343911976L},
                   {0.999, 4.841132560550296586992L},
                   {0.9999999999990905, 15.24923797232203670879L}};  // 1 - 2^-40
  for (const auto& r : ks) {
    INFO("m = " << r.m);
    const long double m = r.m;
    CHECK(std::fabs(tumble::test::elliptic_k(m, 1 - m) - r.k) < 8 * kEpsLd * r.k);
    CHECK(std::fabs(tumble::test::elliptic_k(r.m) - static_cast<double>(r.k)) <=
          kEps * static_cast<double>(r.k));
  }
  struct Fv {
    double phi, m;
    long double f;
  };
  const Fv fs[] = {{1.2, 0.7, 1.429448433022763339164L},
                   {4.0, 0.95, 6.795850720474278500726L},
                   {-2.5, 0.5, -3.04440847748726132859L},
                   {1.5, 0.999999, 3.340628544301661738388L},
                   {20.0, 0.3, 21.7840759769387339902L}};
  for (const auto& r : fs) {
    INFO("phi = " << r.phi << ", m = " << r.m);
    const long double m = r.m;
    const long double f = tumble::test::elliptic_f(static_cast<long double>(r.phi), m, 1 - m);
    CHECK(std::fabs(f - r.f) < 16 * kEpsLd * std::fabs(r.f));
    CHECK(std::fabs(tumble::test::elliptic_f(r.phi, r.m) - static_cast<double>(r.f)) <=
          kEps * std::fabs(static_cast<double>(r.f)));
  }
}

TEST_CASE("Adaptive Gauss-Legendre quadrature", "[integrate][reference]") {
  using tumble::test::integrate;
  CHECK(std::fabs(integrate([](long double x) { return std::cos(x); }, 0.0L, 10.0L) -
                  std::sin(10.0L)) < 32 * kEpsLd);
  // A narrow peak: int 1 / (1 + 1e4 x^2) over [-1, 2] = (atan(200) + atan(100)) / 100.
  const long double peak =
      integrate([](long double x) { return 1.0L / (1.0L + 1e4L * x * x); }, -1.0L, 2.0L);
  CHECK(std::fabs(peak - (std::atan(200.0L) + std::atan(100.0L)) / 100.0L) < 64 * kEpsLd * peak);
}

// ==== omega(t) =================================================================================

TEST_CASE("Torque-free omega(t): initial value, conservation laws, Euler equations",
          "[integrate][reference]") {
  for (const auto& c : cases()) {
    const TorqueFreeBody body(c.inertia, c.omega0);
    INFO(c.name << " (regime " << static_cast<int>(body.regime())
                << ", m = " << static_cast<double>(body.parameter_m()) << ")");
    const Vec3L& in = c.inertia;
    const long double two_t = c.omega0.dot(in.cwiseProduct(c.omega0));
    const long double h2 = in.cwiseProduct(c.omega0).squaredNorm();
    const long double scale = c.omega0.norm();
    CHECK((body.omega_ld(0.0L) - c.omega0).cwiseAbs().maxCoeff() < 16 * kEpsLd * scale);
    CHECK((body.omega(0.0) - c.omega0.cast<double>()).cwiseAbs().maxCoeff() <= kEps * scale);
    for (long double t = -3.0L; t <= 50.0L; t += 1.37L) {
      const Vec3L w = body.omega_ld(t);
      CHECK(std::fabs(w.dot(in.cwiseProduct(w)) - two_t) < 64 * kEpsLd * two_t);
      CHECK(std::fabs(in.cwiseProduct(w).squaredNorm() - h2) < 64 * kEpsLd * h2);
    }
    for (const long double t : {0.0L, 0.8L, 7.7L, 41.0L}) {
      const auto d =
          richardson_derivative([&](long double h) { return body.omega_ld(t + h); }, kH0);
      const Vec3L expected = body.omega_dot_ld(t);
      const long double noise = argument_noise(time_scale(body, t), expected.norm());
      INFO("t = " << static_cast<double>(t) << ", fd error " << static_cast<double>(d.error)
                  << ", argument noise " << static_cast<double>(noise));
      CHECK(d.error < 1e-14L * scale);
      CHECK((d.value - expected).cwiseAbs().maxCoeff() < d.error + noise + 64 * kEpsLd * scale);
    }
  }
}

TEST_CASE("Torque-free omega(t): period and half-period flip", "[integrate][reference]") {
  for (const auto& c : cases()) {
    const TorqueFreeBody body(c.inertia, c.omega0);
    if (!std::isfinite(body.period_ld())) continue;
    INFO(c.name);
    const long double p = body.period_ld();
    const long double scale = c.omega0.norm();
    const int a = body.axis_a(), b = body.axis_b(), cc = body.axis_c();
    for (const long double t : {0.0L, 1.3L, 5.9L}) {
      const Vec3L w = body.omega_ld(t);
      CHECK((body.omega_ld(t + p) - w).cwiseAbs().maxCoeff() < 1e-16L * scale);
      const Vec3L half = body.omega_ld(t + 0.5L * p);
      CHECK(std::fabs(half(a) + w(a)) < 1e-16L * scale);
      CHECK(std::fabs(half(b) + w(b)) < 1e-16L * scale);
      CHECK(std::fabs(half(cc) - w(cc)) < 1e-16L * scale);
    }
  }
}

// ==== R(t) =====================================================================================

TEST_CASE("Torque-free R(t): R(0) = R0, orthogonality, constant inertial angular momentum",
          "[integrate][reference]") {
  tumble::test::Random rng(7);
  for (const auto& c : cases()) {
    const Mat3L r0 = rotation_of(to_ld(rng.quaternion()));
    const TorqueFreeBody body(c.inertia, c.omega0, r0);
    INFO(c.name);
    CHECK(max_abs(body.rotation_ld(0.0L) - r0) < 16 * kEpsLd);
    const Vec3L h = r0 * c.inertia.cwiseProduct(c.omega0);
    CHECK((body.angular_momentum_ld() - h).cwiseAbs().maxCoeff() < 4 * kEpsLd * h.norm());
    for (long double t = -2.0L; t <= 50.0L; t += 3.1L) {
      const Mat3L r = body.rotation_ld(t);
      CHECK(max_abs(r.transpose() * r - Mat3L::Identity()) < 32 * kEpsLd);
      CHECK(std::fabs(r.determinant() - 1.0L) < 32 * kEpsLd);
      // The quaternion interface: scalar first, e0 >= 0, the same rotation (rounded to double).
      const double td = static_cast<double>(t);
      const Eigen::Vector4d q = body.quaternion(td);
      CHECK(q(0) >= 0.0);
      CHECK(max_abs(rotation_of(q.cast<long double>()) - body.rotation_ld(td)) < 8 * kEps);
      const Vec3L ht = r * c.inertia.cwiseProduct(body.omega_ld(t));
      CHECK((ht - h).cwiseAbs().maxCoeff() < 64 * kEpsLd * h.norm());
    }
  }
}

TEST_CASE("Torque-free R(t): S(omega) = R^T Rdot", "[integrate][reference]") {
  tumble::test::Random rng(11);
  for (const auto& c : cases()) {
    const TorqueFreeBody body(c.inertia, c.omega0, rotation_of(to_ld(rng.quaternion())));
    INFO(c.name);
    for (const long double t : {0.0L, 2.9L, 17.2L, 44.4L}) {
      const auto d =
          richardson_derivative([&](long double h) { return body.rotation_ld(t + h); }, kH0);
      const Mat3L s = body.rotation_ld(t).transpose() * d.value;
      // R also carries the quadrature's rounding, ~32 eps_ld |psi| (rel_tol of integrate()).
      const long double noise = argument_noise(time_scale(body, t), body.omega_ld(t).norm()) +
                                3 * 32 * kEpsLd * std::fabs(body.psi_ld(t)) / (kH0 / 16);
      INFO("t = " << static_cast<double>(t) << ", fd error " << static_cast<double>(d.error)
                  << ", argument noise " << static_cast<double>(noise));
      CHECK(d.error < 1e-14L);
      CHECK(max_abs(s - skew(body.omega_ld(t))) < d.error + noise + 64 * kEpsLd * c.omega0.norm());
    }
  }
}

TEST_CASE("Torque-free omega(t) and R(t) agree with RK4 of the kinematics and of the full system",
          "[integrate][reference]") {
  // (1) qdot = 1/2 q (x) (0, omega(t)) with the closed-form omega; (2) the Euler equations
  // I wdot = (I w) x w and the kinematics together (no part of the reference). RK4 in long double,
  // h = 1/2000 s over 10 s: global error ~ (|omega| h)^4 t, below 3e-14 here (it falls 16-fold
  // per halving of h from 1/500 s on), the rounding 2e4 x 1e-19 far below that. Check < 1e-12.
  tumble::test::Random rng(13);
  for (const auto& c : cases()) {
    const Vec4L q0 = to_ld(rng.quaternion());
    const TorqueFreeBody body(c.inertia, c.omega0, rotation_of(q0));
    INFO(c.name);
    const Mat3L r10 = body.rotation_ld(10.0L);
    const FullState y = rk4_full(c.inertia, {c.omega0, q0}, 10.0L, 20000);
    const long double ew = (y.w - body.omega_ld(10.0L)).cwiseAbs().maxCoeff();
    const long double e1 = angle_between(rotation_of(rk4_kinematics(body, q0, 10.0L, 20000)), r10);
    const long double e2 = angle_between(rotation_of(y.q), r10);
    INFO("omega " << static_cast<double>(ew) << " rad/s, R by kinematics "
                  << static_cast<double>(e1) << " rad, by the full system "
                  << static_cast<double>(e2) << " rad");
    CHECK(ew < 1e-12L * c.omega0.norm());
    CHECK(e1 < 1e-12L);
    CHECK(e2 < 1e-12L);
  }
}

TEST_CASE("Torque-free reference on random bodies and states agrees with RK4",
          "[integrate][reference]") {
  // Every order of the moments and every sign pattern, drawn at random: omega(0) = omega0 and
  // omega(2), R(2) against RK4 of the full system (h = 1/2000 s).
  tumble::test::Random rng(19);
  for (int n = 0; n < 24; ++n) {
    const Vec3L inertia(rng.uniform(0.5, 3.0), rng.uniform(0.5, 3.0), rng.uniform(0.5, 3.0));
    const Vec3L omega0 = rng.vector(1.0).cast<long double>();
    const Vec4L q0 = to_ld(rng.quaternion());
    const TorqueFreeBody body(inertia, omega0, rotation_of(q0));
    INFO("I = (" << static_cast<double>(inertia(0)) << ", " << static_cast<double>(inertia(1))
                 << ", " << static_cast<double>(inertia(2)) << "), omega0 = ("
                 << static_cast<double>(omega0(0)) << ", " << static_cast<double>(omega0(1)) << ", "
                 << static_cast<double>(omega0(2)) << ")");
    CHECK((body.omega_ld(0.0L) - omega0).cwiseAbs().maxCoeff() < 16 * kEpsLd * omega0.norm());
    const FullState y = rk4_full(inertia, {omega0, q0}, 2.0L, 4000);
    CHECK((y.w - body.omega_ld(2.0L)).cwiseAbs().maxCoeff() < 1e-12L * omega0.norm());
    CHECK(angle_between(rotation_of(y.q), body.rotation_ld(2.0L)) < 1e-12L);
  }
}

TEST_CASE("Torque-free key case agrees with mpmath's Taylor ODE solver", "[integrate][reference]") {
  const TorqueFreeBody body(Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(0.1, 2.0, 0.05));
  for (const auto& ref : key_case_mpmath()) {
    INFO("t = " << static_cast<double>(ref.t));
    const long double ew = (body.omega_ld(ref.t) - ref.w).cwiseAbs().maxCoeff();
    const long double er = max_abs(body.rotation_ld(ref.t) - ref.r);
    INFO("omega error " << static_cast<double>(ew) << ", R error " << static_cast<double>(er));
    CHECK(ew < 1e-17L);
    CHECK(er < 1e-17L);
    // The double interface: rounded to double.
    CHECK((body.omega(static_cast<double>(ref.t)) - ref.w.cast<double>()).cwiseAbs().maxCoeff() <=
          2 * kEps);
    CHECK(
        (body.rotation(static_cast<double>(ref.t)) - ref.r.cast<double>()).cwiseAbs().maxCoeff() <=
        kEps);
  }
}

TEST_CASE("Torque-free reference: steady rotations", "[integrate][reference]") {
  tumble::test::Random rng(17);
  const Vec4L q0 = to_ld(rng.quaternion());
  const Mat3L r0 = rotation_of(q0);
  // Pure spins about each principal axis (the intermediate one is an unstable equilibrium), a
  // sphere, and rest.
  const Case steady[] = {{"spin about 1", Vec3L(1, 2, 3), Vec3L(1.5L, 0, 0)},
                         {"spin about 2", Vec3L(1, 2, 3), Vec3L(0, -0.8L, 0)},
                         {"spin about 3", Vec3L(1, 2, 3), Vec3L(0, 0, 2.5L)},
                         {"sphere", Vec3L(2, 2, 2), Vec3L(0.3L, -0.4L, 1.2L)},
                         {"rest", Vec3L(1, 2, 3), Vec3L(0, 0, 0)}};
  for (const auto& c : steady) {
    INFO(c.name);
    const TorqueFreeBody body(c.inertia, c.omega0, r0);
    CHECK(body.regime() == TorqueFreeBody::Regime::steady);
    const FullState y = rk4_full(c.inertia, {c.omega0, q0}, 10.0L, 10000);
    CHECK((body.omega_ld(10.0L) - c.omega0).cwiseAbs().maxCoeff() == 0.0L);
    CHECK(angle_between(body.rotation_ld(10.0L), rotation_of(y.q)) < 1e-12L);
  }
}

// ==== report ===================================================================================

TEST_CASE("Torque-free reference: key-case numbers", "[integrate][reference][.report]") {
  const TorqueFreeBody body(Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(0.1, 2.0, 0.05));
  const auto start = std::chrono::steady_clock::now();
  const Eigen::Matrix3d r50 = body.rotation(50.0);
  const double us =
      std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
  const Eigen::Vector3d w50 = body.omega(50.0);
  std::printf("key case: I = diag(1, 2, 3), omega0 = (0.1, 2.0, 0.05), R0 = I\n");
  std::printf("  regime          %s (H^2 < 2 T I_mid: polhode around body axis %d)\n",
              body.regime() == TorqueFreeBody::Regime::minor_axis ? "minor_axis" : "other",
              body.axis_c() + 1);
  std::printf("  2T = %.17Lg, H^2 = %.17Lg\n", 2 * body.kinetic_energy_ld(),
              body.angular_momentum_ld().squaredNorm());
  std::printf("  m               %.20Lg\n  1 - m           %.20Lg\n", body.parameter_m(),
              body.parameter_m1());
  std::printf("  K(m)            %.20Lg\n  lambda          %.20Lg rad/s\n", body.quarter_period_k(),
              body.frequency_lambda());
  std::printf("  u0              %.20Lg\n", body.initial_argument_u0());
  std::printf("  period 4K/lambda %.20Lg s\n  flip interval   %.20Lg s\n", body.period_ld(),
              body.flip_interval_ld());
  std::printf("  omega(50)       (%.17g, %.17g, %.17g) rad/s\n", w50(0), w50(1), w50(2));
  std::printf("  R(50)           [%.17g, %.17g, %.17g]\n", r50(0, 0), r50(0, 1), r50(0, 2));
  std::printf("                  [%.17g, %.17g, %.17g]\n", r50(1, 0), r50(1, 1), r50(1, 2));
  std::printf("                  [%.17g, %.17g, %.17g]\n", r50(2, 0), r50(2, 1), r50(2, 2));
  std::printf("  rotation(50) took %.0f us\n", us);
  for (const auto& ref : key_case_mpmath()) {
    std::printf("  vs mpmath's Taylor ODE solver at t = %2.0Lf: max |d omega| %.1Le rad/s, max |d "
                "R| %.1Le\n",
                ref.t, (body.omega_ld(ref.t) - ref.w).cwiseAbs().maxCoeff(),
                max_abs(body.rotation_ld(ref.t) - ref.r));
  }
  SUCCEED();
}
