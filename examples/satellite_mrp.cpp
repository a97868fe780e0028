// A satellite slewing with modified Rodrigues parameters (MRP) and a PD attitude controller.
//
// Problem: a rigid spacecraft (principal inertia 10, 15, 20 kg m^2), turned 100 deg about a
// skewed axis a and tumbling at omega0 = (0.05, -0.08, 0.1) rad/s, must turn to 240 deg about a
// (the short way, through 180 deg, where |sigma| = 1). Its attitude is integrated in MRP, sigma = n
// tan(phi/4), which are singular only at 360 deg; the scene switches to the shadow set
// -sigma/|sigma|^2 whenever |sigma| > 1, so the coordinates stay bounded (the switches are
// counted). Equations: I alpha = M - omega x I omega (reference chapter Eq. 1.33 with Q = [0; G^T
// M]), control moment M = -Kp sigma_e - Kd omega, with sigma_e the (short-way) MRP of the attitude
// error R_target^T R, in body components (a UserForce that reads R and omega).
// Units: SI; angles in rad.

#include <cstdio>
#include <numbers>

#include "tumble/cvode.hpp"

int main() {
  using namespace tumble;
  using Mrp = ModifiedRodriguesParameters;
  using Sat = RigidBody<Mrp>;
  const Eigen::Matrix3d inertia = Eigen::Vector3d(10, 15, 20).asDiagonal();
  const Eigen::Vector3d axis = Eigen::Vector3d(1, 2, 3).normalized();
  const double deg = std::numbers::pi / 180;
  const Eigen::Matrix3d start = Eigen::AngleAxisd(100 * deg, axis).toRotationMatrix();
  const Eigen::Matrix3d target = Eigen::AngleAxisd(240 * deg, axis).toRotationMatrix();
  const double kp = 2.0, kd = 12.0;  // N m, N m s: time constant about Kd/Kp = 6 s

  auto controller = make_user_force<true>([&](double, const KinematicsView<double>& k) {
    const Eigen::Vector3d sigma_e = Mrp::from_rotation<double>(target.transpose() * k.rotation);
    Wrench<double> w;
    w.add_moment(-kp * sigma_e - kd * k.omega);
    return w;
  });
  using Controller = decltype(controller);

  Scene<Bodies<Sat>, Loads<Controller>> scene;
  const auto id = scene.add(Sat(MassProperties<>::about_centroid(500.0, inertia)),
                            {.rotation = start, .omega = {0.05, -0.08, 0.1}});
  scene.add_load(id, controller);

  SceneIntegratorOptions options;
  options.method = CvodeMethod::adams;
  options.rtol = 1e-9;
  options.atol = 1e-11;
  SceneIntegrator integrator(scene, 0.0, options);
  std::printf("   t (s)   error (deg)   |omega| (rad/s)   |sigma|\n");
  for (double t : {0.0, 10.0, 20.0, 40.0, 60.0, 90.0, 120.0}) {
    integrator.advance(t);  // nothing to do at t = 0
    const tumble::SceneState& y = integrator.state();
    const Eigen::Matrix3d e = target.transpose() * tumble::rotation(scene, id, y);
    const double err = Eigen::AngleAxisd(e).angle() / deg;
    std::printf("%8.1f %13.4f %17.3e %9.4f\n", t, err, tumble::omega(scene, id, y).norm(),
                y.y.segment<3>(scene.offset(id) + 3).norm());
  }
  const auto s = integrator.statistics();
  std::printf("MRP shadow-set switches: %ld; CVODE: %ld steps, %ld right-hand sides\n",
              s.chart_switches, s.steps, s.rhs_evals);
  return 0;
}
