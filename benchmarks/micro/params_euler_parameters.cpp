// tumble_micro: the per-call benchmarks (micro/micro.cpp) of Euler parameters, with the
// hand-written floor (micro/floor.hpp) in the same translation unit: floor and subject compiled
// alike and run by the same harness on the same data.

#include <cstdio>
#include <cstdlib>

#include "micro/floor.hpp"
#include "micro/register.hpp"

namespace tumble::bench {
namespace {

/// The floor, checked against tumble on every state first (see micro/floor.hpp).
void register_hand_written() {
  using Body = RigidBody<EulerParameters, ReferencePoint::centroid, double>;
  {
    const States<Body> s;
    const Body body(mass_properties<ReferencePoint::centroid>());
    const HandWritten h;
    const LoadSet l;
    for (std::size_t i = 0; i < kStates; ++i) {
      const auto a = body.accelerations(s.q[i], s.qdot[i], s.wrench[i]);
      const auto b = h.accelerations(s.q[i], s.qdot[i], s.wrench[i].force, s.wrench[i].moment);
      const auto c =
          tumble::accelerations(body, 0.0, s.q[i], s.qdot[i], l.gravity, l.force, l.moment);
      const auto d = h.accelerations_loads(s.q[i], s.qdot[i]);
      if (!((a - b).norm() <= 1e-10 * (1.0 + a.norm())) ||
          !((c - d).norm() <= 1e-10 * (1.0 + c.norm()))) {
        std::fprintf(stderr,
                     "tumble_micro: the hand-written closed form and tumble disagree, "
                     "state %zu\n",
                     i);
        std::exit(2);
      }
    }
  }
  add("hand_written/EulerParameters/centroid", [](benchmark::State& st) {
    static const States<Body> s;
    const HandWritten h;
    run_cycling(st, [&](std::size_t i) {
      return h.accelerations(s.q[i], s.qdot[i], s.wrench[i].force, s.wrench[i].moment);
    });
  });
  add("hand_written_loads/EulerParameters/centroid", [](benchmark::State& st) {
    static const States<Body> s;
    const HandWritten h;
    run_cycling(st, [&](std::size_t i) { return h.accelerations_loads(s.q[i], s.qdot[i]); });
  });
}

}  // namespace

void register_euler_parameters() {
  register_all<EulerParameters>();
  register_hand_written();
}

}  // namespace tumble::bench
