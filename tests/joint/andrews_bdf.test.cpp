// IFToMM A03, Andrews' squeezing mechanism (examples/andrews.cpp), with CVODE's BDF: against the
// second model in joint angles (andrews_reference.hpp) at 1e-9; with the exact Jacobian
// (scene/jacobian.hpp) against difference quotients; and at atol = 1e-11, where BDF's step size
// collapses, stopping there rather than extrapolating. The explicit runs: andrews.test.cpp.

#include <algorithm>
#include <cmath>
#include <vector>

#include "support/catch.hpp"
#include "tumble/integrate.hpp"

#define main andrews_bdf_main          // unused: the example runs in andrews.test.cpp
#include "../../examples/andrews.cpp"  // NOLINT(bugprone-suspicious-include)
#undef main

#include "andrews_reference.hpp"

namespace {

using namespace tumble;
using namespace andrews_test;

}  // namespace

TEST_CASE("IFToMM A03: Andrews' mechanism with CVODE's BDF against the second model",
          "[joint][iftomm]") {
  Real closure = 0;
  const auto [q, w] = split(minimal_reference(closure));
  const andrews::Andrews<> m;
  const andrews::Run b = tumble_run<SceneIntegrator<andrews::Andrews<>::SceneT>>(m, 1e-9);
  INFO("BDF: angles " << andrews::mixed_error(b.q, q) << ", rates "
                      << andrews::mixed_error(b.rates, w) << ", energy " << b.energy << " J, |C| "
                      << b.closure << " m");
  // BDF's global error against its tolerance is larger than Fehlberg's (its error test is a
  // weighted RMS norm, over about ten times more steps of order <= 5). Measured at 1e-7 to 1e-10:
  // angles 23-61 tol, rates 5400-20000 tol, energy 15-57 tol J.
  CHECK(andrews::mixed_error(b.q, q) <= 300 * 1e-9);
  CHECK(andrews::mixed_error(b.rates, w) <= 1e5 * 1e-9);
  CHECK(b.energy <= 300 * 1e-9);
  CHECK(b.closure <= 1e-13);
}

TEST_CASE("IFToMM A03: BDF at atol = 1e-11 stops at its stall, never extrapolating past it",
          "[joint][iftomm]") {
  // At 1e-11 CVODE's BDF step size on this mechanism falls to a denormal (8e-320 near
  // t = 0.0102 s, SUNDIALS 6.4), where CVODE's own test for having passed an output time
  // underflows and it returned success with states extrapolated from where it was stuck
  // (cvode_report.hpp, underflow_failure). Either the run reaches 0.03 s, or it stops with a
  // step-size error; every state it gave is on the explicit run at 1e-12 (itself within 1e-10 of
  // the second model: andrews.test.cpp).
  const andrews::Andrews<> m;
  SceneIntegratorOptions opt;
  opt.rtol = 1e-11;
  opt.atol = 1e-11;
  SceneIntegrator<andrews::Andrews<>::SceneT> bdf(m.scene, 0.0, opt);
  OdeintIntegrator<andrews::Andrews<>::SceneT> explicit_run(m.scene, 0.0,
                                                            {.rtol = 1e-12, .atol = 1e-12});
  double t = 0.0, worst = 0.0;
  try {
    for (int k = 1; k <= 100; ++k) {
      t = 0.0003 * k;
      bdf.advance(t);
      explicit_run.advance(t);
      worst = std::max(worst, (bdf.state().y - explicit_run.state().y).cwiseAbs().maxCoeff());
    }
  } catch (const IntegrationError& e) {
    INFO(e.what());
    CHECK(e.reason() == IntegrationFailure::step_size);
    CHECK(e.time() <= t);
  }
  INFO("largest difference of the states given: " << worst);
  CHECK(worst <= 1e-4);  // positions in m, rates up to 1e3 rad/s: BDF at 1e-11
}

TEST_CASE("mechanism jacobian: BDF on Andrews' mechanism with it and with difference quotients",
          "[joint][jacobian]") {
  const andrews::Andrews<> m;
  for (const bool exact : {true, false}) {
    const andrews::Run r = andrews::run(m, [&](const std::vector<double>& times, const auto& obs) {
      SceneIntegratorOptions opt;
      opt.rtol = 1e-9;
      opt.atol = 1e-9;
      opt.cvode.use_system_jacobian = exact;
      SceneIntegrator<andrews::Andrews<>::SceneT> integrator(m.scene, 0.0, opt);
      integrator.integrate(times, obs);
      INFO((exact ? "exact" : "difference quotients")
           << ": " << integrator.statistics().steps << " steps");
    });
    INFO((exact ? "exact" : "difference quotients")
         << ": angles " << andrews::mixed_error(r.q, andrews::kEnd) << ", energy " << r.energy);
    CHECK(andrews::mixed_error(r.q, andrews::kEnd) <= 3e-7);
    CHECK(r.energy <= 3e-7);
  }
}
