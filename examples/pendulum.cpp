// The simple pendulum (problem A01 of the IFToMM multibody benchmark library): a point mass of
// 1 kg on a massless bar of 1 m, released at rest with the bar horizontal, under gravity, 10 s.
//
// Model: a small ball (1 kg, inertia 4e-5 kg m^2) whose centre hangs from the origin on a
// Distance joint of 1 m (a massless bar with spherical ends: it transmits no moment, so the
// ball's inertia does not enter its centre's motion). Gravity 9.81 m/s^2 along -y; the ball
// starts at rest at x = +1 m.
// Checks, printed: the ball's centre (the reference point) over time, against the closed form
//   theta(t) = 2 asin(k sn(K - w0 t | k^2)),   k = sin(theta0 / 2),  w0 = sqrt(g / l),
// theta from straight down (theta0 = pi / 2), the centre at l (sin theta, -cos theta); the energy
// balance (no dissipation: constant) and the bar's length. The program exits with status 1 if
// the trajectory or the energy is missed.
// Units: SI.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "support/amplitude.hpp"
#include "tumble/integrate.hpp"

int main() {
  using Eigen::Vector3d;
  using Ball = tumble::RigidBody<tumble::EulerParameters>;
  const double g = 9.81, l = 1.0;
  tumble::Mechanism<tumble::Bodies<Ball>, tumble::Joints<tumble::Distance>,
                    tumble::Loads<tumble::UniformGravity>>
      scene;
  const auto ball = scene.add(
      Ball(tumble::MassProperties<>::about_centroid(1.0, Eigen::Matrix3d::Identity() * 4e-5)),
      {.position = Vector3d(l, 0, 0)});
  scene.add_load(ball, tumble::UniformGravity(Vector3d(0, -g, 0)));
  scene.add_joint(ball, tumble::ground, tumble::Distance(Vector3d::Zero(), Vector3d::Zero(), l));

  const double theta0 = std::numbers::pi / 2, w0 = std::sqrt(g / l), k = std::sin(theta0 / 2);
  const double kk = std::comp_ellint_1(k);
  const auto exact = [&](double t) {  // the closed form's centre at t
    const double theta = 2 * std::asin(k * std::sin(tumble_examples::jacobi_am(kk - w0 * t, k)));
    return Vector3d(l * std::sin(theta), -l * std::cos(theta), 0);
  };
  std::vector<double> times;
  for (int i = 0; i <= 400; ++i) {
    times.push_back(0.025 * i);  // 10 s
  }
  const double tol = 1e-11;
  const double e0 = tumble::energy(scene, scene.initial_state());
  double worst_r = 0, worst_e = 0, worst_l = 0;
  std::size_t n = 0;
  std::printf("%6s %22s %12s %12s\n", "t (s)", "centre x, y (m)", "|r - exact|", "E - E0 (J)");
  const tumble::AutoStatistics st = tumble::integrate(
      scene, 0.0, times,
      [&](double t, const tumble::SceneState& s) {
        const Vector3d r = tumble::position(scene, ball, s);
        const double dr = (r - exact(t)).norm(), de = tumble::energy(scene, s) - e0;
        worst_r = std::max(worst_r, dr);
        worst_e = std::max(worst_e, std::abs(de));
        worst_l = std::max(worst_l, std::abs(r.norm() - l));
        if (n++ % 20 == 0) {  // every 0.5 s
          std::printf("%6.2f %10.6f %11.6f %12.3e %12.3e\n", t, r(0), r(1), dr, de);
        }
      },
      {.rtol = tol, .atol = tol});
  std::printf("%s, %ld steps; |r - exact| <= %.2e m, |E - E0| <= %.2e J (m g l = %.2f J), "
              "||r| - l| <= %.2e m\n",
              tumble::name(st.choices.front().method), st.steps, worst_r, worst_e, g * l, worst_l);
  return n == times.size() && worst_r <= 1e-8 && worst_e <= 1e-8 ? 0 : 1;
}
