// Bad input to scenes and their integration: every case throws with a message that
// says what is wrong and where, and CVODE's failures (too much work, too much accuracy, repeated
// error-test failures, a failing callback) arrive as an IntegrationError naming the flag, the
// time and the cause, never as a crash, a hang or a silent NaN.

#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "support/catch.hpp"
#include "tumble/body/rigid_body.hpp"
#include "tumble/force/coupling.hpp"
#include "tumble/force/user_force.hpp"
#include "tumble/integrate/scene_integrator.hpp"
#include "tumble/orientation/euler_angles.hpp"
#include "tumble/scene/observables.hpp"
#include "tumble/scene/scene.hpp"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using Eigen::VectorXd;
using tumble::Bodies;
using tumble::CvodeError;
using tumble::CvodeMethod;
using tumble::IntegrationError;
using tumble::Loads;
using tumble::MassProperties;
using tumble::RigidBody;
using tumble::Scene;
using tumble::SceneIntegrator;
using tumble::SceneIntegratorOptions;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

template <class E> std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  } catch (const std::exception& e) {
    FAIL_CHECK("threw the wrong exception type: " << e.what());
    return "";
  }
  FAIL_CHECK("did not throw");
  return "";
}
bool has(const std::string& message, const std::string& part) {
  return message.find(part) != std::string::npos;
}

using Ep = RigidBody<tumble::EulerParameters>;
using Zyx = RigidBody<tumble::EulerZYX>;
const auto kMass = MassProperties<>::about_centroid(1.0, Vector3d(1.0, 2.0, 2.5).asDiagonal());

/// A user force (a function of t) on the bodies of a test scene.
using ForceOfTime = std::function<Vector3d(double)>;
struct TimeForce {
  ForceOfTime f;
  template <class K> tumble::Wrench<double> operator()(double t, const K&) const {
    tumble::Wrench<double> w;
    w.force = f(t);
    return w;
  }
};
using UserF = tumble::UserForce<TimeForce, false>;
using TestScene = Scene<Bodies<Ep, Zyx>, Loads<UserF, tumble::SpringDamperBetween>>;

SceneIntegratorOptions opts(CvodeMethod m = CvodeMethod::bdf) {
  SceneIntegratorOptions o;
  o.method = m;
  return o;
}

}  // namespace

// ---- building a scene ---------------------------------------------------------------------------

TEST_CASE("bad input: a body's initial state with a non-finite entry", "[integrate][bad_input]") {
  TestScene scene;
  // The message names the body, the field and its value (docs/conventions.md).
  const char* expected[] = {"body 0: the initial position is not finite: (0, nan, 0)",
                            ("body 0: the initial rotation (row by row) is not finite: "
                             "(1, 0, 0, 0, 1, 0, 0, 0, inf)"),
                            "body 0: the initial velocity is not finite: (-inf, 0, 0)",
                            "body 0: the initial omega is not finite: (0, 0, nan)"};
  for (int field = 0; field < 4; ++field) {
    tumble::InitialState s;
    switch (field) {
      case 0:
        s.position(1) = kNaN;
        break;
      case 1:
        s.rotation(2, 2) = kInf;
        break;
      case 2:
        s.velocity(0) = -kInf;
        break;
      default:
        s.omega(2) = kNaN;
        break;
    }
    INFO("field " << field);
    CHECK(has(message_of<std::invalid_argument>([&] { (void)scene.add(Ep(kMass), s); }),
              std::string("tumble::Scene::add: ") + expected[field]));
  }
  CHECK(scene.body_count() == 0);
}

TEST_CASE("bad input: an initial rotation that is not a rotation", "[integrate][bad_input]") {
  TestScene scene;
  const Matrix3d zero = Matrix3d::Zero();
  const Matrix3d scaled = 2.0 * Matrix3d::Identity();
  const Matrix3d reflection = Vector3d(1, 1, -1).asDiagonal();
  Matrix3d sheared = Matrix3d::Identity();
  sheared(0, 1) = 1e-6;
  for (const Matrix3d& r : {zero, scaled, reflection, sheared}) {
    INFO("R =\n" << r);
    const std::string msg =
        message_of<std::invalid_argument>([&] { (void)scene.add(Ep(kMass), {.rotation = r}); });
    CHECK(has(msg, "the initial rotation is not a proper rotation matrix"));
  }
}

TEST_CASE("bad input: a scene with no bodies", "[integrate][bad_input]") {
  TestScene scene;
  CHECK(has(message_of<std::invalid_argument>([&] { SceneIntegrator integrator(scene, 0.0); }),
            "the scene has no bodies"));
}

TEST_CASE("bad input: a body handle that is not of this scene", "[integrate][bad_input]") {
  TestScene a, b;
  (void)a.add(Zyx(kMass));
  const auto in_a = a.add(Ep(kMass));  // global id 1, local 0
  (void)b.add(Ep(kMass));              // global id 0, local 0
  const UserF force(TimeForce{[](double) { return Vector3d::Zero(); }});
  CHECK(has(message_of<std::invalid_argument>([&] { b.add_load(in_a, force); }),
            "the body handle 1 does not refer to a body of this scene"));
  const tumble::BodyId<Ep> forged{7, 3};
  CHECK(has(message_of<std::invalid_argument>([&] { (void)b.offset(forged); }),
            "the body handle 7 does not refer to a body of this scene"));
  CHECK(has(message_of<std::invalid_argument>([&] {
              (void)tumble::rotation(b, tumble::BodyId<Zyx>{0, 0}, b.initial_state());
            }),
            "does not refer to a body of this scene"));
}

TEST_CASE("bad input: a coupling from a body to itself, an event without a function",
          "[integrate][bad_input]") {
  TestScene scene;
  const auto id = scene.add(Ep(kMass));
  CHECK(has(message_of<std::invalid_argument>([&] {
              scene.add_load(id, id,
                             tumble::SpringDamperBetween(Vector3d::Zero(), Vector3d::Zero(),
                                                         {.stiffness = 1.0}));
            }),
            "a coupling needs two different bodies"));
  CHECK(has(message_of<std::invalid_argument>([&] { scene.add_event(tumble::Event{}); }),
            "the event has no root function"));
}

// ---- options and times --------------------------------------------------------------------------

TEST_CASE("bad input: tolerances that are not positive and finite", "[integrate][bad_input]") {
  TestScene scene;
  (void)scene.add(Ep(kMass), {.omega = {0, 1, 0}});
  for (const double rtol : {0.0, -1e-6, kNaN, kInf}) {
    auto o = opts();
    o.rtol = rtol;
    INFO("rtol " << rtol);
    CHECK(has(message_of<std::invalid_argument>([&] { SceneIntegrator i(scene, 0.0, o); }),
              "'rtol' must be finite and > 0"));
  }
  for (const double atol : {0.0, -1.0, kNaN}) {
    auto o = opts();
    o.atol = atol;
    INFO("atol " << atol);
    CHECK(has(message_of<std::invalid_argument>([&] { SceneIntegrator i(scene, 0.0, o); }),
              "'atol' must be finite and > 0"));
  }
  auto o = opts();
  VectorXd atol = VectorXd::Constant(scene.size(), 1e-8);
  atol(4) = 0.0;
  o.atol = atol;
  CHECK(has(message_of<std::invalid_argument>([&] { SceneIntegrator i(scene, 0.0, o); }),
            "'atol' entry 4 must be finite and > 0"));
  o.atol = VectorXd::Constant(3, 1e-8);
  CHECK(has(message_of<std::invalid_argument>([&] { SceneIntegrator i(scene, 0.0, o); }),
            "'atol' per entry must have the state's size 13 (got 3)"));
}

TEST_CASE("bad input: other options out of range", "[integrate][bad_input]") {
  TestScene scene;
  (void)scene.add(Ep(kMass), {.omega = {0, 1, 0}});
  auto o = opts(CvodeMethod::bdf);
  o.cvode.max_order = 6;
  CHECK(has(message_of<std::invalid_argument>([&] { SceneIntegrator i(scene, 0.0, o); }),
            "'max_order' must be in [1, 5] for BDF"));
  o = opts();
  o.max_steps = -1;
  CHECK(has(message_of<std::invalid_argument>([&] { SceneIntegrator i(scene, 0.0, o); }),
            "'max_steps' must be >= 0, 0 for no limit (got -1)"));
  o = opts();
  o.cvode.stop_time = -1.0;
  CHECK(has(message_of<std::invalid_argument>([&] { SceneIntegrator i(scene, 0.0, o); }),
            "'stop_time' must be finite and after the initial time"));
  CHECK(has(message_of<std::invalid_argument>([&] { SceneIntegrator i(scene, kNaN); }),
            "the initial time must be finite"));
}

TEST_CASE("bad input: initial states of the wrong size or non-finite", "[integrate][bad_input]") {
  TestScene scene;
  (void)scene.add(Ep(kMass), {.omega = {0, 1, 0}});
  CHECK(has(message_of<std::invalid_argument>([&] {
              SceneIntegrator i(scene, 0.0, tumble::SceneState{VectorXd::Zero(5), {}});
            }),
            "the state has 5 entries and 0 chart bases, but the scene has size 13 and 1 bodies"));
  tumble::SceneState y = scene.initial_state();
  y.y(9) = kNaN;
  CHECK(has(message_of<std::invalid_argument>([&] { SceneIntegrator i(scene, 0.0, y); }),
            "the initial state has a non-finite component"));
  SceneIntegrator integrator(scene, 0.0);
  CHECK(has(message_of<std::invalid_argument>([&] { integrator.reset(0.0, y); }),
            "tumble::Cvode::reset: the state has a non-finite component"));
}

TEST_CASE("bad input: output times behind the current time or not finite",
          "[integrate][bad_input]") {
  TestScene scene;
  (void)scene.add(Ep(kMass), {.omega = {0, 1, 0}});
  SceneIntegrator integrator(scene, 0.0);
  (void)integrator.advance(1.0);
  CHECK(has(message_of<std::invalid_argument>([&] { (void)integrator.advance(0.5); }),
            "tumble::Cvode::advance: the time 0.5 is behind the current time 1"));
  CHECK(has(message_of<std::invalid_argument>([&] { (void)integrator.advance(kNaN); }),
            "is not finite"));
  const std::vector<double> times{2.0, 3.0, 2.5};
  CHECK(has(message_of<std::invalid_argument>(
                [&] { integrator.integrate(times, [](double, const tumble::SceneState&) {}); }),
            "output times must be finite, non-decreasing"));
  // Nothing was integrated by the rejected calls.
  CHECK(integrator.time() == 1.0);
}

// ---- failures during integration ----------------------------------------------------------------

TEST_CASE("bad input: a user force that returns NaN during integration", "[integrate][bad_input]") {
  TestScene scene;
  const auto id = scene.add(Ep(kMass), {.omega = {0, 1, 0}});
  scene.add_load(id, UserF(TimeForce{[](double t) {
                   return t > 0.5 ? Vector3d(kNaN, 0, 0) : Vector3d(1, 0, 0);
                 }}));
  SceneIntegrator integrator(scene, 0.0);
  try {
    (void)integrator.advance(2.0);
    FAIL("integrated through a NaN force");
  } catch (const CvodeError& e) {
    const std::string msg = e.what();
    CHECK(has(msg, "UserForce: the user force returned a non-finite wrench"));
    CHECK(has(msg, "rhs()"));
    CHECK(e.time() <= 0.5 + 1e-9);
    CHECK(e.time() > 0.4);
    // The state where CVODE stopped is finite.
    CHECK(integrator.state().y.allFinite());
  }
}

TEST_CASE("bad input: a user force or an event function that throws", "[integrate][bad_input]") {
  {
    TestScene scene;
    const auto id = scene.add(Ep(kMass), {.omega = {0, 1, 0}});
    scene.add_load(id, UserF(TimeForce{[](double t) -> Vector3d {
                     if (t > 0.25) throw std::runtime_error("sensor unplugged");
                     return Vector3d::Zero();
                   }}));
    SceneIntegrator integrator(scene, 0.0);
    try {
      (void)integrator.advance(1.0);
      FAIL("no error");
    } catch (const CvodeError& e) {
      CHECK(has(e.what(), "rhs() threw"));
      CHECK(has(e.what(), "sensor unplugged"));
      REQUIRE(e.cause() != nullptr);
      CHECK_THROWS_AS(std::rethrow_exception(e.cause()), std::runtime_error);
    }
  }
  {
    TestScene scene;
    (void)scene.add(Ep(kMass), {.omega = {0, 1, 0}});
    scene.add_event({[](double t, const tumble::SceneStateView&) -> double {
                       if (t > 0.3) throw std::logic_error("root function failed");
                       return 1.0;
                     },
                     0,
                     {}});
    SceneIntegrator integrator(scene, 0.0);
    try {
      (void)integrator.advance(1.0);
      FAIL("no error");
    } catch (const CvodeError& e) {
      CHECK(e.flag_name() == "CV_RTFUNC_FAIL");
      CHECK(has(e.what(), "roots() threw"));
      CHECK(has(e.what(), "root function failed"));
    }
  }
  {
    // An event action runs outside CVODE: its exception arrives unchanged.
    TestScene scene;
    (void)scene.add(Ep(kMass), {.omega = {0, 1, 0}});
    scene.add_event({[](double t, const tumble::SceneStateView&) { return t - 0.5; }, 0,
                     [](double, tumble::SceneState&) { throw std::domain_error("bad action"); }});
    SceneIntegrator integrator(scene, 0.0);
    CHECK(has(message_of<std::domain_error>([&] { (void)integrator.advance(1.0); }), "bad action"));
  }
}

TEST_CASE("bad input: CVODE failures arrive as IntegrationError with the flag and the cause",
          "[integrate][bad_input]") {
  SECTION("too much work") {
    TestScene scene;
    (void)scene.add(Zyx(kMass), {.omega = {0.3, 2, 0.1}});
    auto o = opts(CvodeMethod::adams);
    o.max_steps = 10;
    o.rtol = 1e-10;
    SceneIntegrator integrator(scene, 0.0, o);
    try {
      (void)integrator.advance(100.0);
      FAIL("no error");
    } catch (const CvodeError& e) {
      CHECK(e.flag_name() == "CV_TOO_MUCH_WORK");
      CHECK(has(e.what(), "(max_steps = 10)"));
      CHECK(e.time() > 0.0);
      CHECK(e.time() < 100.0);
    }
  }
  SECTION("too much accuracy requested") {
    TestScene scene;
    (void)scene.add(Ep(kMass), {.velocity = {1e3, 0, 0}, .omega = {0.3, 2, 0.1}});
    auto o = opts();
    o.rtol = 1e-20;
    o.atol = 1e-30;
    SceneIntegrator integrator(scene, 0.0, o);
    try {
      (void)integrator.advance(1.0);
      FAIL("no error");
    } catch (const CvodeError& e) {
      CHECK(e.flag_name() == "CV_TOO_MUCH_ACC");
      CHECK(has(e.what(), "CV_TOO_MUCH_ACC"));
    }
  }
  SECTION("repeated error-test failures") {
    // A force that jumps by 1e12 N at t = 0.3, two error-test failures allowed per step (with
    // one, an ordinary failure of the start-up steps, at t = 0.0036, ends the run first).
    TestScene scene;
    const auto id = scene.add(Ep(kMass), {.omega = {0, 1, 0}});
    scene.add_load(id, UserF(TimeForce{[](double t) {
                     return t > 0.3 ? Vector3d(1e12, 0, 0) : Vector3d::Zero();
                   }}));
    auto o = opts();
    o.cvode.max_error_test_failures = 2;
    SceneIntegrator integrator(scene, 0.0, o);
    try {
      (void)integrator.advance(1.0);
      FAIL("no error");
    } catch (const CvodeError& e) {
      CHECK(e.flag_name() == "CV_ERR_FAILURE");
      CHECK(has(e.what(), "the local error test failed max_error_test_failures times"));
      INFO(e.what());
      CHECK(std::abs(e.time() - 0.3) < 0.05);
    }
  }
}
