#pragma once
// The heavy symmetric (Lagrange) top in closed form, for the tests of bodies held at a fixed
// point. Written from the classical solution (Goldstein, Classical Mechanics, Sec. 5.7), not from
// tumble: with Euler angles psi (precession about the vertical), theta (nutation), phi (spin),
// A and C the transverse and axial moments of inertia about the fixed point, l the distance from
// the fixed point to the centroid and u = cos(theta),
//   udot^2 = f(u) = (alpha - beta u)(1 - u^2) - (b - a u)^2,
//   a = C omega_3 / A, b = p_psi / A, alpha = 2 E' / A, beta = 2 m g l / A,
// E' = E - C omega_3^2 / 2. u oscillates between the two roots u2 < u1 of the cubic f in [-1, 1]
// (the third, u3, is above 1) with the period
//   T = 2 int_{u2}^{u1} du / sqrt(f(u)) = 4 K(k) / sqrt(beta (u3 - u2)),  k^2 = (u1 - u2)/(u3 -
//   u2),
// and psi advances by
//   dpsi = 2 int_{u2}^{u1} (b - a u) / (1 - u^2) du / sqrt(f(u))
// per period, evaluated here with u = u2 + (u1 - u2) sin^2(s): du / sqrt(f) = 2 ds /
// sqrt(beta (u3 - u)), a smooth, even, pi-periodic integrand in s, for which the trapezoidal
// rule converges geometrically.

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "tumble/body/kinematics.hpp"
#include "tumble/body/mass_properties.hpp"
#include "tumble/body/rigid_body.hpp"
#include "tumble/scene/observables.hpp"
#include "tumble/scene/scene.hpp"
#include "tumble/scene/state.hpp"

namespace tumble::test {

/// The top's parameters (defaults: the top of the fixed-point tests) and its closed form.
struct LagrangeTop {
  double mass = 1.0;     ///< kg
  double length = 0.1;   ///< l, fixed point to centroid, m
  double a_tip = 0.05;   ///< A, transverse moment about the fixed point, kg m^2
  double c_axis = 0.02;  ///< C, axial moment, kg m^2
  double g = 9.81;       ///< m/s^2
  double theta0 = 0.5;   ///< initial tilt of the axis from the vertical, rad
  double spin = 50.0;    ///< omega_3, rad/s; the top starts with thetadot = psidot = 0

  [[nodiscard]] double u0() const { return std::cos(theta0); }
  [[nodiscard]] double a() const { return c_axis * spin / a_tip; }
  [[nodiscard]] double beta() const { return 2 * mass * g * length / a_tip; }
  /// p_psi / A and 2 E' / A from the initial state (thetadot = psidot = 0).
  [[nodiscard]] double b() const { return a() * u0(); }
  [[nodiscard]] double alpha() const { return beta() * u0(); }

  /// f(u) (see the file comment).
  [[nodiscard]] double f(double u) const {
    const double d = b() - a() * u;
    return (alpha() - beta() * u) * (1 - u * u) - d * d;
  }

  /// The three real roots of f, ascending (u2, u1, u3): the trigonometric solution of the
  /// cubic beta u^3 - (alpha + a^2) u^2 + (2 a b - beta) u + (alpha - b^2), polished by Newton.
  [[nodiscard]] std::array<double, 3> roots() const {
    const double c2 = -(alpha() + a() * a()) / beta(), c1 = (2 * a() * b() - beta()) / beta(),
                 c0 = (alpha() - b() * b()) / beta();
    // u = x - c2/3: x^3 + p x + q = 0.
    const double p = c1 - c2 * c2 / 3, q = 2 * c2 * c2 * c2 / 27 - c2 * c1 / 3 + c0;
    const double r = 2 * std::sqrt(-p / 3);
    const double phi = std::acos(std::clamp(3 * q / (p * r), -1.0, 1.0)) / 3;
    std::array<double, 3> u{};
    for (int k = 0; k < 3; ++k) {
      double x = r * std::cos(phi - 2 * std::numbers::pi * k / 3) - c2 / 3;
      for (int it = 0; it < 3; ++it) {  // Newton on the monic cubic
        const double val = ((x + c2) * x + c1) * x + c0, der = (3 * x + 2 * c2) * x + c1;
        if (der != 0) {
          x -= val / der;
        }
      }
      u[static_cast<std::size_t>(k)] = x;
    }
    std::sort(u.begin(), u.end());
    return u;
  }

  /// The nutation period, s.
  [[nodiscard]] double nutation_period() const {
    const auto [u2, u1, u3] = roots();
    const double k = std::sqrt((u1 - u2) / (u3 - u2));
    return 4 * std::comp_ellint_1(k) / std::sqrt(beta() * (u3 - u2));
  }

  /// The advance of psi over one nutation period, rad.
  [[nodiscard]] double precession_per_period() const {
    const auto [u2, u1, u3] = roots();
    const int n = 400;  // trapezoid over a full period of the integrand in s: geometric
    double sum = 0;
    for (int i = 0; i < n; ++i) {
      const double s = 2 * std::numbers::pi * (i + 0.5) / n, sn = std::sin(s);
      const double u = u2 + (u1 - u2) * sn * sn;
      sum += (b() - a() * u) / (1 - u * u) * 2 / std::sqrt(beta() * (u3 - u));
    }
    // int_0^{pi/2} = (1/4) int_0^{2 pi}; dpsi = 2 int_0^{pi/2}.
    return 2 * (sum * 2 * std::numbers::pi / n) / 4;
  }

  /// The mean precession rate dpsi / T, rad/s.
  [[nodiscard]] double mean_precession_rate() const {
    return precession_per_period() / nutation_period();
  }

  // --- the top as a tumble body -----------------------------------------------------------------
  /// Its mass properties about the tip: I_c = diag(A, A, C), centroid at l up the body z axis.
  [[nodiscard]] MassProperties<double> mass_properties() const {
    return MassProperties<double>::about_reference(
        mass, Eigen::Vector3d(a_tip, a_tip, c_axis).asDiagonal(), Eigen::Vector3d(0, 0, length));
  }
  /// The initial state: tilted by theta0 about the inertial x axis, spinning about its axis, the
  /// tip at `pivot`.
  [[nodiscard]] InitialState initial_state(const Eigen::Vector3d& pivot) const {
    InitialState s;
    s.position = pivot;
    s.rotation = Eigen::AngleAxisd(theta0, Eigen::Vector3d::UnitX()).toRotationMatrix();
    s.omega = Eigen::Vector3d(0, 0, spin);
    return s;
  }
  [[nodiscard]] Eigen::Vector3d gravity() const { return {0, 0, -g}; }
};

/// What a run of the top shows, measured from its samples (see measure_top).
struct TopMeasurement {
  double u_min = 1, u_max = -1;  ///< extremes of u = cos(theta), refined between samples
  double period = 0;             ///< mean spacing of the rising crossings of (u1 + u2)/2, s
  double precession_rate = 0;    ///< psi(n T) - psi(0) over n T (T from the closed form), rad/s
  double energy_drift = 0;       ///< max |E - E0| / (C omega_3^2 / 2 + m g l)
  double p_psi_drift = 0;        ///< max |p_psi - p_psi0| / |p_phi0|
  double p_phi_drift = 0;        ///< max |p_phi - p_phi0| / |p_phi0|
};

/// Samples the top (body `id` of `scene`, held at a fixed point on the vertical through the
/// inertial origin) from its initial state s0 at `per_period` points per closed-form nutation
/// period over `periods` periods, through advance(t) -> const SceneState&. u = (R e3)_z and its
/// rate udot = (R (omega x e3))_z give a cubic Hermite interpolant between samples, from which the
/// extremes of u and its crossings are found; psi is the unwrapped azimuth of the axis R e3 (plus
/// pi/2, which cancels).
template <class SceneT, class Body, class Advance>
TopMeasurement measure_top(const SceneT& scene, BodyId<Body> id, const LagrangeTop& top,
                           const SceneState& s0, Advance&& advance, int periods = 4,
                           int per_period = 400) {
  const double t_period = top.nutation_period(), dt = t_period / per_period;
  const auto roots = top.roots();
  const double u_mid = 0.5 * (roots[0] + roots[1]);
  const double t_scale = 0.5 * top.c_axis * top.spin * top.spin + top.mass * top.g * top.length;
  struct Sample {
    double u, udot;
  };
  auto sample = [&](const SceneState& s) {
    const Eigen::Matrix3d r = tumble::rotation(scene, id, s);
    const Eigen::Vector3d w = tumble::omega(scene, id, s);
    return Sample{r(2, 2), (r * w.cross(Eigen::Vector3d::UnitZ()))(2)};
  };
  auto azimuth = [&](const SceneState& s) {
    const Eigen::Vector3d axis = tumble::rotation(scene, id, s).col(2);
    return std::atan2(axis.y(), axis.x());
  };
  TopMeasurement m;
  const double e0 = tumble::energy(scene, s0);
  const double p_psi0 = tumble::angular_momentum(scene, s0).z();
  const double p_phi0 = top.c_axis * tumble::omega(scene, id, s0).z();
  Sample prev = sample(s0);
  double psi = 0, last_azimuth = azimuth(s0);
  std::vector<double> crossings;
  for (int k = 1; k <= periods * per_period; ++k) {
    const double t1 = k * dt;
    const SceneState& s = advance(t1);
    const Sample cur = sample(s);
    // The Hermite cubic on [t1 - dt, t1]: its extremes and its rising crossing of u_mid.
    auto h = [&](double x) {  // x in [0, 1]
      const double x2 = x * x, x3 = x2 * x;
      return (2 * x3 - 3 * x2 + 1) * prev.u + (x3 - 2 * x2 + x) * dt * prev.udot +
             (-2 * x3 + 3 * x2) * cur.u + (x3 - x2) * dt * cur.udot;
    };
    for (int j = 0; j <= 64; ++j) {
      const double u = h(j / 64.0);
      m.u_min = std::min(m.u_min, u);
      m.u_max = std::max(m.u_max, u);
    }
    if (prev.u < u_mid && cur.u >= u_mid) {
      double lo = 0, hi = 1;
      for (int it = 0; it < 60; ++it) {
        const double mid = 0.5 * (lo + hi);
        (h(mid) < u_mid ? lo : hi) = mid;
      }
      crossings.push_back(t1 - dt + 0.5 * (lo + hi) * dt);
    }
    const double az = azimuth(s);
    psi += std::remainder(az - last_azimuth, 2 * std::numbers::pi);
    last_azimuth = az;
    m.energy_drift = std::max(m.energy_drift, std::abs(tumble::energy(scene, s) - e0) / t_scale);
    m.p_psi_drift =
        std::max(m.p_psi_drift, std::abs(tumble::angular_momentum(scene, s).z() - p_psi0) / p_phi0);
    m.p_phi_drift = std::max(
        m.p_phi_drift, std::abs(top.c_axis * tumble::omega(scene, id, s).z() - p_phi0) / p_phi0);
    prev = cur;
  }
  if (crossings.size() >= 2) {
    m.period = (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  }
  m.precession_rate = psi / (periods * t_period);
  return m;
}

}  // namespace tumble::test
