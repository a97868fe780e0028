#pragma once
// Independent analytic reference for the torque-free rigid body: the closed-form body angular
// velocity omega(t) (Jacobi elliptic functions) and attitude R(t) (classical angles, precession
// by quadrature) for the Euler equations I omegadot + omega x I omega = 0 with a principal
// inertia I = diag(I1, I2, I3). Used by the integration tests and the benchmark work-precision
// driver, so it is self-contained (Eigen + std, no tumble headers) and computes in long double.
//
// Conventions (those of the reference chapter, Chapter 1, "Rigid body"):
// R maps body components to inertial ones (r_F = R r_f, Eq. 1.1); omega is the angular velocity
// of the body frame in BODY components, S(omega) = R^T Rdot (Eq. 1.3 gives Rdot = S(omega_F) R,
// and omega_F = R omega). A quaternion is scalar first (e0, e1, e2, e3), Hamilton product.
//
// Sources (the elliptic functions and the quadrature: support/elliptic.hpp):
//  - The Euler top: L. D. Landau & E. M. Lifshitz, Mechanics, 3rd ed., Sec. 37 (omega in sn, cn,
//    dn; the angles theta, psi, phi of the angular momentum in the body frame, psidot).
//
// Solution used here (all moments distinct). 2T = sum I_i w_i^2 and H^2 = sum I_i^2 w_i^2 are
// conserved. b is the axis of the intermediate moment; c is the axis the polhode encircles: the
// major axis when H^2 > 2 T I_b, the minor axis when H^2 < 2 T I_b; a is the remaining one.
// With D_a = H^2 - 2T I_a, D_b = H^2 - 2T I_b and D_c = 2T I_c - H^2 (each evaluated as a sum of
// terms of one sign, sum_i I_i (I_i - I_x) w_i^2, so without cancellation):
//   w_a = s_a A_a cn(u),   w_b = s_b A_b sn(u),   w_c = s_c A_c dn(u),   u = u0 + lambda t,
//   A_a^2 = D_c / (I_a (I_c - I_a)),
//   A_b^2 = D_c / (I_b (I_c - I_b)),
//   A_c^2 = D_a / (I_c (I_c - I_a)),
//   lambda^2 = (I_c - I_b) D_a / (I_a I_b I_c),
//   m = (I_b - I_a) D_c / ((I_c - I_b) D_a),   1 - m = (I_c - I_a) D_b / ((I_c - I_b) D_a)
// (every ratio is positive in both regimes: in the minor-axis one each factor changes sign; 1 - m
// is computed from D_b, not as 1 - m, to keep its accuracy near the separatrix). The signs:
// s_c = sign(w_c(0)) (dn > 0), s_a = +1, and s_a s_b s_c = eps sign(I_c - I_a), eps = +1 when
// (a, b, c) is a cyclic permutation of (1, 2, 3) and -1 otherwise (substitute into the Euler
// equations with sn' = cn dn, cn' = -sn dn, dn' = -m sn cn). The phase u0 solves
// sn(u0) = w_b(0) / (s_b A_b), cn(u0) = w_a(0) / (s_a A_a) with the incomplete integral, so
// omega(0) = omega0 exactly, signs included.
//
// Periods. omega(t) has the period 4K / lambda (period()). The intermediate-axis component w_b
// changes sign every 2K / lambda (flip_interval()): for a body tumbling near the separatrix of
// the intermediate axis (the Dzhanibekov effect) that is the time between two successive flips,
// so one flip and the flip back take period(). w_a^2, w_b^2, w_c^2 and psidot have the period
// 2K / lambda.
//
// Attitude. h = R I omega is constant. In the inertial "h-frame" whose z axis is h / H,
//   R(t) = A R_h(t),   R_h = R_z(psi) R_x(theta) R_z(phi) P,
// P the cyclic axis permutation taking body components (v_1, v_2, v_3) to (v_i, v_j, v_k), and A
// the constant rotation fixed by R(0) = R0 (psi(0) = 0). From R_h^T e_z = h_body / H:
//   cos(theta) = h_k / H,  sin(theta) = sqrt(h_i^2 + h_j^2) / H,  (sin phi, cos phi) ~ (h_i, h_j),
// and the body angular velocity of the 3-1-3 sequence gives (as in Landau Sec. 37 for k = 3)
//   psidot = H (I_i w_i^2 + I_j w_j^2) / (I_i^2 w_i^2 + I_j^2 w_j^2),
// integrated over u by Gauss-Legendre quadrature in long double: tabulated once on a grid of one
// half period [0, 2K] (panels halved until the 20-point rule on each panel agrees with the rule on
// its halves to 64 eps), then whole half periods plus the table plus one panel for the rest.
// The axis k is the one of a and c that keeps the denominator H^2 - h_k^2 larger: the polhode
// touches neither (c is inside it, a on the other side of the separatrix); the minimum of
// H^2 - h_k^2 along the orbit is I_a^2 A_a^2 for k = c and I_c^2 A_c^2 for k = a, and these add
// up to H^2, so the chosen axis keeps sin^2(theta) >= 1/2. (Always taking the encircled axis c
// fails for a nearly pure spin about c, where theta -> 0 and psidot -> 0/0.)
//
// Special cases in closed form: a steady rotation (omega0 along a principal axis, a spherical
// body, omega0 = 0): R = R0 exp(S(omega0) t); the axisymmetric body (two equal moments, c the
// symmetry axis, I_t the transverse moment): w_c constant and (w_a, w_b) rotating at
// Omega = (I_c - I_t) w_c / I_t, with k = c, theta constant and psi = H t / I_t; the exact
// separatrix (H^2 = 2T I_b, m = 1): sn = tanh, cn = dn = sech, aperiodic (psi by adaptive
// quadrature from u = 0).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "support/elliptic.hpp"

namespace tumble::test {

// ==== The torque-free rigid body ==============================================================

/// Closed-form torque-free motion of a rigid body with principal inertia diag(inertia) (any order
/// of the moments), body angular velocity omega0 and attitude R0 at t = 0. All work in long double;
/// the *_ld accessors return long double, the others round to double.
class TorqueFreeBody {
 public:
  using Vec3L = Eigen::Matrix<long double, 3, 1>;
  using Mat3L = Eigen::Matrix<long double, 3, 3>;

  enum class Regime {
    steady,        ///< omega0 along a principal axis (or zero, or a spherical body): constant omega
    axisymmetric,  ///< two equal moments: closed form with sin and cos
    major_axis,    ///< H^2 > 2 T I_mid: the polhode encircles the axis of the largest moment
    minor_axis,    ///< H^2 < 2 T I_mid: the polhode encircles the axis of the smallest moment
    separatrix     ///< H^2 = 2 T I_mid exactly: sn = tanh, cn = dn = sech, aperiodic
  };

  TorqueFreeBody(const Vec3L& inertia, const Vec3L& omega0, const Mat3L& r0 = Mat3L::Identity())
      : inertia_(inertia), omega0_(omega0), r0_(r0) {
    if (!(inertia.minCoeff() > 0.0L)) {
      throw std::invalid_argument("TorqueFreeBody: the principal moments must be positive");
    }
    classify();
    setup_attitude();
  }
  TorqueFreeBody(const Eigen::Vector3d& inertia, const Eigen::Vector3d& omega0,
                 const Eigen::Matrix3d& r0 = Eigen::Matrix3d::Identity())
      : TorqueFreeBody(Vec3L(inertia.cast<long double>()), Vec3L(omega0.cast<long double>()),
                       Mat3L(r0.cast<long double>())) {}

  // ---- omega(t) ----

  /// Body angular velocity at time t.
  [[nodiscard]] Vec3L omega_ld(long double t) const {
    switch (regime_) {
      case Regime::steady:
        return omega0_;
      case Regime::axisymmetric: {
        const long double s = std::sin(spin_rate_ * t), c = std::cos(spin_rate_ * t);
        Vec3L w;
        w(a_) = omega0_(a_) * c - omega0_(b_) * s;
        w(b_) = omega0_(a_) * s + omega0_(b_) * c;
        w(c_) = omega0_(c_);
        return w;
      }
      default:
        return omega_at_u(u0_ + lambda_ * t);
    }
  }
  [[nodiscard]] Eigen::Vector3d omega(double t) const { return omega_ld(t).cast<double>(); }

  /// omegadot from the Euler equations, I^-1 (I omega x omega), at time t.
  [[nodiscard]] Vec3L omega_dot_ld(long double t) const {
    const Vec3L w = omega_ld(t);
    const Vec3L h = inertia_.cwiseProduct(w);
    return h.cross(w).cwiseQuotient(inertia_);
  }

  // ---- R(t) ----

  /// Attitude (body -> inertial) at time t; R(0) = R0.
  [[nodiscard]] Mat3L rotation_ld(long double t) const {
    if (regime_ == Regime::steady) {
      const long double n = omega0_.norm();
      if (n == 0.0L) return r0_;
      return r0_ * Eigen::AngleAxis<long double>(n * t, omega0_ / n).toRotationMatrix();
    }
    return a_frame_ * h_frame_rotation(psi_ld(t), omega_ld(t));
  }
  [[nodiscard]] Eigen::Matrix3d rotation(double t) const { return rotation_ld(t).cast<double>(); }

  /// Attitude as a unit quaternion, scalar first (e0, e1, e2, e3), with e0 >= 0.
  [[nodiscard]] Eigen::Vector4d quaternion(double t) const {
    const Eigen::Quaternion<long double> q(rotation_ld(t));
    Eigen::Matrix<long double, 4, 1> v(q.w(), q.x(), q.y(), q.z());
    if (v(0) < 0.0L) v = -v;
    return v.normalized().cast<double>();
  }

  /// The precession angle psi(t) about h (psi(0) = 0): int_0^t psidot, by quadrature. Zero for a
  /// steady rotation (where the h-frame angles are not used).
  [[nodiscard]] long double psi_ld(long double t) const {
    switch (regime_) {
      case Regime::steady:
        return 0.0L;
      case Regime::axisymmetric:
        return momentum_ / inertia_(a_) * t;
      default:
        return (psi_integral(u0_ + lambda_ * t) - psi_integral_u0_) / lambda_;
    }
  }
  /// psidot = H (I_i w_i^2 + I_j w_j^2) / (I_i^2 w_i^2 + I_j^2 w_j^2) at time t.
  [[nodiscard]] long double psi_dot_ld(long double t) const {
    return regime_ == Regime::steady ? 0.0L : psi_dot_of(omega_ld(t));
  }

  // ---- constants of the motion and of the solution ----

  [[nodiscard]] Regime regime() const { return regime_; }
  /// Inertial angular momentum h = R I omega (constant).
  [[nodiscard]] Eigen::Vector3d angular_momentum() const { return h_inertial_.cast<double>(); }
  [[nodiscard]] Vec3L angular_momentum_ld() const { return h_inertial_; }
  /// Kinetic energy T = 1/2 omega . I omega.
  [[nodiscard]] long double kinetic_energy_ld() const {
    return 0.5L * omega0_.dot(inertia_.cwiseProduct(omega0_));
  }
  /// Period of omega(t): 4K / lambda (elliptic), 2 pi / |Omega| (axisymmetric); +inf for steady
  /// rotation and on the separatrix.
  [[nodiscard]] long double period_ld() const { return period_; }
  [[nodiscard]] double period() const { return static_cast<double>(period_); }
  /// Half of period(): the time between two successive sign changes of the intermediate-axis
  /// component w_b (the Dzhanibekov flips), and the period of psidot and of the w_i^2.
  [[nodiscard]] long double flip_interval_ld() const { return 0.5L * period_; }
  [[nodiscard]] double flip_interval() const { return static_cast<double>(0.5L * period_); }
  /// Parameter m (= k^2) and complementary parameter 1 - m of the elliptic functions (0 and 1
  /// outside the elliptic regimes).
  [[nodiscard]] long double parameter_m() const { return m_; }
  [[nodiscard]] long double parameter_m1() const { return m1_; }
  /// K(m).
  [[nodiscard]] long double quarter_period_k() const { return k_; }
  /// lambda: u = u0 + lambda t (|Omega| in the axisymmetric case).
  [[nodiscard]] long double frequency_lambda() const { return lambda_; }
  /// u0: the initial argument of sn, cn, dn.
  [[nodiscard]] long double initial_argument_u0() const { return u0_; }
  /// Body axes (0-based): a (cn), b (sn, the intermediate moment), c (dn, encircled by the
  /// polhode; the symmetry axis in the axisymmetric case), and k (the z axis of the 3-1-3 angles).
  [[nodiscard]] int axis_a() const { return a_; }
  [[nodiscard]] int axis_b() const { return b_; }
  [[nodiscard]] int axis_c() const { return c_; }
  [[nodiscard]] int axis_k() const { return k_axis_; }
  /// Signed amplitudes: w_a = amp(a) cn, w_b = amp(b) sn, w_c = amp(c) dn.
  [[nodiscard]] Vec3L amplitudes() const { return amp_; }

 private:
  Vec3L inertia_, omega0_;
  Mat3L r0_;
  Regime regime_ = Regime::steady;
  int a_ = 0, b_ = 1, c_ = 2;
  Vec3L amp_ = Vec3L::Zero();
  long double lambda_ = 0.0L, m_ = 0.0L, m1_ = 1.0L, k_ = std::numbers::pi_v<long double> / 2;
  long double u0_ = 0.0L, period_ = std::numeric_limits<long double>::infinity();
  JacobiElliptic jacobi_{0.0L, 1.0L};
  long double spin_rate_ = 0.0L;  // Omega, axisymmetric case
  // attitude
  int i_axis_ = 0, j_axis_ = 1, k_axis_ = 2;
  long double momentum_ = 0.0L;  // H
  Vec3L h_inertial_ = Vec3L::Zero();
  Mat3L a_frame_ = Mat3L::Identity();
  std::vector<long double> psi_grid_;   // G at the grid points of [0, 2K]; back() = G(2K)
  long double psi_integral_u0_ = 0.0L;  // G(u0)

  static int sign_of(long double x) { return x < 0.0L ? -1 : 1; }

  void classify() {
    const Vec3L& im = inertia_;
    const Vec3L& w = omega0_;
    const Vec3L h = im.cwiseProduct(w);
    h_inertial_ = r0_ * h;
    momentum_ = h.norm();

    // Steady: omega0 is an eigenvector of I (each pair of nonzero components has equal moments).
    bool steady = true;
    for (int i = 0; i < 3; ++i) {
      for (int j = i + 1; j < 3; ++j) {
        if (w(i) != 0.0L && w(j) != 0.0L && im(i) != im(j)) steady = false;
      }
    }
    if (steady) {
      regime_ = Regime::steady;
      return;
    }

    // Axisymmetric: exactly two equal moments (three equal would have been steady).
    for (int c = 0; c < 3; ++c) {
      const int a = (c + 1) % 3, b = (c + 2) % 3;
      if (im(a) == im(b)) {
        regime_ = Regime::axisymmetric;
        a_ = a;
        b_ = b;
        c_ = c;
        spin_rate_ = (im(c) - im(a)) * w(c) / im(a);
        lambda_ = std::fabs(spin_rate_);
        period_ = lambda_ == 0.0L ? std::numeric_limits<long double>::infinity()
                                  : 2.0L * std::numbers::pi_v<long double> / lambda_;
        return;
      }
    }

    // Triaxial. Sort the axes by moment.
    std::array<int, 3> idx{0, 1, 2};
    std::sort(idx.begin(), idx.end(), [&](int p, int q) { return im(p) < im(q); });
    const int lo = idx[0], mid = idx[1], hi = idx[2];
    const auto sq = [&](int i) { return w(i) * w(i); };
    // D_mid = H^2 - 2 T I_mid as a sum of terms of known sign.
    const long double d_mid =
        im(lo) * (im(lo) - im(mid)) * sq(lo) + im(hi) * (im(hi) - im(mid)) * sq(hi);
    b_ = mid;
    if (d_mid >= 0.0L) {
      regime_ = d_mid > 0.0L ? Regime::major_axis : Regime::separatrix;
      c_ = hi;
      a_ = lo;
    } else {
      regime_ = Regime::minor_axis;
      c_ = lo;
      a_ = hi;
    }
    const int a = a_, b = b_, c = c_;
    const long double ia = im(a), ib = im(b), ic = im(c);
    const long double d_a = ib * (ib - ia) * sq(b) + ic * (ic - ia) * sq(c);  // H^2 - 2T I_a
    const long double d_c = ia * (ic - ia) * sq(a) + ib * (ic - ib) * sq(b);  // 2T I_c - H^2
    const long double d_b = ia * (ia - ib) * sq(a) + ic * (ic - ib) * sq(c);  // H^2 - 2T I_b
    const long double amp_a = std::sqrt(d_c / (ia * (ic - ia)));
    const long double amp_b = std::sqrt(d_c / (ib * (ic - ib)));
    const long double amp_c = std::sqrt(d_a / (ic * (ic - ia)));
    lambda_ = std::sqrt((ic - ib) * d_a / (ia * ib * ic));
    m_ = (ib - ia) * d_c / ((ic - ib) * d_a);
    m1_ = (ic - ia) * d_b / ((ic - ib) * d_a);
    if (regime_ == Regime::separatrix) {
      m_ = 1.0L;
      m1_ = 0.0L;
    }
    m_ = std::clamp(m_, 0.0L, 1.0L);
    m1_ = std::clamp(m1_, 0.0L, 1.0L);
    jacobi_ = JacobiElliptic(m_, m1_);
    k_ = jacobi_.k();
    period_ = 4.0L * k_ / lambda_;

    const int cyclic = (b == (a + 1) % 3) ? 1 : -1;
    const int s_c = sign_of(w(c));
    const int s_a = (regime_ == Regime::separatrix) ? sign_of(w(a)) : 1;  // cn = sech > 0 there
    const int s_b = cyclic * sign_of(ic - ia) * s_a * s_c;
    amp_(a) = s_a * amp_a;
    amp_(b) = s_b * amp_b;
    amp_(c) = s_c * amp_c;
    u0_ = jacobi_argument(w(b) / amp_(b), w(a) / amp_(a), m_, m1_);
  }

  [[nodiscard]] Vec3L omega_at_u(long double u) const {
    const auto f = jacobi_(u);
    Vec3L w;
    w(a_) = amp_(a_) * f.cn;
    w(b_) = amp_(b_) * f.sn;
    w(c_) = amp_(c_) * f.dn;
    return w;
  }

  [[nodiscard]] long double psi_dot_of(const Vec3L& w) const {
    const long double hi = inertia_(i_axis_) * w(i_axis_), hj = inertia_(j_axis_) * w(j_axis_);
    const long double num = hi * w(i_axis_) + hj * w(j_axis_);
    return momentum_ * num / (hi * hi + hj * hj);
  }

  /// G(u) = int_0^u g, g(u) = psidot at argument u (g has period 2K): whole half periods times
  /// their integral, the tabulated integral up to the grid point below the remainder, and one
  /// 20-point Gauss-Legendre panel for the rest (a part of a grid panel on which the rule was
  /// verified converged). Aperiodic (separatrix): adaptive quadrature from 0.
  [[nodiscard]] long double psi_integral(long double u) const {
    const auto g = [this](long double v) { return psi_dot_of(omega_at_u(v)); };
    if (m1_ == 0.0L) return integrate(g, 0.0L, u);
    const long double half = 2.0L * k_;
    const long double n = std::floor(u / half);
    const long double r = u - n * half;
    const int panels = static_cast<int>(psi_grid_.size()) - 1;
    const long double width = half / static_cast<long double>(panels);
    const int j = std::clamp(static_cast<int>(r / width), 0, panels - 1);
    const long double lo = width * static_cast<long double>(j);
    return n * psi_grid_.back() + psi_grid_[static_cast<std::size_t>(j)] +
           detail_quadrature::gauss_panel(g, lo, r);
  }

  /// Tabulates G on an even grid of [0, 2K]: panels of width <= 1/2, halved until on every panel
  /// the 20-point rule and the rule on both halves agree to 64 eps_ld.
  void tabulate_psi() {
    const auto g = [this](long double v) { return psi_dot_of(omega_at_u(v)); };
    const long double half = 2.0L * k_;
    const long double eps = std::numeric_limits<long double>::epsilon();
    int panels = std::max(1, static_cast<int>(std::ceil(half / 0.5L)));
    for (; panels <= (1 << 16); panels *= 2) {
      const long double width = half / static_cast<long double>(panels);
      std::vector<long double> grid(static_cast<std::size_t>(panels) + 1, 0.0L);
      bool converged = true;
      for (int j = 0; j < panels && converged; ++j) {
        const long double lo = width * static_cast<long double>(j);
        const long double hi = (j + 1 == panels) ? half : lo + width;
        const long double mid = 0.5L * (lo + hi);
        const long double whole = detail_quadrature::gauss_panel(g, lo, hi);
        const long double halves =
            detail_quadrature::gauss_panel(g, lo, mid) + detail_quadrature::gauss_panel(g, mid, hi);
        converged = std::fabs(halves - whole) <= 64.0L * eps * std::fabs(halves);
        grid[static_cast<std::size_t>(j) + 1] = grid[static_cast<std::size_t>(j)] + halves;
      }
      if (converged) {
        psi_grid_ = std::move(grid);
        return;
      }
    }
    throw std::runtime_error("TorqueFreeBody: the precession quadrature did not converge");
  }

  /// R_h = R_z(psi) R_x(theta) R_z(phi) P from psi and the body angular momentum I omega.
  [[nodiscard]] Mat3L h_frame_rotation(long double psi, const Vec3L& w) const {
    const Vec3L h = inertia_.cwiseProduct(w);
    const long double hi = h(i_axis_), hj = h(j_axis_), hk = h(k_axis_);
    const long double ht = std::hypot(hi, hj);
    const long double hn = std::hypot(ht, hk);
    const long double st = ht / hn, ct = hk / hn;
    const long double sp = hi / ht, cp = hj / ht;
    const long double ss = std::sin(psi), cs = std::cos(psi);
    Mat3L rz_psi, rx_theta, rz_phi, p = Mat3L::Zero();
    rz_psi << cs, -ss, 0,  //
        ss, cs, 0,         //
        0, 0, 1;
    rx_theta << 1, 0, 0,  //
        0, ct, -st,       //
        0, st, ct;
    rz_phi << cp, -sp, 0,  //
        sp, cp, 0,         //
        0, 0, 1;
    p(0, i_axis_) = 1;
    p(1, j_axis_) = 1;
    p(2, k_axis_) = 1;
    return rz_psi * rx_theta * rz_phi * p;
  }

  void setup_attitude() {
    if (regime_ == Regime::steady) return;
    if (regime_ == Regime::axisymmetric) {
      k_axis_ = c_;
    } else {
      // k = c when min(H^2 - h_c^2) = (I_a A_a)^2 >= min(H^2 - h_a^2) = (I_c A_c)^2, else k = a.
      const long double ha = inertia_(a_) * amp_(a_), hc = inertia_(c_) * amp_(c_);
      k_axis_ = (ha * ha >= hc * hc) ? c_ : a_;
    }
    i_axis_ = (k_axis_ + 1) % 3;
    j_axis_ = (k_axis_ + 2) % 3;
    a_frame_ = r0_ * h_frame_rotation(0.0L, omega0_).transpose();
    if (regime_ == Regime::axisymmetric) return;
    if (m1_ != 0.0L) tabulate_psi();
    psi_integral_u0_ = psi_integral(u0_);
  }
};

}  // namespace tumble::test
