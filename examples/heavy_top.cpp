// A heavy symmetric (Lagrange) top spinning on its tip, held at a fixed point.
//
// Problem: a top of mass m = 1 kg whose centroid is l = 0.1 m up its symmetry axis from the tip,
// with moments of inertia A = 0.05 kg m^2 (transverse) and C = 0.02 kg m^2 (axial) about the tip,
// starts tilted by theta0 = 0.5 rad from the vertical, spinning at omega_3 = 50 rad/s about its
// axis, with no precession or nutation rate. Gravity makes it precess and nod (nutate).
// Equations: the tip is held (ReferencePoint::fixed_point): the body's coordinates are its Euler
// parameters alone, and its equations of motion are the theta-rows of the reference chapter's
// M qddot = f_v + Q (Eq. 1.32) with the tip at rest, I_c alpha = M_c - omega x I_c omega about
// the tip; the r-rows give the force the floor exerts on the tip (tumble::reaction_force).
// Closed form (Goldstein, Sec. 5.7): with u = cos(theta), udot^2 = f(u), a cubic, and u
// oscillates between its two roots u2 < u1 in [-1, 1]; the nutation period is
// T = 4 K(k) / sqrt(beta (u3 - u2)), k^2 = (u1 - u2) / (u3 - u2), and psi advances by
// 2 int_{u2}^{u1} (b - a u) / (1 - u^2) du / sqrt(f(u)) per period.
// Units: SI.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "tumble/cvode.hpp"

namespace {

/// The closed form of the Lagrange top started at rest in theta and psi (see the file comment).
struct ClosedForm {
  double a, b, alpha, beta;  // C omega_3 / A, p_psi / A, 2 E' / A, 2 m g l / A
  std::array<double, 3> u;   // roots of f, ascending: u2, u1, u3

  ClosedForm(double m, double g, double l, double a_tip, double c_axis, double theta0,
             double spin) {
    a = c_axis * spin / a_tip;
    beta = 2 * m * g * l / a_tip;
    b = a * std::cos(theta0);
    alpha = beta * std::cos(theta0);
    // f(u) = beta u^3 - (alpha + a^2) u^2 + (2 a b - beta) u + (alpha - b^2): trigonometric roots.
    const double c2 = -(alpha + a * a) / beta, c1 = (2 * a * b - beta) / beta,
                 c0 = (alpha - b * b) / beta;
    const double p = c1 - c2 * c2 / 3, q = 2 * c2 * c2 * c2 / 27 - c2 * c1 / 3 + c0;
    const double r = 2 * std::sqrt(-p / 3),
                 phi = std::acos(std::clamp(3 * q / (p * r), -1.0, 1.0)) / 3;
    for (int k = 0; k < 3; ++k) {
      u[static_cast<std::size_t>(k)] = r * std::cos(phi - 2 * std::numbers::pi * k / 3) - c2 / 3;
    }
    std::sort(u.begin(), u.end());
  }
  [[nodiscard]] double period() const {
    const double k = std::sqrt((u[1] - u[0]) / (u[2] - u[0]));
    return 4 * std::comp_ellint_1(k) / std::sqrt(beta * (u[2] - u[0]));
  }
  /// psi's advance per period, by the trapezoidal rule in s with u = u2 + (u1 - u2) sin^2(s).
  [[nodiscard]] double precession_per_period() const {
    const int n = 400;
    double sum = 0;
    for (int i = 0; i < n; ++i) {
      const double sn = std::sin(2 * std::numbers::pi * (i + 0.5) / n);
      const double uu = u[0] + (u[1] - u[0]) * sn * sn;
      sum += (b - a * uu) / (1 - uu * uu) * 2 / std::sqrt(beta * (u[2] - uu));
    }
    return sum * std::numbers::pi / n;  // 2 x (1/4) x the integral over a full period
  }
};

}  // namespace

int main() {
  using namespace tumble;
  const double m = 1.0, g = 9.81, l = 0.1, a_tip = 0.05, c_axis = 0.02, theta0 = 0.5, spin = 50;
  using Top = RigidBody<EulerParameters, ReferencePoint::fixed_point>;
  // Inertia about the tip, centroid position (not m r_g) l up the axis.
  const Top top(
      MassProperties<>::about_reference(m, Eigen::Vector3d(a_tip, a_tip, c_axis).asDiagonal(),
                                        Eigen::Vector3d(0, 0, l)),
      Eigen::Vector3d::Zero());
  Scene<Bodies<Top>, Loads<UniformGravity>, StateForm::quasi_velocities> scene;
  const Eigen::Matrix3d r0 = Eigen::AngleAxisd(theta0, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const auto id = scene.add(top, {.rotation = r0, .omega = {0, 0, spin}});
  scene.add_load(id, UniformGravity({0, 0, -g}));

  SceneIntegratorOptions options;
  options.method = CvodeMethod::adams;  // not stiff: no spring at the tip
  options.rtol = 1e-10;
  options.atol = 1e-10;
  SceneIntegrator integrator(scene, 0.0, options);

  const ClosedForm exact(m, g, l, a_tip, c_axis, theta0, spin);
  const int periods = 10, per_period = 500;
  const double t_period = exact.period(), dt = t_period / per_period;
  // u = cos(theta) = (R e3)_z; psi = azimuth of the axis R e3, unwrapped; nutation period from
  // the times u rises through the middle of its range (linear interpolation between samples).
  const double u_mid = 0.5 * (exact.u[0] + exact.u[1]);
  double u_min = 1, u_max = -1, psi = 0, last_azimuth = -std::numbers::pi / 2,
         u_prev = std::cos(theta0);
  double first_crossing = -1, last_crossing = -1, reaction_max = 0, reaction_min = 1e300;
  int crossings = 0;
  for (int k = 1; k <= periods * per_period; ++k) {
    integrator.advance(k * dt);
    const SceneState& s = integrator.state();
    const Eigen::Vector3d axis = tumble::rotation(scene, id, s).col(2);
    const double u = axis.z(), azimuth = std::atan2(axis.y(), axis.x());
    psi += std::remainder(azimuth - last_azimuth, 2 * std::numbers::pi);
    last_azimuth = azimuth;
    u_min = std::min(u_min, u);
    u_max = std::max(u_max, u);
    if (u_prev < u_mid && u >= u_mid) {
      const double t = (k - 1) * dt + dt * (u_mid - u_prev) / (u - u_prev);
      (crossings == 0 ? first_crossing : last_crossing) = t;
      ++crossings;
    }
    u_prev = u;
    const double fz = tumble::reaction_force(scene, id, s, k * dt).z();
    reaction_max = std::max(reaction_max, fz);
    reaction_min = std::min(reaction_min, fz);
  }
  const double period = (last_crossing - first_crossing) / (crossings - 1);
  const double rate = psi / (periods * t_period),
               rate_exact = exact.precession_per_period() / t_period;
  std::printf("nutation: theta in [%.6f, %.6f] rad (closed form [%.6f, %.6f])\n", std::acos(u_max),
              std::acos(u_min), std::acos(exact.u[1]), std::acos(exact.u[0]));
  std::printf("nutation period: %.8f s (closed form %.8f s, error %.1e)\n", period, t_period,
              std::abs(period - t_period) / t_period);
  std::printf("mean precession rate: %.8f rad/s (closed form %.8f rad/s, error %.1e; fast-top "
              "estimate m g l/(C w3) = %.4f)\n",
              rate, rate_exact, std::abs(rate - rate_exact) / rate_exact,
              m * g * l / (c_axis * spin));
  std::printf("vertical reaction at the tip: %.4f to %.4f N (m g = %.4f N)\n", reaction_min,
              reaction_max, m * g);
  const auto st = integrator.statistics();
  std::printf("Adams: %ld steps, %ld right-hand sides, quaternion drift %.1e\n", st.steps,
              st.rhs_evals, tumble::constraint_drift(scene, integrator.state()));
  return 0;
}
