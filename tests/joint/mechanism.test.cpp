// Mechanisms against independent references: a spherical joint to the ground against the body
// held at that point (its own equations, Eq. 1.32 with rddot_oc = 0), the physical pendulum
// against its closed form in Jacobi elliptic functions, a welded pair against the one rigid body
// it makes, energy and constraint drift over long runs, reactions against Newton's second law,
// both integrators and the front door, every family of parameterization and both state forms.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <Eigen/Geometry>

#include "support/catch.hpp"
#include "support/random.hpp"
#include "support/torque_free.hpp"
#include "tumble/integrate.hpp"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using Eigen::VectorXd;
using namespace tumble;

constexpr double g0 = 9.81;

Matrix3d about_y(double a) { return Eigen::AngleAxisd(a, Vector3d::UnitY()).toRotationMatrix(); }

/// A slender box (the rod of the pendulum): mass m, length l along body z, 5 cm square section.
MassProperties<> rod(double m, double l) {
  const double s = 0.05;
  return MassProperties<>::about_centroid(
      m, Vector3d(m * (l * l + s * s) / 12, m * (l * l + s * s) / 12, m * s * s / 6).asDiagonal());
}

/// The physical pendulum's angle by its closed form: theta(t) = 2 asin(k sn(K - w0 t | k^2)),
/// k = sin(theta0 / 2), w0^2 = m g d / I_o (released at rest from theta0).
double pendulum_angle(double theta0, double w0, double t) {
  const double k = std::sin(0.5 * theta0);
  const double kk = std::comp_ellint_1(k);
  const auto e = tumble::test::jacobi_sn_cn_dn(kk - w0 * t, k * k);
  return 2.0 * std::asin(k * e.sn);
}

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

TEST_CASE("mechanism: a spherical joint to the ground is the body held at that point", "[joint]") {
  // One body, Euler parameters, in two models: free (centroid) with a spherical joint at its
  // point s to the ground point o, and held at o (ReferencePoint::fixed_point, centroid at -s).
  using Free = RigidBody<EulerParameters>;
  using Held = RigidBody<EulerParameters, ReferencePoint::fixed_point>;
  const double m = 3.0;
  const Matrix3d ig = Vector3d(0.4, 0.6, 0.3).asDiagonal();
  const Vector3d s(0.1, -0.2, 0.5), o(0.3, 0.2, 1.0);
  const Matrix3d r0 = Eigen::AngleAxisd(0.8, Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Vector3d w(1.5, -2.0, 4.0);
  const UniformGravity gravity(Vector3d(0, 0, -g0));

  Mechanism<Bodies<Free>, Joints<Spherical>, Loads<UniformGravity>> joined;
  const auto a = joined.add(
      Free(MassProperties<>::about_centroid(m, ig)),
      {.position = o - r0 * s, .rotation = r0, .velocity = -(r0 * w.cross(s)), .omega = w});
  joined.add_load(a, gravity);
  const auto sph = joined.add_joint(a, ground, Spherical(s, o));

  Scene<Bodies<Held>, Loads<UniformGravity>> held;
  const auto b =
      held.add(Held(MassProperties<>::about_centroid(m, ig, -s), o), {.rotation = r0, .omega = w});
  held.add_load(b, gravity);

  SECTION("the same accelerations, to rounding") {
    SceneWorkspace<decltype(joined)> wj(joined);
    SceneWorkspace<decltype(held)> wh(held);
    VectorXd fj(joined.size()), fh(held.size());
    rhs(joined, wj, 0.0, joined.initial_state(), fj);
    rhs(held, wh, 0.0, held.initial_state(), fh);
    const Vector3d alpha_j = fj.tail<3>(), alpha_h = fh.tail<3>();
    INFO("alpha joined " << alpha_j.transpose() << ", held " << alpha_h.transpose());
    CHECK((alpha_j - alpha_h).norm() <= 1e-14 * alpha_h.norm());
    CHECK((fj.segment<4>(3) - fh.head<4>()).norm() <= 1e-15 * fh.head<4>().norm());
    // The centroid's acceleration of the held body, R (alpha x r_g + omega x (omega x r_g)).
    const Vector3d ag = r0 * (alpha_h.cross(-s) + w.cross(w.cross(-s)));
    CHECK((fj.segment<3>(7) - ag).norm() <= 1e-14 * ag.norm());
    // The reaction at the point: the support's force on the body, both ways.
    const JointReaction rj = joint_reaction(joined, joined.initial_state(), 0.0, sph);
    const Vector3d rh = reaction_force(held, b, held.initial_state(), 0.0);
    INFO("reaction joined " << rj.on_a.force.transpose() << ", held " << rh.transpose());
    CHECK((rj.on_a.force - rh).norm() <= 1e-13 * rh.norm());
    CHECK((rj.on_b.force + rh).norm() <= 1e-13 * rh.norm());
  }
  SECTION("the same motion, to the integrators' tolerance") {
    OdeintOptions opt;
    opt.rtol = 1e-12;
    opt.atol = 1e-12;
    OdeintIntegrator<decltype(joined)> ij(joined, 0.0, opt);
    OdeintIntegrator<decltype(held)> ih(held, 0.0, opt);
    double worst = 0.0;
    for (int k = 1; k <= 20; ++k) {
      ij.advance(0.5 * k);
      ih.advance(0.5 * k);
      worst = std::max(worst, tumble::test::rotation_angle_between(rotation(joined, a, ij.state()),
                                                                   rotation(held, b, ih.state())));
      CHECK(constraint_residual(joined, ij.state()).position <= 1e-12);
    }
    INFO("largest attitude difference over 10 s: " << worst << " rad");
    CHECK(worst <= 1e-9);
  }
}

TEMPLATE_TEST_CASE("mechanism: the pendulum against its closed form", "[joint]", EulerParameters,
                   EulerZYX, RotationVector, ModifiedRodriguesParameters, RodriguesParameters) {
  const double theta0 = 2.5;  // rad: far from small oscillations
  // Bounds: the global error of ~7 swings at the local tolerance given (Fehlberg 7(8): about
  // 1e3 tol; BDF, of order 5 at most: about 1e4 tol), and the drift at the projection's level.
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
    const Pendulum<TestType, StateForm::quasi_velocities> p(theta0);
    using I = SceneIntegrator<decltype(p.scene)>;
    CHECK(pendulum_error<I>(p, theta0, 10.0, 1e-11, 3e4) <= 1e-6);
  }
}

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

TEST_CASE("mechanism: two bodies welded move as the one rigid body they make", "[joint]") {
  using Body = RigidBody<EulerParameters>;
  using One = RigidBody<EulerParameters, ReferencePoint::offset>;
  const double m1 = 2.0, m2 = 1.0;
  const Matrix3d i1 = Vector3d(0.2, 0.3, 0.4).asDiagonal(),
                 i2 = Vector3d(0.1, 0.05, 0.12).asDiagonal();
  const Vector3d c2(0.4, 0.1, -0.2);  // body 2's centroid in body 1's frame (frames parallel)
  const Matrix3d r0 = Eigen::AngleAxisd(0.5, Vector3d(1, -1, 2).normalized()).toRotationMatrix();
  const Vector3d w(0.3, 2.0, -0.7), v(0.1, 0.0, 0.2), x0(1.0, 2.0, 3.0);

  Mechanism<Bodies<Body>, Joints<Weld>> welded;
  const auto b1 = welded.add(Body(MassProperties<>::about_centroid(m1, i1)),
                             {.position = x0, .rotation = r0, .velocity = v, .omega = w});
  welded.add(
      Body(MassProperties<>::about_centroid(m2, i2)),
      {.position = x0 + r0 * c2, .rotation = r0, .velocity = v + r0 * w.cross(c2), .omega = w});
  welded.add_joint(b1, BodyId<Body>{1, 1},
                   Weld(JointFrame{c2, Matrix3d::Identity()}, JointFrame{}));

  // The one body: reference at body 1's centroid, centroid at m2 c2 / M, inertia about it by the
  // parallel axis theorem.
  const double mt = m1 + m2;
  const Vector3d g = m2 * c2 / mt;
  const auto shift = [](double m, const Vector3d& d) {
    return Matrix3d(m * (d.squaredNorm() * Matrix3d::Identity() - d * d.transpose()));
  };
  const Matrix3d ig = i1 + shift(m1, -g) + i2 + shift(m2, c2 - g);
  Scene<Bodies<One>> one;
  const auto o = one.add(One(MassProperties<>::about_centroid(mt, ig, g)),
                         {.position = x0, .rotation = r0, .velocity = v, .omega = w});

  OdeintOptions opt;
  opt.rtol = 1e-12;
  opt.atol = 1e-12;
  OdeintIntegrator<decltype(welded)> iw(welded, 0.0, opt);
  OdeintIntegrator<decltype(one)> io(one, 0.0, opt);
  double da = 0.0, dx = 0.0;
  for (int k = 1; k <= 20; ++k) {
    iw.advance(0.25 * k);
    io.advance(0.25 * k);
    da = std::max(da, tumble::test::rotation_angle_between(rotation(welded, b1, iw.state()),
                                                           rotation(one, o, io.state())));
    dx = std::max(dx, (position(welded, b1, iw.state()) - position(one, o, io.state())).norm());
  }
  INFO("attitude difference " << da << " rad, position difference " << dx << " m");
  CHECK(da <= 1e-9);
  CHECK(dx <= 1e-9);
}
