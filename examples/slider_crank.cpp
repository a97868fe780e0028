// A slider-crank under gravity: a mechanism of three bodies (crank, connecting rod, slider) and
// four joints (three hinges and a prismatic guide), with a closed loop.
//
// Problem: a crank of r = 0.2 m hinged to the ground at the origin (axis z), a connecting rod of
// l = 0.6 m, and a slider guided along the x axis; gravity along -y. The crank starts at
// phi0 = 1 rad turning at 5 rad/s; the rod and the slider are placed roughly and put onto the
// joints by tumble::assemble, which keeps the crank as given.
// Checks, printed: the slider's position against the loop's closed form
// x_C = r cos(phi) + sqrt(l^2 - r^2 sin^2(phi)) at the simulated crank angle, the energy balance
// (no dissipation: constant), the largest constraint residual, and the force on the crank's
// pivot. The program exits with status 1 if the closed form or the energy is missed.
// Units: SI.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "tumble/integrate.hpp"

int main() {
  using namespace tumble;
  using Eigen::Matrix3d;
  using Eigen::Vector3d;
  using Link = RigidBody<EulerParameters>;
  using SceneT = Mechanism<Bodies<Link>, Joints<Revolute, Prismatic>, Loads<UniformGravity>>;
  const double r = 0.2, l = 0.6, phi0 = 1.0, rate = 5.0;
  // Slender links along body x (2 cm square section); the slider a 10 cm cube.
  const auto bar = [](double m, double len) {
    const double s = 0.02;
    return Link(MassProperties<>::about_centroid(
        m, Vector3d(m * s * s / 6, m * (len * len + s * s) / 12, m * (len * len + s * s) / 12)
               .asDiagonal()));
  };
  const auto turned = [](double a) {
    return Matrix3d(Eigen::AngleAxisd(a, Vector3d::UnitZ()).toRotationMatrix());
  };

  SceneT scene;
  const Vector3d tip = r * Vector3d(std::cos(phi0), std::sin(phi0), 0);
  const auto crank = scene.add(bar(1.0, r), {.position = 0.5 * tip,
                                             .rotation = turned(phi0),
                                             .velocity = 0.5 * rate * Vector3d(-tip(1), tip(0), 0),
                                             .omega = {0, 0, rate}});
  const auto rod = scene.add(bar(2.0, l), {.position = Vector3d(0.35, 0.05, 0)});  // roughly
  const auto slider =
      scene.add(Link(MassProperties<>::about_centroid(0.5, Matrix3d::Identity() * 0.5 * 0.01 / 6)),
                {.position = Vector3d(0.65, 0, 0)});  // roughly
  const Vector3d z = Vector3d::UnitZ();
  const auto pivot =
      scene.add_joint(crank, ground, Revolute({-0.5 * r, 0, 0}, z, Vector3d::Zero(), z));
  scene.add_joint(crank, rod, Revolute({0.5 * r, 0, 0}, z, {-0.5 * l, 0, 0}, z));
  scene.add_joint(rod, slider, Revolute({0.5 * l, 0, 0}, z, Vector3d::Zero(), z));
  JointFrame guide;       // z along the inertial x axis: the sliding direction
  guide.axes << 0, 0, 1,  //
      1, 0, 0,            //
      0, 1, 0;
  scene.add_joint(slider, ground, Prismatic(guide, guide));
  for (const auto b : {crank, rod, slider}) {
    scene.add_load(b, UniformGravity(Vector3d(0, -9.81, 0)));
  }

  SceneState s0 = scene.initial_state();
  const AssemblyReport rep = assemble(scene, s0, {.keep = {crank.id}});
  std::printf("assembled in %d Newton iterations: |C| %.2e -> %.2e m, rank %d of %d rows\n",
              rep.iterations, rep.before.position, rep.after.position, rep.after.rank,
              scene.constraint_count());

  std::vector<double> times;
  for (int k = 0; k <= 20; ++k) {
    times.push_back(0.1 * k);
  }
  const double e0 = energy(scene, s0);
  double worst_x = 0, worst_e = 0, worst_c = 0;
  std::printf("%6s %10s %12s %12s %12s %10s\n", "t (s)", "phi (rad)", "x_C (m)", "closed form",
              "E - E0 (J)", "pivot |F|");
  const AutoStatistics st = integrate(
      scene, 0.0, s0, times,
      [&](double t, const SceneState& s) {
        const Vector3d dir = rotation(scene, crank, s) * Vector3d::UnitX();
        const double phi = std::atan2(dir(1), dir(0));
        const double xc = position(scene, slider, s)(0);
        const double exact = r * std::cos(phi) + std::sqrt(l * l - std::pow(r * std::sin(phi), 2));
        const double de = energy(scene, s) - e0;
        const JointReaction f = joint_reaction(scene, s, t, pivot);
        worst_x = std::max(worst_x, std::abs(xc - exact));
        worst_e = std::max(worst_e, std::abs(de));
        worst_c = std::max(worst_c, constraint_residual(scene, s).position);
        std::printf("%6.2f %10.6f %12.9f %12.9f %12.3e %10.4f\n", t, phi, xc, exact, de,
                    f.on_a.force.norm());
      },
      {.rtol = 1e-10, .atol = 1e-10});
  std::printf("%s, %ld steps; largest |x_C - closed form| %.2e m, |E - E0| %.2e J, |C| %.2e m\n",
              name(st.choices.front().method), st.steps, worst_x, worst_e, worst_c);
  return worst_x <= 1e-9 && worst_e <= 1e-7 * std::abs(e0) + 1e-9 ? 0 : 1;
}
