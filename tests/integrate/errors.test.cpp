// The errors of include/tumble/integrate/errors.hpp, alike for every integrator (the front
// door's promise that the two integrators speak alike): one test per case, run for CVODE's
// SceneIntegrator (BDF and Adams), the explicit OdeintIntegrator (Fehlberg 7(8), and
// Dormand-Prince, whose integrate() reads the outputs off its dense output) and the front door
// (AutoIntegrator), each asserting the same:
//  - a user load that throws at t > 0.25: IntegrationError with reason() callback, time() near
//    0.25 (the time reached), what() "rhs() threw at t = ..." with the load's message, cause()
//    the load's own exception; in advance() and in integrate();
//  - a user load that throws from the start: the same error, at t0 (the explicit integrator meets
//    it when it is made, CVODE in its first step);
//  - an event function that throws: the same, "roots() threw";
//  - the user's observer and an event's action that throw: their own exception, unchanged (they
//    are called between steps, not from inside one);
//  - output times: the same refused (std::invalid_argument, nothing integrated), a repeated
//    time the same state twice.

#include "tumble/integrate/errors.hpp"

#include <cmath>
#include <exception>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "support/catch.hpp"
#include "tumble/body/rigid_body.hpp"
#include "tumble/force/user_force.hpp"
#include "tumble/integrate/auto_integrator.hpp"
#include "tumble/integrate/explicit_integrator.hpp"
#include "tumble/integrate/scene_integrator.hpp"
#include "tumble/orientation/euler_parameters.hpp"
#include "tumble/scene/scene.hpp"

namespace {

using Eigen::Vector3d;
using tumble::IntegrationError;
using tumble::IntegrationFailure;
using tumble::SceneState;

/// A user force of time alone.
struct TimeForce {
  std::function<Vector3d(double)> f;
  template <class K> tumble::Wrench<double> operator()(double t, const K&) const {
    tumble::Wrench<double> w;
    w.force = f(t);
    return w;
  }
};
using UserF = tumble::UserForce<TimeForce, false>;
using Ep = tumble::RigidBody<tumble::EulerParameters>;
using TestScene = tumble::Scene<tumble::Bodies<Ep>, tumble::Loads<UserF>>;

const auto kMass =
    tumble::MassProperties<>::about_centroid(1.0, Vector3d(1.0, 2.0, 3.0).asDiagonal());

/// A tumbling body with a user force that throws std::runtime_error("sensor unplugged") for
/// t > after (after < 0: always).
TestScene scene_with_failing_load(double after) {
  TestScene scene;
  const auto id = scene.add(Ep(kMass), {.omega = {0.1, 2.0, 0.05}});
  scene.add_load(id, UserF(TimeForce{[after](double t) -> Vector3d {
                   if (t > after) {
                     throw std::runtime_error("sensor unplugged");
                   }
                   return Vector3d::Zero();
                 }}));
  return scene;
}

// The integrators under test, one type each: make(scene) at t0 = 0.
struct CvodeBdf {
  static constexpr const char* name = "CVODE BDF";
  static auto make(const TestScene& s) { return tumble::SceneIntegrator(s, 0.0); }
};
struct CvodeAdams {
  static constexpr const char* name = "CVODE Adams";
  static auto make(const TestScene& s) {
    tumble::SceneIntegratorOptions o;
    o.method = tumble::CvodeMethod::adams;
    return tumble::SceneIntegrator(s, 0.0, o);
  }
};
struct Fehlberg {
  static constexpr const char* name = "Odeint Fehlberg 7(8)";
  static auto make(const TestScene& s) { return tumble::OdeintIntegrator(s, 0.0); }
};
struct Dopri {
  static constexpr const char* name = "Odeint Dormand-Prince (dense outputs)";
  static auto make(const TestScene& s) {
    tumble::OdeintOptions o;
    o.method = tumble::OdeintMethod::dopri5;
    o.interpolate_outputs = true;
    return tumble::OdeintIntegrator(s, 0.0, o);
  }
};
struct Auto {
  static constexpr const char* name = "front door";
  static auto make(const TestScene& s) { return tumble::AutoIntegrator(s, 0.0); }
};

/// The exception f() throws, as an exception_ptr (null if none).
std::exception_ptr thrown_by(const std::function<void()>& f) {
  try {
    f();
  } catch (...) {
    return std::current_exception();
  }
  return nullptr;
}

/// e is an IntegrationError of reason callback at a time in [t_min, t_max], whose what() names
/// `where` and the cause's message, and whose cause is a std::exception E with that message.
template <class E>
void check_callback_error(const std::exception_ptr& e, const std::string& where,
                          const std::string& message, double t_min, double t_max) {
  REQUIRE(e);
  try {
    std::rethrow_exception(e);
  } catch (const IntegrationError& x) {
    INFO(x.what());
    CHECK(x.reason() == IntegrationFailure::callback);
    CHECK(x.time() >= t_min);
    CHECK(x.time() <= t_max);
    CHECK_THAT(x.what(), TUMBLE_CONTAINS(where + " threw at t = "));
    CHECK_THAT(x.what(), TUMBLE_CONTAINS(": " + message));
    REQUIRE(x.cause());
    try {
      std::rethrow_exception(x.cause());
    } catch (const E& cause) {
      CHECK(std::string(cause.what()) == message);
    } catch (...) {
      FAIL("the cause has the wrong type");
    }
  } catch (const std::exception& x) {
    FAIL("not an IntegrationError: " << x.what());
  }
}

struct ObserverError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace

TEMPLATE_TEST_CASE("errors: a load that throws stops every integrator alike", "[integrate][errors]",
                   CvodeBdf, CvodeAdams, Fehlberg, Dopri, Auto) {
  INFO(TestType::name);
  const TestScene scene = scene_with_failing_load(0.25);
  SECTION("advance") {
    auto integrator = TestType::make(scene);
    const auto e = thrown_by([&] { integrator.advance(1.0); });
    check_callback_error<std::runtime_error>(e, "rhs()", "sensor unplugged", 0.0, 0.25);
    // The time reached: before the failure, within a step of it (Fehlberg 7(8) steps about 0.16
    // here, CVODE stops at about 0.23).
    CHECK(integrator.time() > 0.0);
    CHECK(integrator.time() <= 0.25);
    CHECK(integrator.time() == Approx(0.25).margin(0.2));
  }
  SECTION("integrate, outputs on both sides of the failure") {
    auto integrator = TestType::make(scene);
    std::vector<double> seen;
    const auto e = thrown_by([&] {
      integrator.integrate(std::vector<double>{0.1, 0.2, 0.3, 0.4},
                           [&](double t, const SceneState&) { seen.push_back(t); });
    });
    check_callback_error<std::runtime_error>(e, "rhs()", "sensor unplugged", 0.0, 0.25);
    CHECK(seen == std::vector<double>{0.1, 0.2});
  }
  SECTION("from the start") {
    const TestScene always = scene_with_failing_load(-1.0);
    const auto e = thrown_by([&] {
      auto integrator = TestType::make(always);
      integrator.advance(1.0);
    });
    check_callback_error<std::runtime_error>(e, "rhs()", "sensor unplugged", 0.0, 0.0);
  }
}

TEMPLATE_TEST_CASE("errors: an event function that throws stops every integrator alike",
                   "[integrate][errors]", CvodeBdf, CvodeAdams, Fehlberg, Dopri, Auto) {
  INFO(TestType::name);
  TestScene scene = scene_with_failing_load(1e9);
  scene.add_event({[](double t, const tumble::SceneStateView&) -> double {
                     if (t > 0.3) {
                       throw std::logic_error("root function failed");
                     }
                     return 1.0;
                   },
                   0,
                   {}});
  auto integrator = TestType::make(scene);
  const auto e = thrown_by([&] { integrator.advance(1.0); });
  // time(): the time reached, the step that ended past 0.3 (CVODE: where it had stepped to when
  // the root check failed; the explicit integrator: that step's start, the last accepted state).
  check_callback_error<std::logic_error>(e, "roots()", "root function failed", 0.1, 1.0);
  CHECK(integrator.time() > 0.1);
  CHECK(integrator.time() <= 1.0);
  CHECK(integrator.state().y.allFinite());
}

TEMPLATE_TEST_CASE("errors: the observer's and an event action's own exceptions arrive unchanged",
                   "[integrate][errors]", CvodeBdf, CvodeAdams, Fehlberg, Dopri, Auto) {
  INFO(TestType::name);
  SECTION("observer") {
    const TestScene scene = scene_with_failing_load(1e9);
    auto integrator = TestType::make(scene);
    CHECK_THROWS_AS(integrator.integrate(std::vector<double>{0.1, 0.2, 0.3},
                                         [](double t, const SceneState&) {
                                           if (t > 0.15) {
                                             throw ObserverError("observer gave up");
                                           }
                                         }),
                    ObserverError);
  }
  SECTION("event action") {
    TestScene scene = scene_with_failing_load(1e9);
    scene.add_event({[](double t, const tumble::SceneStateView&) { return t - 0.5; }, 0,
                     [](double, SceneState&) { throw std::domain_error("bad action"); }});
    auto integrator = TestType::make(scene);
    CHECK_THROWS_AS(integrator.advance(1.0), std::domain_error);
  }
}

TEST_CASE("errors: the front door does not take a load's exception for stiffness",
          "[integrate][errors]") {
  const TestScene scene = scene_with_failing_load(0.25);
  tumble::AutoIntegrator integrator(scene, 0.0);
  REQUIRE(integrator.method() == tumble::AutoMethod::fehlberg78);
  const auto e = thrown_by([&] { integrator.advance(1.0); });
  check_callback_error<std::runtime_error>(e, "rhs()", "sensor unplugged", 0.0, 0.25);
  CHECK(integrator.method() == tumble::AutoMethod::fehlberg78);  // no hand-over to BDF
  // And tumble::integrate, the one call.
  const auto f = thrown_by([&] {
    (void)tumble::integrate(scene, 0.0, {0.5, 1.0}, [](double, const SceneState&) {});
  });
  check_callback_error<std::runtime_error>(f, "rhs()", "sensor unplugged", 0.0, 0.25);
}

TEMPLATE_TEST_CASE("errors: every integrator takes and refuses the same output times",
                   "[integrate][errors]", CvodeBdf, CvodeAdams, Fehlberg, Dopri, Auto) {
  INFO(TestType::name);
  const TestScene scene = scene_with_failing_load(1e9);  // never throws
  auto integrator = TestType::make(scene);
  // Refused before anything is integrated: backwards, not finite, before the current time.
  const auto refuses = [&](const std::vector<double>& times) {
    int calls = 0;
    std::string what;
    try {
      integrator.integrate(times, [&](double, const SceneState&) { ++calls; });
    } catch (const std::invalid_argument& e) {
      what = e.what();
    }
    CHECK(what.find("the output times must be finite, non-decreasing") != std::string::npos);
    CHECK(calls == 0);
    CHECK(integrator.time() == 0.0);
  };
  refuses({0.5, 1.0, 0.75});
  refuses({0.5, std::nan("")});
  refuses({-0.5, 1.0});
  // A time repeated (the start time too) gives the same state again.
  std::vector<double> seen;
  std::vector<Eigen::VectorXd> states;
  integrator.integrate(std::vector<double>{0.0, 0.0, 0.5, 0.5, 1.0},
                       [&](double t, const SceneState& s) {
                         seen.push_back(t);
                         states.push_back(s.y);
                       });
  CHECK(seen == std::vector<double>{0.0, 0.0, 0.5, 0.5, 1.0});
  REQUIRE(states.size() == 5);
  CHECK(states[0] == states[1]);
  CHECK(states[2] == states[3]);
  CHECK(states[3] != states[4]);
}
