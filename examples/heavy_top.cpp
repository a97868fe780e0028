// A heavy symmetric top held at its tip by a stiff spring-damper: a stiff problem for BDF.
//
// Problem: a top of mass m spins fast about its symmetry axis, tilted from the vertical; its tip
// is held at the inertial origin by a stiff isotropic spring-damper (a penalty joint, k/m =
// 2e6 s^-2) instead of an ideal pivot. Gravity makes it precess.
// Equations: the body is framed at its tip (ReferencePoint::offset, centroid at l along the
// symmetry axis), so M has the coupling block m12 and f_v its translational part (reference
// chapter Eqs. 1.21b, 1.26); loads: gravity m g at the centroid and the spring force
// F = -k r_tip - c v_tip at the tip (Eq. 1.30). The spring's fast mode (period 2 pi/sqrt(k/m) =
// 4.4 ms) makes the system stiff: BDF with Newton steps over it, Adams must resolve it.
// Check: for a fast top the mean precession rate is close to Omega = m g l / (I3 omega3).
// Units: SI.

#include <cmath>
#include <cstdio>
#include <numbers>

#include "tumble/cvode.hpp"

int main() {
  using namespace tumble;
  const double m = 0.5, l = 0.05, i1 = 1.5e-3, i3 = 1.0e-3, spin = 150.0, tilt = 0.35;
  using Top = RigidBody<EulerParameters, ReferencePoint::offset>;
  const Top top(MassProperties<>::about_centroid(m, Eigen::Vector3d(i1, i1, i3).asDiagonal(),
                                                 Eigen::Vector3d(0, 0, l)));
  Scene<Bodies<Top>, Loads<UniformGravity, SpringDamper>> scene;
  const Eigen::Matrix3d r0 = Eigen::AngleAxisd(tilt, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const auto id = scene.add(top, {.rotation = r0, .omega = {0, 0, spin}});
  scene.add_load(id, UniformGravity({0, 0, -9.81}));
  scene.add_load(id, SpringDamper({0, 0, 0}, {0, 0, 0},
                                  {.stiffness = 1e6, .damping = 100.0, .rest_length = 0.0}));

  SceneIntegratorOptions options;
  options.cvode.method = CvodeMethod::bdf;
  options.cvode.rtol = 1e-8;
  options.cvode.atol = 1e-10;
  SceneIntegrator integrator(scene, 0.0, options);

  // Precession: the azimuth of the symmetry axis R e3, unwrapped.
  const double t_end = 4.0;
  double azimuth = 0, last = 0, tip_max = 0;
  bool first = true;
  for (int k = 1; k <= 4000; ++k) {
    const tumble::SceneState& y = integrator.advance(t_end * k / 4000);
    const Eigen::Vector3d axis = tumble::rotation(scene, id, y).col(2);
    const double a = std::atan2(axis(1), axis(0));
    if (!first) {
      double d = a - last;
      d -= 2 * std::numbers::pi * std::round(d / (2 * std::numbers::pi));
      azimuth += d;
    }
    first = false;
    last = a;
    tip_max = std::max(tip_max, tumble::position(scene, id, y).norm());
  }
  const auto s = integrator.statistics();
  const double omega_fast = m * 9.81 * l / (i3 * spin);
  std::printf("mean precession rate: %.4f rad/s (fast-top estimate m g l/(I3 w3) = %.4f rad/s)\n",
              azimuth / t_end, omega_fast);
  std::printf("largest tip displacement from the pivot: %.2e m (static sag m g/k = %.2e m)\n",
              tip_max, m * 9.81 / 1e6);
  std::printf("BDF: %ld steps, %ld right-hand sides, %ld Jacobians, quaternion drift %.1e\n",
              s.steps, s.rhs_evals, s.jacobian_evals,
              tumble::constraint_drift(scene, integrator.state()));
  return 0;
}
