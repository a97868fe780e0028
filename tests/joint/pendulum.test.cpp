// The physical pendulum, a rod hinged at its end to the ground, against its closed form in Jacobi
// elliptic functions: every family of parameterization, both state forms, the explicit integrator
// and CVODE's BDF, with the constraint drift and the energy kept over the run; and the hinge's
// reaction against Newton's second law for the rod's centroid, from the closed form of the motion.
// Compiled in slices, one parameterization each (tests/CMakeLists.txt); the hinge force is in
// slice 0.

#include "support/pendulum.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <vector>

#include <Eigen/Geometry>

#include "support/catch.hpp"
#include "support/parameterizations.hpp"
#include "tumble/integrate.hpp"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using namespace tumble;

constexpr double g0 = 9.81;

/// One of each family: Euler parameters, Euler angles, and the three vector charts.
using PendulumParameterizations = std::tuple<EulerParameters, EulerZYX, RotationVector,
                                             ModifiedRodriguesParameters, RodriguesParameters>;
using TUMBLE_TEST_SLICED_NAME(PendulumSlice) = tumble::test::ThisSlice<PendulumParameterizations>;

Matrix3d about_y(double a) { return Eigen::AngleAxisd(a, Vector3d::UnitY()).toRotationMatrix(); }

/// A slender box (the rod of the pendulum): mass m, length l along body z, 5 cm square section.
MassProperties<> rod(double m, double l) {
  const double s = 0.05;
  return MassProperties<>::about_centroid(
      m, Vector3d(m * (l * l + s * s) / 12, m * (l * l + s * s) / 12, m * s * s / 6).asDiagonal());
}

/// The physical pendulum's angle by its closed form (support/pendulum.hpp), w0^2 = m g d / I_o.
using tumble::test::pendulum_angle;

/// The pendulum: a rod of length l hinged at its top end to the ground at the origin, axis y,
/// released at rest from theta0 (the angle about y from hanging straight down).
template <class P, StateForm Form> struct Pendulum {
  using Body = RigidBody<P>;
  using SceneT = Mechanism<Bodies<Body>, Joints<Revolute>, Loads<UniformGravity>, Form>;
  static constexpr double m = 2.0, l = 1.2;
  SceneT scene;
  BodyId<Body> id;
  JointId<Revolute> hinge;
  double w0;

  explicit Pendulum(double theta0) {
    const Vector3d top(0, 0, 0.5 * l);
    const Matrix3d r0 = about_y(theta0);
    id = scene.add(Body(rod(m, l)), {.position = -r0 * top, .rotation = r0});
    scene.add_load(id, UniformGravity(Vector3d(0, 0, -g0)));
    hinge = scene.add_joint(id, ground,
                            Revolute(top, Vector3d::UnitY(), Vector3d::Zero(), Vector3d::UnitY()));
    const double io = rod(m, l).inertia_centroid()(1, 1) + m * 0.25 * l * l;
    w0 = std::sqrt(m * g0 * 0.5 * l / io);
  }
  [[nodiscard]] double angle(const SceneStateView& s) const {
    const Matrix3d r = rotation(scene, id, s);
    return std::atan2(r(0, 2), r(0, 0));
  }
};

/// Integrates the pendulum to t_end with the integrator Integrator and returns the largest error
/// of the angle against the closed form over 101 outputs, with the drift and energy checked.
/// energy_factor: the energy change allowed, in units of tol |E0| (the global error of the
/// method over the run: small for Fehlberg 7(8), larger for BDF's orders 1-5).
template <class Integrator, class Pend>
double pendulum_error(const Pend& p, double theta0, double t_end, double tol,
                      double energy_factor) {
  typename Integrator::Options opt;
  opt.rtol = tol;
  opt.atol = tol;
  Integrator integrator(p.scene, 0.0, opt);
  std::vector<double> times;
  for (int k = 0; k <= 100; ++k) {
    times.push_back(t_end * k / 100.0);
  }
  const double e0 = energy(p.scene, p.scene.initial_state());
  double err = 0.0, drift = 0.0, de = 0.0;
  integrator.integrate(times, [&](double t, const SceneState& s) {
    err = std::max(err, std::abs(p.angle(s) - pendulum_angle(theta0, p.w0, t)));
    const ConstraintResidual r = constraint_residual(p.scene, s);
    drift = std::max(drift, r.position);
    de = std::max(de, std::abs(energy(p.scene, s) - e0));
  });
  INFO("angle error " << err << " rad, drift " << drift << " m, energy change " << de << " J");
  CHECK(drift <= 1e-12);
  CHECK(de <= energy_factor * tol * std::abs(e0));
  return err;
}

}  // namespace

TEMPLATE_LIST_TEST_CASE("mechanism: the pendulum against its closed form", "[joint]",
                        TUMBLE_TEST_SLICED_NAME(PendulumSlice)) {
  const double theta0 = 2.5;  // rad: far from small oscillations
  // Bounds: the global error of ~7 swings at the local tolerance given (Fehlberg 7(8): about
  // 1e3 tol; BDF, of order 5 at most: 1e4 to 2e5 tol, below), and the drift at the projection's
  // level.
  SECTION("quasi-velocities, explicit") {
    const Pendulum<TestType, StateForm::quasi_velocities> p(theta0);
    using I = OdeintIntegrator<decltype(p.scene)>;
    CHECK(pendulum_error<I>(p, theta0, 10.0, 1e-12, 1e3) <= 5e-9);
  }
  SECTION("generalized, explicit") {
    const Pendulum<TestType, StateForm::generalized> p(theta0);
    using I = OdeintIntegrator<decltype(p.scene)>;
    CHECK(pendulum_error<I>(p, theta0, 10.0, 1e-12, 1e3) <= 5e-9);
  }
  SECTION("quasi-velocities, CVODE BDF") {
    // BDF's global error at 1e-11 over the ~7 swings, measured (GCC 12) for EP, ZYX, RV, MRP and
    // Gibbs: 1.4, 3.2, 1.4, 2.5 and 3.4e-7 rad with CVODE's error estimate left whole in the
    // hinge's normal directions; 3.8e-7, 1.7e-6, 3.9e-7, 2.5e-7 and 1.6e-7 with it projected
    // (scene/assembly.hpp, project_error_estimate), in 6-11 % fewer steps. ZYX's pitch passes its
    // singular value in each swing: each chart switch restarts BDF at order 1, and its error
    // scatters most (1e-10: 4.6e-7, 1e-11: 1.7e-6, 1e-12: 2.2e-7).
    const Pendulum<TestType, StateForm::quasi_velocities> p(theta0);
    using I = SceneIntegrator<decltype(p.scene)>;
    CHECK(pendulum_error<I>(p, theta0, 10.0, 1e-11, 3e4) <= 3e-6);
  }
}

#if TUMBLE_TEST_PRIMARY_SLICE
TEST_CASE("mechanism: the pendulum's hinge force is Newton's m a_g - m g", "[joint]") {
  const double theta0 = 1.1;
  const Pendulum<EulerParameters, StateForm::quasi_velocities> p(theta0);
  OdeintOptions opt;
  opt.rtol = 1e-12;
  opt.atol = 1e-12;
  OdeintIntegrator<decltype(p.scene)> integrator(p.scene, 0.0, opt);
  const double d = 0.5 * p.l;
  for (double t : {0.0, 0.37, 1.3, 2.9}) {
    integrator.advance(t);
    const SceneStateView s = integrator.state();
    // From the closed form of the motion: theta, thetadot, thetaddot = -w0^2 sin(theta); the
    // centroid at (-d sin, 0, -d cos), so a_g = d (-cos th thdd + sin th thd^2, 0,
    // sin th thdd + cos th thd^2).
    const double th = p.angle(s);
    const double thd = omega(p.scene, p.id, s)(1);  // about body y = inertial y
    const double thdd = -p.w0 * p.w0 * std::sin(th);
    const Vector3d ag = d * Vector3d(-std::cos(th) * thdd + std::sin(th) * thd * thd, 0,
                                     std::sin(th) * thdd + std::cos(th) * thd * thd);
    const Vector3d expected = p.m * ag - p.m * Vector3d(0, 0, -g0);
    const JointReaction r = joint_reaction(p.scene, s, t, p.hinge);
    INFO("t = " << t << ": reaction " << r.on_a.force.transpose() << ", Newton "
                << expected.transpose());
    CHECK((r.on_a.force - expected).norm() <= 1e-8 * expected.norm());
  }
}
#endif  // TUMBLE_TEST_PRIMARY_SLICE
