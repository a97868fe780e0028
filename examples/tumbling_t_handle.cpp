// The tumbling T-handle: the Dzhanibekov effect (intermediate-axis theorem).
//
// Problem: a T-shaped handle spun about its intermediate principal axis in free space flips
// periodically by 180 degrees. We build its mass properties from its two rods, integrate the
// torque-free motion with CVODE, and write omega(t) as a CSV file and a PNG plot.
//
// Equations: torque-free rigid body, M qddot = f_v (reference chapter Eq. 1.33 with Q = 0), which
// tumble solves as I alpha = -omega x I omega in the body frame; the kinetic energy T and the
// inertial angular momentum h = R I omega are constants of the motion (printed as a check).
// Units: SI (m, kg, s, rad). Orientation: Euler parameters (no singularity), Adams method.
//
// Run: ./tumbling_t_handle [output folder]   (default: the current folder)

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "support/png_plot.hpp"
#include "tumble/cvode.hpp"

int main(int argc, char** argv) {
  using namespace tumble;
  const std::string out = argc > 1 ? argv[1] : ".";

  // Two thin rods of 0.1 kg: the handle (0.10 m along x) and the bar (0.08 m along y) welded at
  // the handle's end. Reference point: the joint; inertia about it, then shifted to the centroid.
  const double m_rod = 0.1, l_handle = 0.10, l_bar = 0.08;
  const Eigen::Vector3d c_handle(l_handle / 2, 0, 0), c_bar(0, 0, 0);
  Eigen::Matrix3d i_handle = Eigen::Vector3d(1e-9, 1, 1).asDiagonal();  // thin rod along x
  i_handle *= m_rod * l_handle * l_handle / 12;
  Eigen::Matrix3d i_bar = Eigen::Vector3d(1, 1e-9, 1).asDiagonal();  // thin rod along y
  i_bar *= m_rod * l_bar * l_bar / 12;
  const double m = 2 * m_rod;
  const Eigen::Vector3d centroid = (m_rod * c_handle + m_rod * c_bar) / m;
  const Eigen::Matrix3d i_joint = i_handle + MassProperties<>::parallel_axis(m_rod, c_handle) +
                                  i_bar + MassProperties<>::parallel_axis(m_rod, c_bar);
  const auto mp = MassProperties<>::about_reference(m, i_joint, centroid);
  // The body frame at the centroid, axes along the rods (already principal by symmetry).
  using Body = RigidBody<EulerParameters>;
  const Body body(MassProperties<>::about_centroid(m, mp.inertia_centroid()));
  const Eigen::Vector3d moments = mp.principal_moments();
  std::printf("principal moments about the centroid: %.4e %.4e %.4e kg m^2\n", moments(0),
              moments(1), moments(2));

  // Spin about the intermediate axis (y: the bar, I_x < I_y < I_z) with a tiny perturbation.
  Scene<Bodies<Body>> scene;
  const auto id = scene.add(body, {.omega = {0.01, 10.0, 0.0}});
  SceneIntegratorOptions options;
  options.method = CvodeMethod::adams;
  options.rtol = 1e-10;
  options.atol = 1e-12;
  SceneIntegrator integrator(scene, 0.0, options);

  const double t_end = 10.0;
  std::vector<double> t, wx, wy, wz;
  const double e0 = tumble::kinetic_energy(scene, scene.initial_state());
  const Eigen::Vector3d h0 = tumble::angular_momentum(scene, scene.initial_state());
  std::ofstream csv(out + "/t_handle_omega.csv");
  csv << "t_s,omega_x_rad_s,omega_y_rad_s,omega_z_rad_s\n";
  std::vector<double> times;
  for (int k = 0; k <= 2000; ++k) times.push_back(t_end * k / 2000);
  integrator.integrate(times, [&](double tk, const tumble::SceneState& y) {
    const Eigen::Vector3d w = tumble::omega(scene, id, y);
    t.push_back(tk);
    wx.push_back(w(0));
    wy.push_back(w(1));
    wz.push_back(w(2));
    csv << tk << ',' << w(0) << ',' << w(1) << ',' << w(2) << '\n';
  });
  const tumble::SceneState& y = integrator.state();
  int flips = 0;
  for (std::size_t k = 1; k < wx.size(); ++k) flips += (wy[k - 1] > 0) != (wy[k] > 0);

  tumble_examples::PngPlot plot(900, 500, "T-handle: body angular velocity (Dzhanibekov effect)");
  plot.set_labels("t (s)", "omega (rad/s)");
  plot.add(t, wx, {200, 30, 30}, "omega x");
  plot.add(t, wy, {30, 140, 30}, "omega y");
  plot.add(t, wz, {30, 60, 200}, "omega z");
  plot.write(out + "/t_handle_omega.png");

  const auto s = integrator.statistics();
  std::printf("sign changes of omega_y (flips) in %.0f s: %d\n", t_end, flips);
  std::printf("relative energy drift: %.2e, angular momentum drift: %.2e\n",
              std::abs(tumble::kinetic_energy(scene, y) - e0) / e0,
              (tumble::angular_momentum(scene, y) - h0).norm() / h0.norm());
  std::printf("quaternion constraint drift: %.2e\n", tumble::constraint_drift(scene, y));
  std::printf("CVODE: %ld steps, %ld right-hand sides\n", s.steps, s.rhs_evals);
  std::printf("wrote %s/t_handle_omega.csv and %s/t_handle_omega.png\n", out.c_str(), out.c_str());
  return 0;
}
