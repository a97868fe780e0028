// Bodies held at a fixed point (ReferencePoint::fixed_point) in the quasi-velocity state form
// [theta; omega], integrated by SceneIntegrator (CVODE), against closed forms:
//  - the Lagrange top (tests/integrate/fixed_point_top.hpp) for every parameterization of the
//    integration set, with Adams and with BDF + GMRES preconditioned by the block preconditioner
//    (the generalized form with dense BDF: fixed_point.test.cpp);
//  - the same top held at its tip by a spring-damper (a free body framed at its tip,
//    ReferencePoint::offset) converges to the fixed-point solution as the stiffness k grows, at
//    the rate O(1/k): the tip sags by F/k under a load F, and the attitude error follows.

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

/// The attitudes of the top at `times`, integrated with BDF at tolerance tol.
template <class SceneT, class Body>
std::vector<Eigen::Matrix3d> attitudes(const SceneT& scene, tumble::BodyId<Body> id,
                                       const std::vector<double>& times, double tol) {
  SceneIntegrator integrator(scene, 0.0,
                             tumble::test::integrator_options(CvodeMethod::bdf, tol, 2000000));
  std::vector<Eigen::Matrix3d> r;
  for (const double t : times) {
    r.push_back(tumble::rotation(scene, id, integrator.advance(t)));
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
  const auto reference = attitudes(fixed.scene, fixed.id, times, tol);

  // The spring at the tip, damped at a fixed ratio (c = sqrt(k m): zeta = 1/2): the tip's fast
  // mode then decays within a few of its periods, and what is left is the quasi-static sag F/k.
  std::vector<double> errors;
  const std::vector<double> ks = {1e4, 1e5, 1e6};
  for (const double k : ks) {
    SprungScene scene;
    const auto id =
        scene.add(Sprung(top.mass_properties()), top.initial_state(tumble::test::kTopPivot));
    scene.add_load(id, tumble::UniformGravity(top.gravity()));
    scene.add_load(id, tumble::SpringDamper(Eigen::Vector3d::Zero(), tumble::test::kTopPivot,
                                            {k, std::sqrt(k * top.mass), 0.0}));
    const auto r = attitudes(scene, id, times, tol);
    double e = 0;
    for (std::size_t i = 0; i < times.size(); ++i) {
      e = std::max(e, tumble::test::rotation_angle_between(r[i], reference[i]));
    }
    errors.push_back(e);
  }
  // The order of convergence between successive k (a factor 10 apart): 1 for O(1/k). The next
  // term of the expansion is smaller by (k/m)^(-1/2) over the motion's rates (the fast mode's
  // time scale against the nutation's, ~0.2 at k = 1e4): the measured order is within 0.2 of 1.
  for (std::size_t j = 0; j + 1 < errors.size(); ++j) {
    const double order = std::log10(errors[j] / errors[j + 1]);
    INFO("k = " << ks[j] << ": " << errors[j] << " rad, k = " << ks[j + 1] << ": " << errors[j + 1]
                << " rad, order " << order);
    CHECK(std::abs(order - 1.0) < 0.2);
  }
  if (std::getenv("TUMBLE_TEST_REPORT") != nullptr) {
    for (std::size_t j = 0; j < errors.size(); ++j) {
      std::printf("spring k = %.0e N/m: largest attitude error %.3e rad (k x error %.1f)\n", ks[j],
                  errors[j], ks[j] * errors[j]);
    }
  }
}
#endif  // TUMBLE_TEST_PRIMARY_SLICE
