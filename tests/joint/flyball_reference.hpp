#pragma once
// IFToMM A05, the stiff flyball governor: the second model in minimal coordinates of
// tests/joint/flyball.test.cpp (whose top comment derives it), q = (psi, s, beta_1, beta_2), with
// the problem's data written again. Shared by that test and by the main job's study (e)
// (benchmarks/mechanisms/flyball.cpp), which measure tumble's runs against it. Boost.Odeint.

#include <cmath>
#include <numbers>
#include <vector>

#include <boost/numeric/odeint.hpp>

namespace flyball_test {

/// The problem's data, as stated (SI).
namespace data {
constexpr double g = 9.81, density = 3000, length = 1.0, section = 0.01, cube = 0.1, ball = 5.0;
constexpr double offset = 0.05, stiffness = 8e5, damping = 4e4, rest = 0.5;
constexpr double s0 = 0.5, alpha = std::numbers::pi / 6, spin = 2 * std::numbers::pi;
constexpr double bar_mass = density * length * section * section;
constexpr double cube_mass = density * cube * cube * cube;
}  // namespace data

/// The second model (tests/joint/flyball.test.cpp derives it): y = (psi, s, beta_1, beta_2, their
/// rates, W_damper).
struct Minimal {
  // A std::vector: Odeint's stage buffers for a std::array are copied uninitialized, which GCC
  // 12 reports (-Wuninitialized) where they are inlined.
  using State = std::vector<double>;
  double c = data::damping;  // N s/m

  static constexpr double m = data::bar_mass, l = data::length, w = data::section;
  static constexpr double a = data::offset, mb = data::ball;
  /// The shaft's and the slider's moments of inertia about z.
  static constexpr double i0 =
      m * 2 * w * w / 12 + data::cube_mass * 2 * data::cube * data::cube / 12;
  /// A rod's moment of inertia about its hinge's axis.
  static constexpr double j = m * (l * l / 3 + w * w / 12) + mb * l * l;
  /// A rod's moment of inertia about z and its derivative in beta.
  static double spin_inertia(double b) {
    const double cb = std::cos(b), sb = std::sin(b), mid = a + 0.5 * l * cb, tip = a + l * cb;
    return m * (mid * mid + l * l * cb * cb / 12 + w * w * (1 + sb * sb) / 12) + mb * tip * tip;
  }
  static double spin_inertia_rate(double b) {
    const double cb = std::cos(b), sb = std::sin(b), mid = a + 0.5 * l * cb, tip = a + l * cb;
    return m * (-mid * l * sb - l * l * cb * sb / 6 + w * w * sb * cb / 6) - 2 * mb * tip * l * sb;
  }
  /// Spring k's length and its derivatives in beta_k and s.
  struct Spring {
    double length, d_beta, d_s;
  };
  static Spring spring(double b, double s) {
    const double dr = 0.5 * l * std::cos(b), dz = data::length - 0.5 * l * std::sin(b) - s;
    const double len = std::hypot(dr, dz);
    return {len, (-dr * 0.5 * l * std::sin(b) - dz * 0.5 * l * std::cos(b)) / len, -dz / len};
  }

  void operator()(const State& y, State& dy, double /*t*/) const {
    const double s = y[1], psid = y[4], sd = y[5];
    const double inertia = i0 + spin_inertia(y[2]) + spin_inertia(y[3]);
    double slider_force = -data::cube_mass * data::g, power = 0;
    dy[0] = psid;
    dy[1] = sd;
    dy[4] = 0;
    for (int k = 0; k < 2; ++k) {
      const double b = y[2 + k], bd = y[6 + k];
      const Spring sp = spring(b, s);
      const double rate = sp.d_beta * bd + sp.d_s * sd;
      const double tension = data::stiffness * (sp.length - data::rest) + c * rate;
      power += c * rate * rate;
      slider_force -= tension * sp.d_s;
      dy[2 + k] = bd;
      dy[4] -= spin_inertia_rate(b) * bd * psid / inertia;
      dy[6 + k] = (0.5 * spin_inertia_rate(b) * psid * psid +
                   data::g * std::cos(b) * (m * 0.5 * l + mb * l) - tension * sp.d_beta) /
                  j;
    }
    dy[5] = slider_force / data::cube_mass;
    dy[8] = power;
  }
  /// T + V (J), V from the shaft's centroid, the slider's, the rods' points and the springs.
  static double energy(const State& y) {
    double e = 0.5 * (i0 + spin_inertia(y[2]) + spin_inertia(y[3])) * y[4] * y[4] +
               0.5 * data::cube_mass * y[5] * y[5] + m * data::g * 0.5 * l +
               data::cube_mass * data::g * y[1];
    for (int k = 0; k < 2; ++k) {
      const double b = y[2 + k];
      const double stretch = spring(b, y[1]).length - data::rest;
      e += 0.5 * j * y[6 + k] * y[6 + k] + 0.5 * data::stiffness * stretch * stretch +
           data::g * (m * (l - 0.5 * l * std::sin(b)) + mb * (l - l * std::sin(b)));
    }
    return e;
  }
  /// (I0 + A_1 + A_2) psi' (kg m^2/s).
  static double momentum(const State& y) {
    return (i0 + spin_inertia(y[2]) + spin_inertia(y[3])) * y[4];
  }
  static State start() { return {0, data::s0, data::alpha, data::alpha, data::spin, 0, 0, 0, 0}; }

  /// The states at `times`.
  [[nodiscard]] std::vector<State> run(const std::vector<double>& times) const {
    namespace odeint = boost::numeric::odeint;
    std::vector<State> out;
    State y = start();
    odeint::integrate_times(
        odeint::make_controlled<odeint::runge_kutta_fehlberg78<State>>(1e-12, 1e-12), *this, y,
        times.begin(), times.end(), 1e-4, [&](const State& x, double) { out.push_back(x); });
    return out;
  }
};

}  // namespace flyball_test
