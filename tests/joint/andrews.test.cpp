// IFToMM A03, Andrews' squeezing mechanism (examples/andrews.cpp): tumble's seven bodies in
// absolute coordinates (42 coordinates, 50 constraint rows of rank 41) against a second model in
// the Test Set's seven joint angles (andrews_reference.hpp), integrated in long double; and both
// against the Test Set's published reference at t = 0.03 s. The explicit integrator in both state
// forms here; CVODE's BDF: andrews_bdf.test.cpp. Compiled in three slices (tests/CMakeLists.txt),
// one parameterization each, the other cases spread over them.

#include <cmath>
#include <tuple>
#include <vector>

#include "support/catch.hpp"
#include "support/parameterizations.hpp"
#include "tumble/integrate.hpp"

// The example's main as a function template (one per slice): its body, the front door on the
// mechanism with Euler parameters, is compiled only where a test calls it (slice 2), not in the
// slices that never run it.
#define main(...) TUMBLE_TEST_SLICED_NAME(andrews_main)(auto...)
#include "../../examples/andrews.cpp"  // NOLINT(bugprone-suspicious-include)
#undef main

#include "andrews_reference.hpp"

namespace {

using namespace tumble;
using namespace andrews_test;

/// One parameterization of each family that keeps the plane's rotations regular.
using AndrewsParameterizations = std::tuple<EulerParameters, EulerZYX, RotationVector>;
using TUMBLE_TEST_SLICED_NAME(AndrewsSlice) = tumble::test::ThisSlice<AndrewsParameterizations>;

}  // namespace

#if TUMBLE_TEST_IN_SLICE(0)
TEST_CASE("IFToMM A03: Andrews' mechanism, a second model in joint angles against the Test Set",
          "[joint][iftomm]") {
  Real closure = 0;
  const auto [q, w] = split(minimal_reference(closure));
  CHECK(closure <= 1e-16L);  // the second model stayed on its loops: index 1 kept to 0.03 s
  // The Test Set's reference (RADAU5) is off by 1.1e-9 rad in beta (8.5e-11 of 1 + |beta|) and by
  // 3.1e-7 rad/s in gamma': its last digits are not the exact solution's. tumble's run (below)
  // agrees with the second model, not with those digits.
  const double eq = andrews::mixed_error(q, andrews::kEnd),
               ew = andrews::mixed_error(w, andrews::kEndRates);
  INFO("second model against the Test Set: angles " << eq << ", rates " << ew);
  CHECK(eq <= 1e-10);
  CHECK(ew <= 3e-8);
}

#endif  // TUMBLE_TEST_IN_SLICE(0)

TEMPLATE_LIST_TEST_CASE("IFToMM A03: Andrews' mechanism against the second model, explicit",
                        "[joint][iftomm]", TUMBLE_TEST_SLICED_NAME(AndrewsSlice)) {
  Real closure = 0;
  const auto [q, w] = split(minimal_reference(closure));
  const andrews::Andrews<TestType> m;
  CHECK(m.scene.constraint_count() == 50);
  CHECK(constraint_residual(m.scene, m.scene.initial_state()).rank == 41);
  for (const double tol : {1e-8, 1e-12}) {
    const andrews::Run r =
        tumble_run<OdeintIntegrator<typename andrews::Andrews<TestType>::SceneT>>(m, tol);
    const double eq = andrews::mixed_error(r.q, q), ew = andrews::mixed_error(r.rates, w);
    INFO("tol " << tol << ": angles " << eq << ", rates " << ew << ", energy " << r.energy
                << " J, |C| " << r.closure << " m");
    // The global error is the local tolerance times the mechanism's growth of errors, measured
    // (the three parameterizations, 1e-8 and 1e-12): angles 0.29-0.32 tol, rates 16-105 tol (the
    // crank at 1140 rad/s, 1e6 rad/s^2), energy 1.0-5.8 tol J of the motor's 0.52 J.
    CHECK(eq <= 10 * tol);
    CHECK(ew <= 300 * tol);
    CHECK(r.energy <= 10 * tol);
    CHECK(r.closure <= 1e-13);
  }
}

#if TUMBLE_TEST_IN_SLICE(1)
TEST_CASE("IFToMM A03: Andrews' mechanism in [q; qdot], explicit", "[joint][iftomm]") {
  Real closure = 0;
  const auto [q, w] = split(minimal_reference(closure));
  const andrews::Andrews<EulerParameters, StateForm::generalized> generalized;
  const andrews::Run a =
      tumble_run<OdeintIntegrator<decltype(generalized)::SceneT>>(generalized, 1e-12);
  INFO("[q; qdot]: angles " << andrews::mixed_error(a.q, q) << ", rates "
                            << andrews::mixed_error(a.rates, w));
  CHECK(andrews::mixed_error(a.q, q) <= 1e-10);
  CHECK(andrews::mixed_error(a.rates, w) <= 1e-10);
}

#endif  // TUMBLE_TEST_IN_SLICE(1)

#if TUMBLE_TEST_IN_SLICE(2)
TEST_CASE("examples/andrews.cpp: the squeezer on the Test Set's reference, energy kept",
          "[joint][example]") {
  CHECK(TUMBLE_TEST_SLICED_NAME(andrews_main)() == 0);
}
#endif  // TUMBLE_TEST_IN_SLICE(2)
