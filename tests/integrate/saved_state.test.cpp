// Saved states of a scene (include/tumble/scene/state.hpp, integrate/scene_integrator.hpp): a
// SceneState carries the continuous vector and every body's chart base, so a state saved at one
// time restarts, and reads back, the attitude it was saved at, whatever charts were switched
// since; a copy of the scene reads and integrates it alike. For every parameterization (compiled
// in slices of the list: tests/CMakeLists.txt).

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "support/catch.hpp"
#include "support/parameterizations.hpp"
#include "support/random.hpp"
#include "support/rotation.hpp"
#include "support/scene_fixtures.hpp"
#include "support/torque_free.hpp"
#include "tumble/body/rigid_body.hpp"
#include "tumble/integrate/scene_integrator.hpp"
#include "tumble/scene/chart.hpp"
#include "tumble/scene/observables.hpp"
#include "tumble/scene/scene.hpp"
#include "tumble/scene/state.hpp"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using tumble::Bodies;
using tumble::CvodeMethod;
using tumble::RigidBody;
using tumble::Scene;
using tumble::SceneIntegrator;
using tumble::SceneState;
using tumble::test::rot;
using tumble::test::rotation_angle_between;
using tumble::test::rotation_onto;
using tumble::test::TorqueFreeBody;
using tumble::test::tumbling_mass;

const Vector3d kInertia = tumble::test::kTumblingInertia;
const Vector3d kOmega = tumble::test::kTumblingOmega;

/// Two bodies of parameterization P with I = diag(1, 2, 3): one tumbling near its separatrix
/// (omega0 = (0.1, 2, 0.05) rad/s) with its angular momentum along (1, 1, 1), one spinning about
/// its major axis z (2 rad/s) turned so that the spin axis is inertial y: between them every
/// three-parameter chart meets its switch zone. Save the state at t = 5 s, integrate to 30 s,
/// restart from the saved state. The attitudes read back must be the ones seen at t = 5 s,
/// exactly (the same numbers); a copy of the scene must read and integrate the saved state alike;
/// and the restarted run must follow the exact solutions within the global error bound of the
/// stress tests.
template <class P> void saved_state_round_trip() {
  using Body = RigidBody<P>;
  const Vector3d spin(0.0, 0.0, 2.0);
  const Matrix3d r_tumble = rotation_onto(kInertia.cwiseProduct(kOmega), Vector3d(1, 1, 1));
  const Matrix3d r_spin = rot(-std::numbers::pi / 2, Vector3d::UnitX());  // body z -> inertial y
  Scene<Bodies<Body>> scene;
  const auto a = scene.add(Body(tumbling_mass()), {.rotation = r_tumble, .omega = kOmega});
  const auto b = scene.add(Body(tumbling_mass()), {.rotation = r_spin, .omega = spin});
  const TorqueFreeBody exact_a(kInertia, kOmega, r_tumble), exact_b(kInertia, spin, r_spin);
  const double tol = 1e-10;
  const auto o = tumble::test::integrator_options(CvodeMethod::adams, tol);

  SceneIntegrator integrator(scene, 0.0, o);
  integrator.advance(5.0);
  const SceneState saved = integrator.save();
  const long steps_to_5 = integrator.statistics().steps;
  const Matrix3d ra = tumble::rotation(scene, a, saved), rb = tumble::rotation(scene, b, saved);
  const Vector3d wa = tumble::omega(scene, a, saved), wb = tumble::omega(scene, b, saved);
  integrator.advance(30.0);
  const long switches = integrator.statistics().chart_switches;
  INFO("chart switches in the first 30 s: " << switches);
  if constexpr (tumble::Chart<P>::has_singularity) {
    CHECK(switches > 0);  // the test crosses charts, or it proves nothing
  }
  // The saved state read after the switches: the same attitudes, to the last bit.
  CHECK(tumble::rotation(scene, a, saved) == ra);
  CHECK(tumble::rotation(scene, b, saved) == rb);
  integrator.reset(5.0, saved);
  CHECK(integrator.time() == 5.0);
  CHECK(tumble::rotation(scene, a, integrator.state()) == ra);
  CHECK(tumble::rotation(scene, b, integrator.state()) == rb);
  CHECK(tumble::omega(scene, a, integrator.state()) == wa);
  CHECK(tumble::omega(scene, b, integrator.state()) == wb);
  // A copy of the scene reads it the same, and integrates it the same.
  const Scene<Bodies<Body>> copy = scene;
  CHECK(tumble::rotation(copy, a, saved) == ra);
  SceneIntegrator other(copy, 5.0, saved, o);
  integrator.advance(12.0);
  const SceneState& s = integrator.state();
  other.advance(12.0);
  const SceneState& c = other.state();
  CHECK(s.y == c.y);
  CHECK(s.base == c.base);
  // And the restarted run is the physical motion.
  const long steps = steps_to_5 + other.statistics().steps;
  const double bound = tumble::test::global_error_bound(tol, steps, 2.0, 12.0);
  const double error =
      std::max(rotation_angle_between(tumble::rotation(scene, a, s), exact_a.rotation(12.0)),
               rotation_angle_between(tumble::rotation(scene, b, s), exact_b.rotation(12.0)));
  INFO("attitude error at 12 s " << error << ", bound " << bound << " (" << steps << " steps)");
  CHECK(error < bound);
}

}  // namespace

TEMPLATE_LIST_TEST_CASE("a saved state restarts at the attitude it was saved at",
                        "[integrate][saved_state]", TUMBLE_TEST_PARAMETERIZATIONS) {
  saved_state_round_trip<TestType>();
}
