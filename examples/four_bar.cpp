// The N-four-bar (problem A02 of the IFToMM multibody benchmark library): N + 1 cranks hinged to
// the ground 1 m apart and N couplers joining their tips, every link 1 m and 1 kg, under gravity,
// 10 s. Started with the cranks up and the first crank's tip B0 at 1 m/s, the cranks turn over
// and over, and twice per turn every link lies on the ground line: a singular position, where the
// loops momentarily gain N degrees of freedom and the hinges' constraints are dependent.
//
// Model: the links are rods of 1 cm square section, hinged about z; gravity 9.81 m/s^2 along -y.
// The crank angle theta is counted from +y towards +x. Usage: four_bar [N] (1 to 10, default 2).
// Checks, printed: B0 (the reference point) and theta over time, against the closed form. The
// cranks stay parallel and the couplers translate, so the mechanism is one pendulum turning over
// (I theta'' = G sin theta, I = (N + 1) I_o + N m l^2, G = ((N + 1) / 2 + N) m g l, I_o a crank
// about its pivot):
//   theta(t) = 2 am(K + w0 t / k | k^2) - pi,   w0^2 = G / I,   k^2 = 4 w0^2 / (w^2 + 4 w0^2),
// w = 1 rad/s the start's rate. Also the energy balance (no dissipation: constant) and the
// largest constraint residual. The program exits with status 1 if theta or the energy is missed.
// Units: SI.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <vector>

#include <Eigen/Geometry>

#include "support/amplitude.hpp"
#include "tumble/integrate.hpp"

int main(int argc, char** argv) {
  using Eigen::Vector3d;
  using Rod = tumble::RigidBody<tumble::EulerParameters>;
  const int links = argc > 1 ? std::atoi(argv[1]) : 2;  // N
  if (links < 1 || links > 10) {  // the loops' constraint solve is dense: its cost grows as N^3
    std::fprintf(stderr, "four_bar: N must be 1 to 10 (N = 10 takes some 8 s), not %s\n", argv[1]);
    return 2;
  }
  const double g = 9.81, m = 1.0, l = 1.0, section = 0.01;
  const double i_end = m * (l * l + section * section) / 12;  // a rod about a transverse axis
  const Rod rod(tumble::MassProperties<>::about_centroid(
      m, Vector3d(m * section * section / 6, i_end, i_end).asDiagonal()));
  tumble::Mechanism<tumble::Bodies<Rod>, tumble::Joints<tumble::Revolute>,
                    tumble::Loads<tumble::UniformGravity>>
      scene;
  // Body x along each link; a crank points up (+y) and turns at -1 rad/s about z, so that its
  // tip moves at +1 m/s along x; a coupler lies along x and translates with the tips.
  const Vector3d z = Vector3d::UnitZ(), half(0.5 * l, 0, 0);
  const Eigen::Matrix3d up = Eigen::AngleAxisd(std::numbers::pi / 2, z).toRotationMatrix();
  std::vector<tumble::BodyId<Rod>> crank;
  for (int i = 0; i <= links; ++i) {
    crank.push_back(scene.add(rod, {.position = Vector3d(i * l, 0.5 * l, 0),
                                    .rotation = up,
                                    .velocity = Vector3d(0.5, 0, 0),
                                    .omega = -z}));
    scene.add_joint(crank.back(), tumble::ground,
                    tumble::Revolute(-half, z, Vector3d(i * l, 0, 0), z));
  }
  for (int i = 0; i < links; ++i) {
    const auto c =
        scene.add(rod, {.position = Vector3d((i + 0.5) * l, l, 0), .velocity = Vector3d(1, 0, 0)});
    scene.add_joint(c, crank[std::size_t(i)], tumble::Revolute(-half, z, half, z));
    scene.add_joint(c, crank[std::size_t(i) + 1], tumble::Revolute(half, z, half, z));
  }
  for (int b = 0; b < scene.body_count(); ++b) {
    scene.add_load(tumble::BodyId<Rod>{b, b}, tumble::UniformGravity(Vector3d(0, -g, 0)));
  }

  // The closed form of the file comment.
  const double inertia = (links + 1) * (i_end + m * l * l / 4) + links * m * l * l;
  const double w0 = std::sqrt(((links + 1) / 2.0 + links) * m * g * l / inertia), w = 1.0;
  const double k = 2 * w0 / std::sqrt(w * w + 4 * w0 * w0), kk = std::comp_ellint_1(k);
  const auto exact = [&](double t) {
    return 2 * tumble_examples::jacobi_am(kk + w0 * t / k, k) - std::numbers::pi;
  };
  std::vector<double> times;
  for (int i = 0; i <= 100; ++i) {
    times.push_back(0.1 * i);  // 10 s
  }
  const double tol = 1e-10;
  const double e0 = tumble::energy(scene, scene.initial_state());
  double worst_theta = 0, worst_e = 0, worst_c = 0;
  std::size_t n = 0;
  std::printf("%d-four-bar: %d bodies, %d hinges, %d constraint rows\n", links, scene.body_count(),
              3 * links + 1, scene.constraint_count());
  std::printf("%6s %22s %12s %12s %12s\n", "t (s)", "B0 x, y (m)", "theta (rad)", "error (rad)",
              "E - E0 (J)");
  const tumble::AutoStatistics st = tumble::integrate(
      scene, 0.0, times,
      [&](double t, const tumble::SceneState& s) {
        const Vector3d b0 =
            tumble::position(scene, crank[0], s) + tumble::rotation(scene, crank[0], s) * half;
        const double theta = std::atan2(b0(0), b0(1));  // the crank from its pivot at the origin
        const double err = std::abs(std::remainder(theta - exact(t), 2 * std::numbers::pi));
        const double de = tumble::energy(scene, s) - e0;
        worst_theta = std::max(worst_theta, err);
        worst_e = std::max(worst_e, std::abs(de));
        worst_c = std::max(worst_c, tumble::constraint_residual(scene, s).position);
        if (n++ % 5 == 0) {  // every 0.5 s
          std::printf("%6.2f %10.6f %11.6f %12.6f %12.3e %12.3e\n", t, b0(0), b0(1), theta, err,
                      de);
        }
      },
      {.rtol = tol, .atol = tol});
  std::printf("%s, %ld steps; |theta - exact| <= %.2e rad, |E - E0| <= %.2e J of %.4f J, |C| <= "
              "%.2e m\n",
              tumble::name(st.choices.front().method), st.steps, worst_theta, worst_e, e0, worst_c);
  return n == times.size() && worst_theta <= 1e-5 && worst_e <= 1e3 * tol * std::abs(e0) ? 0 : 1;
}
