// Tests of tumble::SceneIntegrator (include/tumble/integrate/scene_integrator.hpp) with user code
// in the loop: user events with actions (a spinning ball bouncing on the ground, against its
// closed form), an event function that throws, and a user force that returns NaN, each reported
// as an IntegrationError that names its cause. The integrator's setup, reset(), statistics,
// threads and allocations: scene_integrator.test.cpp.

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

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

const Vector3d kOmega = tumble::test::kTumblingOmega;

}  // namespace

// ---- events ------------------------------------------------------------------------------------

TEST_CASE("a user event: a spinning ball bouncing on the ground", "[integrate][scene_integrator]") {
  // A ball of radius 0.5 m dropped from z = 10 m bounces with restitution e = 0.8: the event
  // z - r = 0 (falling) reverses and scales vz. Closed form: the first impact at
  // t1 = sqrt(2 (z0 - r) / g) with speed v1 = g t1, then t_{k+1} = t_k + 2 e^k v1 / g. The ball
  // spins at 6 rad/s, so its rotation-vector chart is re-centered on the way too.
  const double g = 9.81, r = 0.5, z0 = 10.0, e = 0.8;
  for (const CvodeMethod method : {CvodeMethod::adams, CvodeMethod::bdf}) {
    INFO((method == CvodeMethod::adams ? "Adams" : "BDF"));
    Scene<Bodies<RV>, Loads<tumble::UniformGravity>> scene;
    const auto ball = scene.add(
        RV(MassProperties<double>::about_centroid(1.0, Vector3d::Constant(0.1).asDiagonal())),
        {.position = Vector3d(0, 0, z0),
         .velocity = Vector3d(1, 0, 0),
         .omega = Vector3d(0, 0, 6)});
    scene.add_load(ball, tumble::UniformGravity(Vector3d(0, 0, -g)));
    std::vector<double> bounces;
    bounces.reserve(16);
    const int z_index = scene.offset(ball) + 2;
    scene.add_event(
        {.function = [&](double, const tumble::SceneStateView& y) { return y.y[z_index] - r; },
         .direction = -1,
         .action =
             [&](double t, SceneState& y) {
               bounces.push_back(t);
               Vector3d v = tumble::velocity(scene, ball, y);
               v.z() = -e * v.z();
               tumble::set_velocity(scene, ball, y, v, tumble::omega(scene, ball, y));
             }});
    SceneIntegrator integrator(scene, 0.0, options(method, 1e-10));
    integrator.advance(7.5);
    const SceneState& y = integrator.state();

    const double t1 = std::sqrt(2 * (z0 - r) / g), v1 = g * t1;
    std::vector<double> expected{t1};
    for (int k = 1; expected.back() + 2 * std::pow(e, k) * v1 / g < 7.5; ++k) {
      expected.push_back(expected.back() + 2 * std::pow(e, k) * v1 / g);
    }
    REQUIRE(expected.size() == 4);
    REQUIRE(bounces.size() == expected.size());
    for (std::size_t k = 0; k < expected.size(); ++k) {
      CHECK(std::abs(bounces[k] - expected[k]) < 1e-8);
    }
    // Between the bounces: the ball's height on its last arc, its horizontal motion and its spin.
    const double tk = expected.back(), vk = std::pow(e, 4) * v1;
    const double z = r + vk * (7.5 - tk) - 0.5 * g * (7.5 - tk) * (7.5 - tk);
    CHECK(std::abs(tumble::position(scene, ball, y).z() - z) < 1e-7);
    CHECK(std::abs(tumble::position(scene, ball, y).x() - 7.5) < 1e-8);
    CHECK((tumble::omega(scene, ball, y) - Vector3d(0, 0, 6)).norm() < 1e-8);
    const Matrix3d spin = rot(6 * 7.5, Vector3d::UnitZ());
    CHECK(rotation_angle_between(tumble::rotation(scene, ball, y), spin) < 1e-7);

    const auto s = integrator.statistics();
    CHECK(s.chart_switches > 0);
    CHECK(s.roots_found == s.chart_switches + 4);
    CHECK(s.reinits == s.chart_switches + 4);  // each event and each switch restarts CVODE
  }
}

TEST_CASE("an event function that throws stops the integration with its message",
          "[integrate][scene_integrator]") {
  Scene<Bodies<EP>> scene;
  scene.add(EP(tumbling_mass()), {.omega = kOmega});
  scene.add_event({.function = [](double t, const tumble::SceneStateView& y) -> double {
                     if (t > 0.5) {
                       throw std::runtime_error("the wall sensor failed");
                     }
                     return y.y[0] + 1.0;
                   },
                   .direction = 0,
                   .action = {}});
  SceneIntegrator integrator(scene, 0.0, options(CvodeMethod::adams, 1e-8));
  try {
    integrator.advance(2.0);
    FAIL("advance() should have thrown");
  } catch (const CvodeError& e) {
    CHECK(e.flag_name() == "CV_RTFUNC_FAIL");
    CHECK_THAT(e.what(), TUMBLE_CONTAINS("the wall sensor failed"));
    CHECK_THAT(e.what(), TUMBLE_CONTAINS("roots()"));
    REQUIRE(e.cause());
    try {
      std::rethrow_exception(e.cause());
    } catch (const std::runtime_error& cause) {
      CHECK(std::string(cause.what()) == "the wall sensor failed");
    }
    CHECK(e.time() <= 2.0);
  }
}

namespace {

/// A user force that returns NaN once `*broken` is set, or after the time `after`.
struct FailingForce {
  const bool* broken = nullptr;
  double after = std::numeric_limits<double>::infinity();
  template <class S, ReferencePoint Ref>
  tumble::Wrench<S> operator()(const S& t, const tumble::BodyKinematics<S, Ref>& k) const {
    tumble::Wrench<S> w;
    w.force = -k.velocity;
    if (*broken || t > S(after)) {
      w.force.x() = std::numeric_limits<double>::quiet_NaN();
    }
    return w;
  }
};
using Failing = tumble::UserForce<FailingForce, false>;

}  // namespace

TEST_CASE("a user force returning NaN: an IntegrationError that names the cause",
          "[integrate][scene_integrator]") {
  // The scene throws NonFiniteError, which CVODE treats as a recoverable failure: it retries
  // with smaller steps, and gives up when the force stays NaN.
  for (const CvodeMethod method : {CvodeMethod::adams, CvodeMethod::bdf}) {
    INFO((method == CvodeMethod::adams ? "Adams" : "BDF"));
    SECTION("NaN at every state: CVODE cannot take a step") {
      bool broken = false;
      Scene<Bodies<EP>, Loads<Failing>> scene;
      const auto h =
          scene.add(EP(tumbling_mass()), {.velocity = Vector3d(1, 0, 0), .omega = kOmega});
      scene.add_load(h, Failing(FailingForce{&broken}));
      SceneIntegrator integrator(scene, 0.0, options(method, 1e-8));
      integrator.advance(0.5);  // fine so far
      broken = true;
      try {
        integrator.advance(3.0);
        FAIL("advance() should have thrown");
      } catch (const CvodeError& e) {
        INFO(e.what());
        CHECK(e.flag() < 0);
        CHECK_THAT(e.what(), TUMBLE_CONTAINS("the user force returned a non-finite wrench"));
        CHECK_THAT(e.what(), TUMBLE_CONTAINS("rhs()"));
        // Not a step further than CVODE's last internal step before the output time 0.5
        // (measured: 0.525).
        CHECK(e.time() >= 0.5);
        CHECK(e.time() < 0.6);
      }
    }
    SECTION("NaN after t = 1: CVODE creeps up to t = 1 until it runs out of steps") {
      bool broken = false;
      Scene<Bodies<EP>, Loads<Failing>> scene;
      const auto h =
          scene.add(EP(tumbling_mass()), {.velocity = Vector3d(1, 0, 0), .omega = kOmega});
      scene.add_load(h, Failing(FailingForce{&broken, 1.0}));
      SceneIntegratorOptions o = options(method, 1e-8);
      o.max_steps = 2000;
      SceneIntegrator integrator(scene, 0.0, o);
      try {
        integrator.advance(3.0);
        FAIL("advance() should have thrown");
      } catch (const CvodeError& e) {
        INFO(e.what());
        CHECK(e.flag() < 0);
        CHECK_THAT(e.what(), TUMBLE_CONTAINS("the user force returned a non-finite wrench"));
        CHECK(e.time() <= 1.0);
        CHECK(e.time() > 0.99);
      }
    }
  }
}
