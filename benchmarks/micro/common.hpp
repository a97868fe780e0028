#pragma once
// Shared fixtures of tumble's per-step micro-benchmarks (tumble_micro): one body, one set
// of loads and 64 random states, so that every benchmark (tumble, the dense-LU baseline, the
// hand-written closed form, Pinocchio, MuJoCo) times the same work on the same data.
//
// The body: m = 3.5 kg and a full (non-diagonal) inertia about the centroid; framed at its
// centroid (ReferencePoint::centroid) or at a point c with the centroid at r_g = (0.1, -0.2, 0.3)
// m from it (ReferencePoint::offset). The loads: uniform gravity, a force at a body point
// (inertial components) and a body moment (reference chapter, Eqs. 1.28-1.31).
//
// The states: attitudes drawn uniformly on SO(3) (Shoemake's method), converted to each
// parameterization through the unit quaternion (P::from_quaternion, then P::canonical), angular
// velocities and linear velocities with components uniform in [-3, 3], positions in [-1, 1],
// and a random wrench (force inertial, moment body) per state for the functions that take one.
// Every benchmark cycles through the 64 states, so the compiler can hoist nothing out of the loop.

#include <array>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <random>
#include <string>
#include <utility>

#include <benchmark/benchmark.h>

#include "tumble/tumble.hpp"

namespace tumble::bench {

inline constexpr std::size_t kStates = 64;  // a power of two: the index wraps with a mask

inline double body_mass() { return 3.5; }
inline Matrix3<double> body_inertia() {  // about the centroid, body axes (kg m^2)
  Matrix3<double> i;
  i << 1.2, 0.1, -0.05,  //
      0.1, 2.0, 0.08,    //
      -0.05, 0.08, 2.9;
  return i;
}
inline Vector3<double> body_centroid_offset() { return {0.1, -0.2, 0.3}; }

template <ReferencePoint Ref> MassProperties<double> mass_properties() {
  if constexpr (Ref == ReferencePoint::centroid) {
    return MassProperties<double>::about_centroid(body_mass(), body_inertia());
  } else {
    return MassProperties<double>::about_centroid(body_mass(), body_inertia(),
                                                  body_centroid_offset());
  }
}

/// The loads of the "generalized force" and "qddot with loads" benchmarks.
inline Vector3<double> load_gravity() { return {0.0, 0.0, -9.81}; }
inline Vector3<double> load_point() { return {0.3, 0.1, -0.2}; }        ///< r_cp, body
inline Vector3<double> load_point_force() { return {1.5, -2.0, 0.7}; }  ///< inertial
inline Vector3<double> load_moment() { return {0.2, -0.1, 0.4}; }       ///< body
struct LoadSet {
  UniformGravity gravity{load_gravity()};
  PointForce force{load_point(), load_point_force(), Components::inertial};
  BodyMoment moment{load_moment()};
};

/// One state, independent of the parameterization.
struct RawState {
  Eigen::Quaterniond attitude;
  Vector3<double> position;
  Vector3<double> velocity;  ///< of the reference point, inertial components
  Vector3<double> omega;     ///< body components
  Wrench<double> wrench;     ///< force inertial, moment about c body
};

inline const std::array<RawState, kStates>& raw_states() {
  static const std::array<RawState, kStates> states = [] {
    std::mt19937_64 gen(20240611);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::uniform_real_distribution<double> sym(-1.0, 1.0);
    auto vec = [&](double scale) {
      return Vector3<double>(scale * sym(gen), scale * sym(gen), scale * sym(gen));
    };
    std::array<RawState, kStates> s{};
    for (auto& x : s) {
      // Shoemake, "Uniform random rotations", Graphics Gems III (1992).
      const double u1 = unit(gen), u2 = unit(gen), u3 = unit(gen);
      const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
      const double t2 = 2.0 * std::numbers::pi * u2, t3 = 2.0 * std::numbers::pi * u3;
      x.attitude = Eigen::Quaterniond(b * std::cos(t3), a * std::sin(t2), a * std::cos(t2),
                                      b * std::sin(t3));
      x.position = vec(1.0);
      x.velocity = vec(3.0);
      x.omega = vec(3.0);
      x.wrench.force = vec(10.0);
      x.wrench.moment = vec(2.0);
    }
    return s;
  }();
  return states;
}

/// The states in the coordinates of RigidBody<P, Ref>.
template <class Body> struct States {
  std::array<typename Body::Coords, kStates> q;
  std::array<typename Body::Coords, kStates> qdot;
  std::array<Wrench<double>, kStates> wrench;

  States() {
    using P = typename Body::Param;
    const auto& raw = raw_states();
    for (std::size_t i = 0; i < kStates; ++i) {
      const typename P::template Coords<double> th =
          P::canonical(P::from_quaternion(raw[i].attitude));
      q[i] << raw[i].position, th;
      qdot[i] = Body::qdot_from(q[i], raw[i].velocity, raw[i].omega);
      wrench[i] = raw[i].wrench;
    }
  }
};

/// The benchmark loop every case shares: f(i) for i cycling through the states; its result is
/// kept (DoNotOptimize) so that nothing is dead code, and memory is clobbered so that nothing is
/// cached across iterations.
template <class F> void run_cycling(benchmark::State& state, F&& f) {
  std::size_t i = 0;
  for (auto _ : state) {
    auto r = f(i);
    benchmark::DoNotOptimize(r);
    benchmark::ClobberMemory();
    i = (i + 1) & (kStates - 1);
  }
}

/// run_cycling with every call f makes inlined into the loop (`flatten`), whatever GCC's inlining
/// budget in the unit: for tumble's qddot cases, which table (a) compares with the hand-written
/// floor, so that tumble is timed inlined as the floor is (GCC 12 refused to inline
/// `RigidBody::accelerations_impl` by its size estimate, "max-inline-insns-single", and timed a
/// call; docs/benchmarks/floors.md, 2026-12-05). The floor stays in run_cycling: flattened it
/// took as long wrench given (33.9-36.2 against 30.8-40.0 ns) and longer with loads (56.9-58.4
/// against 37.3-49.5 ns), and the faster form is the floor. Only for these cases: flattening
/// every case of a unit took its compile from 1.5 to 10.5 minutes.
template <class F> [[gnu::flatten]] void run_cycling_inlined(benchmark::State& state, F&& f) {
  run_cycling(state, std::forward<F>(f));
}

/// Registers `fn` under `name`, timed in ns.
template <class F> void add(const std::string& name, F&& fn) {
  benchmark::RegisterBenchmark(name.c_str(), std::forward<F>(fn))->Unit(benchmark::kNanosecond);
}

[[nodiscard]] inline const char* ref_name(ReferencePoint r) {
  return r == ReferencePoint::centroid ? "centroid" : "offset";
}

/// Registration hooks of the translation units (micro/*.cpp, peers/*_micro.cpp); the optional
/// peers define theirs only when they are built (TUMBLE_BENCH_HAVE_PINOCCHIO,
/// TUMBLE_BENCH_HAVE_MUJOCO).
void register_tumble();
void register_baselines();
void register_jacobian();
void register_pinocchio();
void register_mujoco();

}  // namespace tumble::bench
