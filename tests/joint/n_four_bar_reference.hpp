#pragma once
// IFToMM A02, the N-four-bar: tumble's model in absolute coordinates (NFourBar) and the second,
// minimal-coordinate model it is measured against (crank_angle), as tests/joint/iftomm.test.cpp
// derives them. Shared by that test and by the main job's study (e)
// (benchmarks/mechanisms/four_bar.cpp). Conventions: the mechanism moves in the world's (x, y)
// plane, its hinges about z, gravity along -y; the crank angle theta is counted from +y towards
// +x (clockwise seen from +z), so that the benchmark's start, B0 moving along +x, has
// thetadot = +1 rad/s. SI units.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <vector>

#include <Eigen/Geometry>
#include <boost/numeric/odeint.hpp>

#include "tumble/tumble.hpp"

namespace n_four_bar_test {

/// The problem's data, as stated (SI): every link 1 m and 1 kg, gravity 9.81 m/s^2 along -y.
namespace data {
constexpr double g = 9.81, length = 1.0, mass = 1.0;
constexpr double section = 0.01;  ///< tumble's links are rods of 1 cm square section (m)
}  // namespace data

using Bar = tumble::RigidBody<tumble::EulerParameters>;

/// A bar of mass m and length l along body x, of square section s (the IFToMM links are "rods").
inline Bar bar(double m, double l, double s = data::section) {
  return Bar(tumble::MassProperties<>::about_centroid(
      m, Eigen::Vector3d(m * s * s / 6, m * (l * l + s * s) / 12, m * (l * l + s * s) / 12)
             .asDiagonal()));
}

/// N + 1 cranks hinged to the ground at x = 0, 1, ..., N (axis z) and N couplers joining their
/// tips; all links 1 m and 1 kg (bar()). The benchmark starts with the cranks up (+y) and B0, the
/// first crank's tip, moving at 1 m/s along +x; `hanging` starts them down (-y) with B0 at 1 m/s
/// along +x instead, a swing of 0.3 rad about the stable position that never nears the singular
/// one. The couplers translate at the start (no angular rate), at the tips' 1 m/s.
struct NFourBar {
  using SceneT = tumble::Mechanism<tumble::Bodies<Bar>, tumble::Joints<tumble::Revolute>,
                                   tumble::Loads<tumble::UniformGravity>>;
  SceneT scene;
  std::vector<tumble::BodyId<Bar>> cranks;    ///< cranks[i] hinged to the ground at x = i
  std::vector<tumble::BodyId<Bar>> couplers;  ///< couplers[i] from cranks[i] to cranks[i + 1]

  NFourBar(int n, bool hanging) {
    using Eigen::Matrix3d;
    using Eigen::Vector3d;
    const Vector3d z = Vector3d::UnitZ(), end(0.5, 0, 0);
    const double side = hanging ? -1.0 : 1.0;
    // Body x along the crank: +y (up) or -y (hanging); the tip moves at +1 m/s along x.
    const Matrix3d r = Eigen::AngleAxisd(side * std::numbers::pi / 2, z).toRotationMatrix();
    const Vector3d w(0, 0, -side);
    for (int i = 0; i <= n; ++i) {
      cranks.push_back(
          scene.add(bar(data::mass, data::length), {.position = Vector3d(i, 0.5 * side, 0),
                                                    .rotation = r,
                                                    .velocity = Vector3d(0.5, 0, 0),
                                                    .omega = w}));
      scene.add_joint(cranks.back(), tumble::ground,
                      tumble::Revolute(-end, z, Vector3d(i, 0, 0), z));
    }
    for (int i = 0; i < n; ++i) {
      const auto c = couplers.emplace_back(
          scene.add(bar(data::mass, data::length),
                    {.position = Vector3d(i + 0.5, side, 0), .velocity = Vector3d(1.0, 0, 0)}));
      scene.add_joint(c, cranks[std::size_t(i)], tumble::Revolute(-end, z, end, z));
      scene.add_joint(c, cranks[std::size_t(i) + 1], tumble::Revolute(end, z, end, z));
    }
    for (int b = 0; b < scene.body_count(); ++b) {
      scene.add_load(tumble::BodyId<Bar>{b, b}, tumble::UniformGravity(Vector3d(0, -data::g, 0)));
    }
  }

  /// The first crank's angle theta from +y towards +x (rad, in (-pi, pi]), from its body x axis
  /// (R x = (sin theta, cos theta)).
  [[nodiscard]] double crank_angle(const tumble::SceneState& s) const {
    const Eigen::Vector3d dir = tumble::rotation(scene, cranks[0], s) * Eigen::Vector3d::UnitX();
    return std::atan2(dir(0), dir(1));
  }
};

/// The minimal-coordinate model of the N-four-bar: theta, the cranks' angle from +y towards +x;
/// T = (I_eff / 2) thetadot^2 with I_eff = (N + 1) I_o + N m l^2 (cranks about their pivots,
/// couplers translating with the tips), V = G cos theta with G = ((N + 1) / 2 + N) m g l, so
/// I_eff theta'' = G sin theta. Integrated by Odeint's Fehlberg 7(8) at 1e-13 from the start
/// (theta, thetadot) = (0, 1) (cranks up) or (pi, -1) (hanging) to t; returns theta(t) (rad,
/// counted over the turns).
inline double crank_angle(int n, bool hanging, double t) {
  const double io = (1.0 + 1e-4) / 12.0 + 0.25;  // the bar about its end: (l^2 + s^2)/12 + 1/4
  const double ieff = (n + 1) * io + n * 1.0;
  const double gg = ((n + 1) * 0.5 + n) * data::g;
  // A std::vector: Odeint's stage buffers for a std::array are copied uninitialized, which GCC
  // 12 reports (-Wmaybe-uninitialized) where they are inlined (as flyball_reference.hpp).
  using State = std::vector<double>;
  State x = hanging ? State{std::numbers::pi, -1.0} : State{0.0, 1.0};
  namespace odeint = boost::numeric::odeint;
  odeint::integrate_adaptive(
      odeint::make_controlled(1e-13, 1e-13, odeint::runge_kutta_fehlberg78<State>()),
      [&](const State& s, State& d, double) {
        d[0] = s[1];
        d[1] = gg / ieff * std::sin(s[0]);
      },
      x, 0.0, t, 1e-3);
  return x[0];
}

/// The crank-angle error of a run: max_k |theta_k - theta_ref_k| over the outputs, each
/// difference taken modulo 2 pi (rad; theta from atan2, theta_ref counted over the turns); NaN
/// when an output is missing (NaN).
inline double crank_angle_error(const std::vector<double>& theta,
                                const std::vector<double>& theta_ref) {
  double err = 0.0;
  for (std::size_t k = 0; k < theta_ref.size(); ++k) {
    const double d = k < theta.size()
                         ? std::abs(std::remainder(theta[k] - theta_ref[k], 2 * std::numbers::pi))
                         : std::nan("");
    if (std::isnan(d)) {
      return d;
    }
    err = std::max(err, d);
  }
  return err;
}

}  // namespace n_four_bar_test
