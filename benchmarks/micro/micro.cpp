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
//                                       registered with Euler parameters, in one translation
//                                       unit, and run by the same harness on the same data.
// Each family of parameterizations is registered from a source of its own (micro/params_*.cpp,
// micro/register.hpp: compiled as a user's translation unit is).
// R and G do not depend on the reference point and are timed once per parameterization. The
// dense-LU baseline is in micro/baselines.cpp, the peers in
// peers/pinocchio_micro.cpp and peers/mujoco_micro.cpp; benchmarks/micro/summarize.py turns the
// JSON output into the ratios of docs/benchmarks/per-call.md, and tumble_bench prints the medians
// of its short list. micro/jacobian.cpp times the scene's Jacobian (automatic differentiation)
// against difference quotients.

#include <string>

#include "micro/common.hpp"

namespace tumble::bench {

// One source per family of parameterizations (micro/register.hpp says why).
void register_euler_parameters();
void register_rodrigues();
void register_rotation_vector();
void register_tait_bryan();
void register_proper_euler();

void register_tumble() {
  // The loop itself (load an index, keep a result): what every number below includes.
  add("loop_overhead", [](benchmark::State& st) {
    const auto& raw = raw_states();
    run_cycling(st, [&](std::size_t i) { return raw[i].omega; });
  });
  register_euler_parameters();
  register_rodrigues();
  register_rotation_vector();
  register_tait_bryan();
  register_proper_euler();
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
