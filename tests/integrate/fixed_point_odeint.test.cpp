// Bodies held at a fixed point (ReferencePoint::fixed_point) integrated by OdeintIntegrator
// (Boost.Odeint, include/tumble/integrate/explicit_integrator.hpp) in both state forms: the
// Lagrange top against its closed form (tests/integrate/fixed_point_top.hpp), every
// parameterization of the integration set, with Fehlberg 7(8) and Dormand-Prince 5(4); the
// Euler-parameter top also with the state's size fixed at compile time (no heap in a step).

#include <Eigen/Core>

#include "integrate/fixed_point_top.hpp"
#include "support/catch.hpp"
#include "support/parameterizations.hpp"
#include "tumble/integrate/explicit_integrator.hpp"
#include "tumble/scene/scene.hpp"

namespace {

using tumble::OdeintIntegrator;
using tumble::OdeintMethod;
using tumble::OdeintOptions;
using tumble::StateForm;

OdeintOptions odeint_options(OdeintMethod method, double tol) {
  OdeintOptions o;
  o.method = method;
  o.rtol = tol;
  o.atol = tol;
  o.max_steps = 200000;
  return o;
}

template <class P, StateForm Form, int N = Eigen::Dynamic> void check_odeint() {
  const double tol = 1e-10;
  // A plain pair, not a structured binding: Clang 14 cannot capture bindings in a lambda.
  for (const auto& m : {std::pair{OdeintMethod::fehlberg78, "Fehlberg78"},
                        std::pair{OdeintMethod::dopri5, "Dopri5"}}) {
    const OdeintMethod method = m.first;
    tumble::test::check_top<P, Form>(m.second, tol, [&](const auto& scene) {
      return OdeintIntegrator<std::remove_cvref_t<decltype(scene)>, N>(scene, 0.0,
                                                                       odeint_options(method, tol));
    });
  }
}

}  // namespace

TEMPLATE_LIST_TEST_CASE("Lagrange top on its tip with the explicit integrator, both state forms",
                        "[integrate][fixed_point][odeint]", TUMBLE_TEST_PARAMETERIZATIONS) {
  check_odeint<TestType, StateForm::generalized>();
  check_odeint<TestType, StateForm::quasi_velocities>();
}

#if TUMBLE_TEST_PRIMARY_SLICE
TEST_CASE("Lagrange top on its tip with the explicit integrator, state size fixed at compile time",
          "[integrate][fixed_point][odeint]") {
  using P = tumble::EulerParameters;
  check_odeint<P, StateForm::generalized, 8>();       // [p; pdot]
  check_odeint<P, StateForm::quasi_velocities, 7>();  // [p; omega]
}
#endif
