// IFToMM A03, Andrews' squeezing mechanism (examples/andrews.cpp), with CVODE's BDF: against the
// second model in joint angles (andrews_reference.hpp) at 1e-9; with the exact Jacobian
// (scene/jacobian.hpp) against difference quotients; and at 1e-11 and 1e-12, where BDF's step
// size used to collapse. The explicit runs: andrews.test.cpp.

#include <algorithm>
#include <cmath>
#include <vector>

#include "support/catch.hpp"
#include "tumble/integrate.hpp"

// Unused here (the example runs in andrews.test.cpp): its main as a function template, which is
// never instantiated, so its body (the front door on the mechanism) is not compiled.
#define main(...) andrews_bdf_main(auto...)
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
  // weighted RMS norm, over about ten times more steps of order <= 5, and its estimate holds no
  // normal components, which the projection removes). Measured at 1e-7 to 1e-10: angles 80-165
  // tol, rates 27000-54000 tol, energy 150-420 tol J (at 1e-9: 165, 54000, 239).
  CHECK(andrews::mixed_error(b.q, q) <= 300 * 1e-9);
  CHECK(andrews::mixed_error(b.rates, w) <= 1e5 * 1e-9);
  CHECK(b.energy <= 300 * 1e-9);
  CHECK(b.closure <= 1e-13);
}

TEST_CASE("IFToMM A03: BDF at 1e-11 and 1e-12 runs through, below BDF's former best",
          "[joint][iftomm]") {
  // With its local error estimate left whole in the joints' normal directions, BDF's step size
  // on this mechanism fell to 1e-68 at 1e-11 (t = 0.0109 s) and to a denormal at 1e-12 (t =
  // 0.0083 s): the estimate's normal velocity components held at 50-100 times the tolerance
  // whatever the step. Projected onto the constraints' tangent space as CVODE's error projection
  // intends (scene/assembly.hpp, project_error_estimate), both run to 0.03 s. Measured (GCC 12):
  // angles 2.7e-9 at 1e-11 and 1.2e-10 at 1e-12; the best before was 3.5e-9, at 1e-10.
  Real closure = 0;
  const auto [q, w] = split(minimal_reference(closure));
  const andrews::Andrews<> m;
  for (const double tol : {1e-11, 1e-12}) {
    const andrews::Run b = tumble_run<SceneIntegrator<andrews::Andrews<>::SceneT>>(m, tol);
    INFO("tol " << tol << ": angles " << andrews::mixed_error(b.q, q) << ", rates "
                << andrews::mixed_error(b.rates, w) << ", energy " << b.energy << " J, |C| "
                << b.closure << " m");
    CHECK(andrews::mixed_error(b.q, q) <= (tol > 5e-12 ? 1e-8 : 1e-9));
    CHECK(b.closure <= 1e-13);
  }
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
