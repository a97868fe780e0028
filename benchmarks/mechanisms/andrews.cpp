// tumble_bench, study (e): IFToMM A03, Andrews' squeezing mechanism (examples/andrews.cpp: seven
// planar links in absolute coordinates, 42 coordinates, 50 constraint rows of rank 41, a spring
// and a motor), from rest to t = 0.03 s with outputs every 0.3 ms, as the andrews tests run it.
// The reference is the tests' second model (tests/joint/andrews_reference.hpp): the Test Set's
// seven joint angles with six loop-closure constraints, integrated by Fehlberg 7(8) in long
// double to 1e-17. The error measure is the andrews tests': the seven angles at 0.03 s, the
// largest |q - q_ref| / (1 + |q_ref|) (the Test Set's mixed measure; |q_ref| up to 15.8 rad).
// The Test Set's published reference (RADAU5) is itself 1.1e-9 rad off in beta (reported beside
// the table): errors below that are measured against the second model only.

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "common/format.hpp"
#include "mechanisms/mechanisms.hpp"
#include "mechanisms/run.hpp"
#include "tumble/integrate.hpp"

#define main tumble_bench_andrews_example_main  // the example's program: not run here
#include "../../examples/andrews.cpp"           // NOLINT(bugprone-suspicious-include)
#undef main

#include "joint/andrews_reference.hpp"

namespace tumble::bench {

MechanismResult run_mechanism_a03(const MechanismPlan& plan, const std::function<void()>& step) {
  const Stopwatch reference_watch;
  andrews_test::Real closure = 0;
  // Not a structured binding: Clang 14 cannot capture one in a lambda (measure, below).
  const andrews::Angles q_ref = andrews_test::split(andrews_test::minimal_reference(closure)).first;
  const double reference_seconds = reference_watch.wall();
  const andrews::Andrews<> m;

  std::vector<double> times;
  for (int k = 1; k <= 100; ++k) {
    times.push_back(0.0003 * k);
  }
  // The links' absolute angles, followed over the crank's turns output by output (as
  // andrews::run does), kept at the last output.
  andrews::Angles a = andrews::absolute(andrews::kStart);
  std::size_t outputs = 0;
  auto record = [&](std::size_t k, const SceneState& s) {
    if (k == 0) {
      a = andrews::absolute(andrews::kStart);
    }
    a = m.angles(s, a);
    outputs = k + 1;
  };
  auto measure = [&] {
    const double e =
        outputs == times.size() ? andrews::mixed_error(andrews::relative(a), q_ref) : std::nan("");
    outputs = 0;
    return e;
  };
  MechanismResult r;
  r.id = "a03";
  r.title = "IFToMM A03, Andrews' squeezing mechanism: 7 links, 10 hinges, spring and motor, "
            "0.03 s (2.5 crank turns)";
  r.measure = "the 7 joint angles at 0.03 s, max |q - q_ref| / (1 + |q_ref|)";
  r.reference = "a second model in the 7 joint angles, Fehlberg 7(8) in long double to 1e-17 (" +
                duration(reference_seconds) + ", loop closure " +
                sci(static_cast<double>(closure)) + "); the Test Set's RADAU5 reference is " +
                sci(andrews::mixed_error(andrews::kEnd, q_ref)) + " from it";
  r.rows = mechanism_sweep(plan, m.scene, times, record, measure, step);
  return r;
}

}  // namespace tumble::bench
