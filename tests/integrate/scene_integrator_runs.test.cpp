// Tests of tumble::SceneIntegrator (include/tumble/integrate/scene_integrator.hpp) over a run:
// reset() mid-run and near a chart's singularity, the statistics of chart switches, the absence
// of heap allocations in advance(), and one scene read by integrators in two threads at once.
// Its setup: scene_integrator.test.cpp.

// Must precede every Eigen include (see integrate/alloc_counter.hpp).
#define EIGEN_RUNTIME_NO_MALLOC

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "integrate/alloc_counter.hpp"
#include "support/catch.hpp"
#include "support/parameterizations.hpp"
#include "support/random.hpp"
#include "support/scene_fixtures.hpp"
#include "support/torque_free.hpp"
#include "tumble/body/rigid_body.hpp"
#include "tumble/force/coupling.hpp"
#include "tumble/force/gravity.hpp"
#include "tumble/force/spring_damper.hpp"
#include "tumble/force/user_force.hpp"
#include "tumble/integrate/errors.hpp"
#include "tumble/integrate/scene_integrator.hpp"
#include "tumble/scene/observables.hpp"
#include "tumble/scene/scene.hpp"
#include "tumble/scene/state.hpp"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using Eigen::VectorXd;
using tumble::Bodies;
using tumble::CvodeError;
using tumble::CvodeMethod;
using tumble::InitialState;
using tumble::IntegrationError;
using tumble::Loads;
using tumble::MassProperties;
using tumble::ReferencePoint;
using tumble::RigidBody;
using tumble::Scene;
using tumble::SceneIntegrator;
using tumble::SceneIntegratorOptions;
using tumble::SceneState;
using tumble::test::rotation_angle_between;
using tumble::test::TorqueFreeBody;

using EP = RigidBody<tumble::EulerParameters>;
using EPOff = RigidBody<tumble::EulerParameters, ReferencePoint::offset>;
using ZYX = RigidBody<tumble::EulerZYX>;
using RV = RigidBody<tumble::RotationVector>;

using tumble::test::rot;
using tumble::test::tumbling_mass;

SceneIntegratorOptions options(CvodeMethod method, double tol) {
  return tumble::test::integrator_options(method, tol, 200000);
}

const Vector3d kInertia = tumble::test::kTumblingInertia;
const Vector3d kOmega = tumble::test::kTumblingOmega;

}  // namespace

// ---- reset() and statistics --------------------------------------------------------------------

TEST_CASE("reset(): change the state mid-run and continue", "[integrate][scene_integrator]") {
  // Torque-free tumbling body: run to t = 2, double omega, continue to t = 5. The expectation is
  // the analytic solution started at t = 2 from the doubled state.
  const double tol = 1e-10;
  for (const CvodeMethod method : {CvodeMethod::adams, CvodeMethod::bdf}) {
    INFO((method == CvodeMethod::adams ? "Adams" : "BDF"));
    Scene<Bodies<EP>> scene;
    const Matrix3d r0 = rot(0.5, Vector3d(1, -1, 2));
    const Vector3d w0(0.7, -0.4, 1.1);
    const auto h = scene.add(EP(tumbling_mass()), {.rotation = r0, .omega = w0});
    SceneIntegrator integrator(scene, 0.0, options(method, tol));
    integrator.advance(2.0);
    SceneState y = integrator.save();
    const TorqueFreeBody first(kInertia, w0, r0);
    REQUIRE(rotation_angle_between(tumble::rotation(scene, h, y), first.rotation(2.0)) < 1e-7);
    const long steps_before = integrator.statistics().steps;
    CHECK(integrator.statistics().reinits == 0);

    const Vector3d w2 = 2.0 * tumble::omega(scene, h, y);
    const Matrix3d r2 = tumble::rotation(scene, h, y);
    tumble::set_velocity(scene, h, y, Vector3d::Zero(), w2);
    integrator.reset(2.0, y);
    CHECK(integrator.time() == 2.0);
    CHECK(integrator.state().y == y.y);
    CHECK(integrator.state().base == y.base);
    const TorqueFreeBody second(kInertia, w2, r2);
    for (int k = 1; k <= 6; ++k) {
      const double t = 2.0 + 0.5 * k;
      integrator.advance(t);
      const SceneState& yk = integrator.state();
      CHECK((tumble::omega(scene, h, yk) - second.omega(t - 2.0)).norm() < 1e-6);
      CHECK(rotation_angle_between(tumble::rotation(scene, h, yk), second.rotation(t - 2.0)) <
            1e-6);
    }
    const auto s = integrator.statistics();
    CHECK(s.reinits == 1);
    CHECK(s.steps > steps_before);  // totals across the restart
    CHECK(s.chart_switches == 0);
  }
}

TEST_CASE("reset() re-centers a chart the new state puts near its singularity",
          "[integrate][scene_integrator]") {
  Scene<Bodies<RV>> scene;
  const auto h = scene.add(RV(tumbling_mass()), {.omega = kOmega});
  SceneIntegrator integrator(scene, 0.0, options(CvodeMethod::adams, 1e-10));
  integrator.advance(0.5);
  const long switches = integrator.statistics().chart_switches;
  // A rotation vector of length 5 rad (1.28 rad from its singularity at 2 pi): inside the zone.
  SceneState y = integrator.state();
  const Vector3d v = 5.0 * Vector3d(1, 2, 2).normalized();
  const Vector3d w(1, -1, 0.5);
  y.y.segment<3>(3) = v;
  tumble::set_velocity(scene, h, y, Vector3d::Zero(), w);  // omega, in the scene's state form
  y.base[0] = Matrix3d::Identity();
  integrator.reset(0.5, y);
  CHECK(integrator.statistics().chart_switches == switches + 1);
  const SceneState y1 = integrator.state();
  CHECK(y1.y.segment<3>(3).norm() == 0.0);  // the chart's center
  CHECK(
      (tumble::rotation(scene, h, y1) - tumble::RotationVector::rotation(v)).cwiseAbs().maxCoeff() <
      1e-14);
  CHECK((tumble::omega(scene, h, y1) - w).norm() < 1e-14);
  // And it continues as the analytic solution from there.
  const TorqueFreeBody ref(kInertia, w, tumble::RotationVector::rotation(v));
  integrator.advance(3.0);
  const SceneState& y2 = integrator.state();
  CHECK(rotation_angle_between(tumble::rotation(scene, h, y2), ref.rotation(2.5)) < 1e-6);
}

TEST_CASE("statistics count chart switches since construction", "[integrate][scene_integrator]") {
  Scene<Bodies<ZYX, EP>> scene;
  const auto z = scene.add(ZYX(tumbling_mass()), {.omega = Vector3d(0.3, 2.0, 0.1)});
  scene.add(EP(tumbling_mass()), {.omega = Vector3d(1, 1, 1)});
  SceneIntegrator first(scene, 0.0, options(CvodeMethod::adams, 1e-8));
  first.advance(5.0);
  const long n1 = first.statistics().chart_switches;
  CHECK(n1 > 0);
  CHECK(n1 == first.chart_switches(z));  // the Euler-parameter body has no chart to leave
  CHECK(first.statistics().reinits == n1);
  // A second integrator of the same scene counts from its own start, and repeats the first run.
  SceneIntegrator second(scene, 0.0, options(CvodeMethod::adams, 1e-8));
  CHECK(second.statistics().chart_switches == 0);
  second.advance(5.0);
  CHECK(second.statistics().chart_switches == n1);
  CHECK(first.statistics().chart_switches == n1);  // the first one's count is its own
}

// ---- allocations -------------------------------------------------------------------------------

TEST_CASE("advance() allocates nothing once set up", "[integrate][scene_integrator]") {
  using Loaded =
      Scene<Bodies<EPOff, ZYX, RV>,
            Loads<tumble::UniformGravity, tumble::SpringDamper, tumble::SpringDamperBetween>>;
  for (const CvodeMethod method : {CvodeMethod::adams, CvodeMethod::bdf}) {
    INFO((method == CvodeMethod::adams ? "Adams" : "BDF"));
    Loaded scene;
    const auto a = scene.add(EPOff(MassProperties<double>::about_centroid(
                                 1.0, kInertia.asDiagonal(), Vector3d(0.2, -0.1, 0.3))),
                             {.position = Vector3d(0, 0, 3), .omega = Vector3d(1, 2, 3)});
    const auto b = scene.add(ZYX(tumbling_mass()),
                             {.position = Vector3d(1, 0, 3), .omega = Vector3d(0.5, 3, 1)});
    const auto c = scene.add(RV(tumbling_mass()),
                             {.position = Vector3d(-1, 0, 3), .omega = Vector3d(0, 0, 5)});
    const tumble::UniformGravity gravity(Vector3d(0, 0, -9.81));
    scene.add_load(a, gravity);
    scene.add_load(b, gravity);
    scene.add_load(c, gravity);
    scene.add_load(b, tumble::SpringDamper(Vector3d(0.1, 0, 0), Vector3d(1, 0, 4),
                                           {.stiffness = 100, .damping = 1, .rest_length = 0.5}));
    scene.add_load(a, c,
                   tumble::SpringDamperBetween(Vector3d::Zero(), Vector3d::Zero(),
                                               {.stiffness = 50, .damping = 0.5}));
    // A floor for body a's reference point: an event whose action changes the state.
    const int za = scene.offset(a) + 2;
    int bounces = 0;
    scene.add_event({.function = [za](double, const tumble::SceneStateView& y) { return y.y[za]; },
                     .direction = -1,
                     .action =
                         [&](double, SceneState& y) {
                           ++bounces;
                           y.y[za + 7] = -y.y[za + 7];
                         }});
    SceneIntegrator integrator(scene, 0.0, options(method, 1e-8));
    integrator.advance(0.01);  // CVODE finishes its own setup in the first call
    tumble::test::AllocationCounter counter;
    integrator.advance(4.0);
    const long n = counter.stop();
    CHECK(n == 0);
    const auto s = integrator.statistics();
    CHECK(s.chart_switches > 0);
    CHECK(bounces > 0);
    CHECK(s.reinits == s.chart_switches + bounces);
    if (method == CvodeMethod::bdf) {
      CHECK(s.projections > 0);
    }
  }
}

TEST_CASE("one scene, read by integrators in two threads at once",
          "[integrate][scene_integrator]") {
  // The scene is only read during a run: two threads integrating it at the same time (each with
  // its own integrator) reproduce the serial run bit for bit.
  Scene<Bodies<ZYX, EP>, Loads<tumble::UniformGravity, tumble::SpringDamperBetween>> scene;
  const auto z = scene.add(ZYX(tumbling_mass()), {.omega = Vector3d(0.3, 2.0, 0.1)});
  const auto e = scene.add(EP(tumbling_mass()), {.position = Vector3d(1, 0, 0), .omega = kOmega});
  scene.add_load(z, tumble::UniformGravity(Vector3d(0, 0, -9.81)));
  scene.add_load(e, tumble::UniformGravity(Vector3d(0, 0, -9.81)));
  scene.add_load(z, e,
                 tumble::SpringDamperBetween(Vector3d::Zero(), Vector3d(0.1, 0, 0),
                                             {.stiffness = 20, .damping = 0.1, .rest_length = 1}));
  const auto run = [&scene](CvodeMethod method) {
    SceneIntegrator integrator(scene, 0.0, options(method, 1e-9));
    integrator.advance(5.0);
    return integrator.save();
  };
  const SceneState adams = run(CvodeMethod::adams), bdf = run(CvodeMethod::bdf);
  SceneState adams_thread, bdf_thread;
  std::thread a([&] { adams_thread = run(CvodeMethod::adams); });
  std::thread b([&] { bdf_thread = run(CvodeMethod::bdf); });
  a.join();
  b.join();
  CHECK(adams_thread.y == adams.y);
  CHECK(adams_thread.base == adams.base);
  CHECK(bdf_thread.y == bdf.y);
  CHECK(bdf_thread.base == bdf.base);
  CHECK((adams.y - bdf.y).cwiseAbs().maxCoeff() < 1e-5);  // and the two methods agree
}
