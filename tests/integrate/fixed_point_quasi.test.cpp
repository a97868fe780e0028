// Bodies held at a fixed point (ReferencePoint::fixed_point) in the quasi-velocity state form
// [theta; omega], integrated by SceneIntegrator (CVODE), against closed forms:
//  - the Lagrange top (tests/integrate/fixed_point_top.hpp) for every parameterization of the
//    integration set, with Adams and with BDF + GMRES preconditioned by the block preconditioner
//    (the generalized form with dense BDF: fixed_point.test.cpp);
//  - the same top held at its tip by a spring-damper (a free body framed at its tip,
//    ReferencePoint::offset) converges to the fixed-point solution as the stiffness k grows, at
//    the rate O(1/k): the tip sags by F/k under a load F, and the attitude error follows; the
//    spring's force on the tip converges to the reaction force at the fixed point likewise.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include <Eigen/Core>

#include "integrate/fixed_point_top.hpp"
#include "support/catch.hpp"
#include "support/lagrange_top.hpp"
#include "support/parameterizations.hpp"
#include "support/random.hpp"
#include "support/scene_fixtures.hpp"
#include "tumble/force/gravity.hpp"
#include "tumble/force/spring_damper.hpp"
#include "tumble/integrate/scene_integrator.hpp"
#include "tumble/scene/accelerations.hpp"
#include "tumble/scene/observables.hpp"
#include "tumble/scene/scene.hpp"

namespace {

using tumble::CvodeMethod;
using tumble::SceneIntegrator;
using tumble::StateForm;

}  // namespace

TEMPLATE_LIST_TEST_CASE("Lagrange top on its tip, quasi-velocity form: closed form and invariants",
                        "[integrate][fixed_point]", TUMBLE_TEST_PARAMETERIZATIONS) {
  const double tol = 1e-10;
  tumble::test::check_top<TestType, StateForm::quasi_velocities>(
      "Adams", tol, [&](const auto& scene) {
        return SceneIntegrator(scene, 0.0,
                               tumble::test::integrator_options(CvodeMethod::adams, tol, 200000));
      });
  tumble::test::check_top<TestType, StateForm::quasi_velocities>(
      "BDF+GMRES", tol, [&](const auto& scene) {
        auto o = tumble::test::integrator_options(CvodeMethod::bdf, tol, 200000);
        o.cvode.linear_solver = tumble::CvodeLinearSolver::gmres;
        o.cvode.preconditioning = tumble::CvodePreconditioning::left;
        return SceneIntegrator(scene, 0.0, o);
      });
}

#if TUMBLE_TEST_PRIMARY_SLICE
namespace {

using P = tumble::EulerParameters;
using Sprung = tumble::RigidBody<P, tumble::ReferencePoint::offset>;
using SprungScene = tumble::Scene<tumble::Bodies<Sprung>,
                                  tumble::Loads<tumble::UniformGravity, tumble::SpringDamper>,
                                  StateForm::quasi_velocities>;

struct Sample {
  Eigen::Matrix3d rotation;
  Eigen::Vector3d tip_force;  ///< the force on the top at its tip, inertial
};

/// The attitude of the top and the force on its tip, tip_force(t, state), at `times`,
/// integrated with BDF at tolerance tol.
template <class SceneT, class Body, class TipForce>
std::vector<Sample> samples(const SceneT& scene, tumble::BodyId<Body> id,
                            const std::vector<double>& times, double tol, TipForce&& tip_force) {
  SceneIntegrator integrator(scene, 0.0,
                             tumble::test::integrator_options(CvodeMethod::bdf, tol, 2000000));
  std::vector<Sample> r;
  for (const double t : times) {
    integrator.advance(t);
    const tumble::SceneState& s = integrator.state();
    r.push_back({tumble::rotation(scene, id, s), tip_force(t, s)});
  }
  return r;
}

}  // namespace

TEST_CASE("the top on a spring-damper converges to the fixed point at the rate O(1/k)",
          "[integrate][fixed_point]") {
  const tumble::test::TopInScene<P, StateForm::quasi_velocities> fixed;
  const auto& top = fixed.top;
  std::vector<double> times;
  for (int i = 1; i <= 40; ++i) {
    times.push_back(0.025 * i);  // one second: about three nutation periods
  }
  const double tol = 1e-11;
  // The fixed top: the force on its tip is the reaction (tumble::reaction_force).
  const auto reference =
      samples(fixed.scene, fixed.id, times, tol, [&](double t, const tumble::SceneState& s) {
        return tumble::reaction_force(fixed.scene, fixed.id, s, t);
      });

  // The spring at the tip, damped at a fixed ratio (c = sqrt(k m): zeta = 1/2): the tip's fast
  // mode then decays within a few of its periods, and what is left is the quasi-static sag F/k.
  std::vector<double> errors, force_errors;
  const std::vector<double> ks = {1e4, 1e5, 1e6};
  for (const double k : ks) {
    SprungScene scene;
    const auto id =
        scene.add(Sprung(top.mass_properties()), top.initial_state(tumble::test::kTopPivot));
    scene.add_load(id, tumble::UniformGravity(top.gravity()));
    const double c = std::sqrt(k * top.mass);
    scene.add_load(
        id, tumble::SpringDamper(Eigen::Vector3d::Zero(), tumble::test::kTopPivot, {k, c, 0.0}));
    // The spring's force on the tip, -k (r_tip - pivot) - c v_tip, written here.
    const auto r = samples(scene, id, times, tol, [&](double, const tumble::SceneState& s) {
      return Eigen::Vector3d(-k * (tumble::position(scene, id, s) - tumble::test::kTopPivot) -
                             c * tumble::velocity(scene, id, s));
    });
    double e = 0, ef = 0;
    for (std::size_t i = 0; i < times.size(); ++i) {
      e = std::max(e, tumble::test::rotation_angle_between(r[i].rotation, reference[i].rotation));
      // After the start, where the spring begins unloaded and its transient decays as
      // exp(-sqrt(k/m) t / 2) (below 1e-5 of m g from 0.1 s at k = 1e4).
      if (times[i] >= 0.1) {
        ef = std::max(ef, (r[i].tip_force - reference[i].tip_force).norm() / (top.mass * top.g));
      }
    }
    errors.push_back(e);
    force_errors.push_back(ef);
  }
  // The order of convergence between successive k (a factor 10 apart): 1 for O(1/k). The next
  // term of the expansion is smaller by (k/m)^(-1/2) over the motion's rates (the fast mode's
  // time scale against the nutation's, ~0.2 at k = 1e4): the measured order is within 0.2 of 1.
  for (std::size_t j = 0; j + 1 < errors.size(); ++j) {
    const double order = std::log10(errors[j] / errors[j + 1]);
    INFO("k = " << ks[j] << ": " << errors[j] << " rad, k = " << ks[j + 1] << ": " << errors[j + 1]
                << " rad, order " << order);
    CHECK(std::abs(order - 1.0) < 0.2);
    // The spring's force converges to the reaction force at the fixed point at the same rate.
    const double force_order = std::log10(force_errors[j] / force_errors[j + 1]);
    INFO("tip force: " << force_errors[j] << " m g, then " << force_errors[j + 1] << " m g, order "
                       << force_order);
    CHECK(std::abs(force_order - 1.0) < 0.2);
  }
  if (std::getenv("TUMBLE_TEST_REPORT") != nullptr) {
    for (std::size_t j = 0; j < errors.size(); ++j) {
      std::printf("spring k = %.0e N/m: largest attitude error %.3e rad (k x error %.1f), tip "
                  "force - reaction %.3e m g\n",
                  ks[j], errors[j], ks[j] * errors[j], force_errors[j]);
    }
  }
}
#endif  // TUMBLE_TEST_PRIMARY_SLICE
