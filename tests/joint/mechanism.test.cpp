// Mechanisms against independent references: a spherical joint to the ground against the body
// held at that point (its own equations, Eq. 1.32 with rddot_oc = 0: the same accelerations and
// reactions to rounding, the same motion), a welded pair against the one rigid body it makes,
// and a free-floating chain against the conservation of its momenta and energy over 10^4 s.
// The pendulum against its closed form: pendulum.test.cpp.

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Geometry>

#include "support/body_fixtures.hpp"
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

TEST_CASE("mechanism: a free-floating chain keeps its momenta, its energy and its joints over "
          "10^4 s",
          "[joint]") {
  // Three bodies in space, no load and no joint to the ground: a spherical joint between the
  // first two, a hinge between the last two. The joints' forces are internal, so the linear
  // momentum and the angular momentum about the origin are conserved, as the energy is; the
  // projection after each step is an internal impulse too (it moves the velocities along
  // M^-1 J^T). Started off the constraints (rough positions, arbitrary velocities) and assembled.
  using Body = RigidBody<EulerParameters>;
  Mechanism<Bodies<Body>, Joints<Spherical, Revolute>> scene;
  const auto box = [](double m, const Vector3d& sides) {
    return Body(
        MassProperties<>::about_centroid(m, tumble::test::box_moments(m, sides).asDiagonal()));
  };
  const auto a =
      scene.add(box(3.0, Vector3d(0.6, 0.4, 0.3)),
                {.velocity = Vector3d(0.1, -0.2, 0.05), .omega = Vector3d(0.4, 1.1, -0.3)});
  const auto b =
      scene.add(box(1.5, Vector3d(0.8, 0.25, 0.2)),
                {.position = Vector3d(0.72, 0.02, -0.01),
                 .rotation = Eigen::AngleAxisd(0.1, Vector3d::UnitZ()).toRotationMatrix(),
                 .velocity = Vector3d(-0.3, 0.5, 0.2),
                 .omega = Vector3d(-0.8, 0.2, 0.6)});
  // The third body's velocity makes the total momentum zero, so that the chain stays near the
  // origin: the projection's tolerance is relative to the largest |r_oc| (assembly.hpp), and a
  // chain drifting 470 m away in 10^4 s is held to 4.7e-11 m instead of 1.4e-13 m.
  const auto c =
      scene.add(box(1.0, Vector3d(0.5, 0.3, 0.2)), {.position = Vector3d(1.37, 0.0, 0.05),
                                                    .velocity = Vector3d(0.15, -0.15, -0.45),
                                                    .omega = Vector3d(0.3, -0.5, 0.9)});
  scene.add_joint(a, b, Spherical(Vector3d(0.3, 0, 0), Vector3d(-0.4, 0, 0)));
  scene.add_joint(
      b, c,
      Revolute(Vector3d(0.4, 0, 0), Vector3d::UnitZ(), Vector3d(-0.25, 0, 0), Vector3d::UnitZ()));
  SceneState s = scene.initial_state();
  const AssemblyReport report = assemble(scene, s);
  REQUIRE(report.before.position >= 1e-3);  // it did start off the constraints
  REQUIRE(report.after.position <= 1e-12);
  REQUIRE(report.after.velocity <= 1e-12);

  const Vector3d p0 = linear_momentum(scene, s), h0 = angular_momentum(scene, s);
  const double e0 = energy(scene, s), tol = 1e-8;
  OdeintOptions opt;
  opt.rtol = tol;
  opt.atol = tol;
  OdeintIntegrator<decltype(scene)> integrator(scene, 0.0, s, opt);
  double dp = 0, dh = 0, de = 0, dc = 0, dv = 0;
  for (int k = 1; k <= 100; ++k) {
    integrator.advance(100.0 * k);  // to 10^4 s
    const SceneState& x = integrator.state();
    dp = std::max(dp, (linear_momentum(scene, x) - p0).norm());
    dh = std::max(dh, (angular_momentum(scene, x) - h0).norm());
    de = std::max(de, std::abs(energy(scene, x) - e0));
    const ConstraintResidual r = constraint_residual(scene, x);
    dc = std::max(dc, r.position);
    dv = std::max(dv, r.velocity);
  }
  INFO("over 10^4 s, " << integrator.statistics().steps << " steps: |p - p0| " << dp
                       << " kg m/s of " << p0.norm() << ", |H - H0| " << dh << " kg m^2/s of "
                       << h0.norm() << ", |E - E0| " << de << " J of " << e0 << ", |C| " << dc
                       << ", |J nu| " << dv);
  // The joints at rounding over the whole run (the chain spans about 1.5 m), and the linear
  // momentum (zero: the projection moves it by internal impulses only, and the integrator's
  // error in it cancels, as the joints' forces do in its rate); the angular momentum and the
  // energy within the run's global error, at most one tolerance per step (measured: 1.3e-6 and
  // 1.2e-5 relative at 1e-8 in 29918 steps, 100 times less at 1e-10: the truncation error).
  const double steps = static_cast<double>(integrator.statistics().steps);
  CHECK(dc <= 1e-12);
  CHECK(dv <= 1e-12);
  CHECK(dp <= 1e-12);
  CHECK(dh <= steps * tol * h0.norm());
  CHECK(de <= steps * tol * e0);
}
