// tumble_floor_check: the floor ratio of tumble_micro measured a second way, without Google
// Benchmark. tumble's qddot (Euler parameters, centroid, wrench given) and the hand-written
// closed form (micro/floor.hpp) are compiled in this one translation unit and called alike: a
// loop of `calls` calls over the 64 states of micro/common.hpp (the input changes every call),
// each result folded into a running sum (so no call is dead and none can be hoisted), timed with
// std::chrono::steady_clock. The loops alternate `rounds` times; the medians of ns per call and
// their ratio are printed, and, for comparison, the former floor (the same equations as nested
// Eigen product expressions, HandWritten::accelerations_nested).
//
//   tumble_floor_check [calls=1000000] [rounds=7]

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "micro/common.hpp"
#include "micro/floor.hpp"

namespace {

using namespace tumble;
using namespace tumble::bench;
using Body = RigidBody<EulerParameters, ReferencePoint::centroid, double>;

template <class F> double ns_per_call(long calls, F&& f) {
  double sink = 0;
  const auto start = std::chrono::steady_clock::now();
  std::size_t i = 0;
  for (long c = 0; c < calls; ++c) {
    sink += f(i).sum();
    i = (i + 1) & (kStates - 1);
  }
  const auto end = std::chrono::steady_clock::now();
  volatile double keep = sink;  // the sum is used: nothing above is dead code
  (void)keep;
  return std::chrono::duration<double, std::nano>(end - start).count() / static_cast<double>(calls);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  const long calls = argc > 1 ? std::atol(argv[1]) : 1'000'000;
  const int rounds = argc > 2 ? std::atoi(argv[2]) : 7;
  const States<Body> s;
  const Body body(mass_properties<ReferencePoint::centroid>());
  const HandWritten h;
  std::vector<double> tumble_ns, floor_ns, nested_ns;
  for (int r = 0; r < rounds; ++r) {
    tumble_ns.push_back(ns_per_call(
        calls, [&](std::size_t i) { return body.accelerations(s.q[i], s.qdot[i], s.wrench[i]); }));
    floor_ns.push_back(ns_per_call(calls, [&](std::size_t i) {
      return h.accelerations(s.q[i], s.qdot[i], s.wrench[i].force, s.wrench[i].moment);
    }));
    nested_ns.push_back(ns_per_call(calls, [&](std::size_t i) {
      return h.accelerations_nested(s.q[i], s.qdot[i], s.wrench[i].force, s.wrench[i].moment);
    }));
  }
  const double t = median(tumble_ns), f = median(floor_ns), n = median(nested_ns);
  std::printf("qddot/EulerParameters/centroid  %.1f ns per call (median of %d x %ld calls)\n", t,
              rounds, calls);
  std::printf("hand-written floor              %.1f ns per call\n", f);
  std::printf("ratio tumble / floor            %.2f\n", t / f);
  std::printf("former floor (nested Eigen products) %.1f ns per call, tumble / it %.2f\n", n,
              t / n);
  return 0;
}
