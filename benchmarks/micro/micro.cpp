// tumble_micro: per-step micro-benchmarks of tumble's core assembly, with Google
// Benchmark. For every parameterization (the 12 Euler sequences, Euler parameters,
// Rodrigues (Gibbs) parameters, modified Rodrigues parameters, the rotation vector) and both
// reference points (centroid, offset) it times, in ns per call:
//   rotation/<P>                        P::rotation, R (Eq. 1.1)
//   G/<P>                               P::G (Eq. 1.5)
//   mass_matrix/<P>/<ref>               RigidBody::mass_matrix, M (Eq. 1.23)
//   centrifugal_coriolis/<P>/<ref>      RigidBody::centrifugal_coriolis, f_v (Eqs. 1.26-1.27)
//   generalized_force/<P>/<ref>         tumble::generalized_force of gravity + a point force + a
//                                       moment, Q (Eq. 1.31)
//   qddot/<P>/<ref>                     RigidBody::accelerations(q, qdot, wrench) (Eq. 1.32)
//   qddot_loads/<P>/<ref>               tumble::accelerations(body, t, q, qdot, loads...): the
//                                       same loads as generalized_force, wrench included
//   hand_written/EulerParameters/centroid        the floor (micro/floor.hpp): qddot of the
//   hand_written_loads/EulerParameters/centroid  centroidal Euler-parameter body written by hand,
//                                       for a given wrench (against qddot/...) and with the same
//                                       loads assembled by hand (against qddot_loads/...);
//                                       registered in this file so that floor and subject are
//                                       compiled in one translation unit and run by the same
//                                       harness on the same data.
// R and G do not depend on the reference point and are timed once per parameterization. The
// dense-LU baseline is in micro/baselines.cpp, the peers in
// peers/pinocchio_micro.cpp and peers/mujoco_micro.cpp; benchmarks/micro/summarize.py turns the
// JSON output into the ratios of docs/benchmarks/per-call.md, and tumble_bench prints the medians
// of its short list. micro/jacobian.cpp times the scene's Jacobian (automatic differentiation)
// against difference quotients.

#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "micro/common.hpp"
#include "micro/floor.hpp"

namespace tumble::bench {
namespace {

template <class P> void register_orientation() {
  const std::string name(P::name);
  using Body = RigidBody<P, ReferencePoint::centroid, double>;
  add("rotation/" + name, [](benchmark::State& st) {
    static const States<Body> s;
    run_cycling(st, [&](std::size_t i) { return P::rotation(Body::theta(s.q[i])); });
  });
  add("G/" + name, [](benchmark::State& st) {
    static const States<Body> s;
    run_cycling(st, [&](std::size_t i) { return P::G(Body::theta(s.q[i])); });
  });
}

template <class P, ReferencePoint Ref> void register_body() {
  using Body = RigidBody<P, Ref, double>;
  const std::string suffix = std::string("/") + std::string(P::name) + "/" + ref_name(Ref);
  add("mass_matrix" + suffix, [](benchmark::State& st) {
    static const States<Body> s;
    const Body body(mass_properties<Ref>());
    run_cycling(st, [&](std::size_t i) { return body.mass_matrix(s.q[i]); });
  });
  add("centrifugal_coriolis" + suffix, [](benchmark::State& st) {
    static const States<Body> s;
    const Body body(mass_properties<Ref>());
    run_cycling(st, [&](std::size_t i) { return body.centrifugal_coriolis(s.q[i], s.qdot[i]); });
  });
  add("generalized_force" + suffix, [](benchmark::State& st) {
    static const States<Body> s;
    const Body body(mass_properties<Ref>());
    const LoadSet l;
    run_cycling(st, [&](std::size_t i) {
      return tumble::generalized_force(body, 0.0, s.q[i], s.qdot[i], l.gravity, l.force, l.moment);
    });
  });
  add("qddot" + suffix, [](benchmark::State& st) {
    static const States<Body> s;
    const Body body(mass_properties<Ref>());
    run_cycling(st,
                [&](std::size_t i) { return body.accelerations(s.q[i], s.qdot[i], s.wrench[i]); });
  });
  add("qddot_loads" + suffix, [](benchmark::State& st) {
    static const States<Body> s;
    const Body body(mass_properties<Ref>());
    const LoadSet l;
    run_cycling(st, [&](std::size_t i) {
      return tumble::accelerations(body, 0.0, s.q[i], s.qdot[i], l.gravity, l.force, l.moment);
    });
  });
}

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

template <class... P> void register_all() {
  (register_orientation<P>(), ...);
  (register_body<P, ReferencePoint::centroid>(), ...);
  (register_body<P, ReferencePoint::offset>(), ...);
}

}  // namespace

void register_tumble() {
  // The loop itself (load an index, keep a result): what every number below includes.
  add("loop_overhead", [](benchmark::State& st) {
    const auto& raw = raw_states();
    run_cycling(st, [&](std::size_t i) { return raw[i].omega; });
  });
  register_all<EulerParameters, RodriguesParameters, ModifiedRodriguesParameters, RotationVector,
               EulerXYZ, EulerXZY, EulerYXZ, EulerYZX, EulerZXY, EulerZYX, EulerXYX, EulerXZX,
               EulerYXY, EulerYZY, EulerZXZ, EulerZYZ>();
  register_hand_written();
}

}  // namespace tumble::bench

namespace {
constexpr const char* kCompiler =
#if defined(__clang__)
    "clang " __clang_version__;
#elif defined(__GNUC__)
    "gcc " __VERSION__;
#else
    "unknown";
#endif
}  // namespace

int main(int argc, char** argv) {
  tumble::bench::register_tumble();
  tumble::bench::register_baselines();
  tumble::bench::register_jacobian();
#ifdef TUMBLE_BENCH_HAVE_PINOCCHIO
  tumble::bench::register_pinocchio();
#endif
#ifdef TUMBLE_BENCH_HAVE_MUJOCO
  tumble::bench::register_mujoco();
#endif
  benchmark::AddCustomContext("tumble_compiler", kCompiler);
#ifdef TUMBLE_BENCH_FLAGS
  benchmark::AddCustomContext("tumble_flags", TUMBLE_BENCH_FLAGS);
#endif
#ifdef NDEBUG
  benchmark::AddCustomContext("tumble_ndebug", "yes");
#else
  benchmark::AddCustomContext("tumble_ndebug", "no (assertions on: not a Release build)");
#endif
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) {
    return 1;
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
