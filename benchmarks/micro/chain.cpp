// The cost of a mechanism's right-hand side and of its projection against the number of bodies:
// a chain of n links hinged end to end (Revolute joints about random axes, the first to the
// ground), n from 1 to 10^4. The constraint solve is banded for a chain of 3 or more, so both
// should grow linearly: micro/summarize.py reports the slope of log(time) against log(n) from 100
// to 10^4 bodies (target <= 1.05).

#include <cmath>
#include <random>
#include <vector>

#include <benchmark/benchmark.h>

#include "tumble/tumble.hpp"

namespace {

using Link = tumble::RigidBody<tumble::EulerParameters>;
using Chain = tumble::Mechanism<tumble::Bodies<Link>, tumble::Joints<tumble::Revolute>,
                                tumble::Loads<tumble::UniformGravity>>;

/// n links of 0.1 m down z, each swinging, joined by hinges about random axes; on the joints.
struct ChainCase {
  Chain scene;
  tumble::SceneState state;
  explicit ChainCase(int n) {
    std::mt19937_64 gen(20261126);
    std::normal_distribution<double> normal;
    const auto random3 = [&] { return Eigen::Vector3d(normal(gen), normal(gen), normal(gen)); };
    const double l = 0.1, s = 0.01, m = 1.0;
    const Eigen::Vector3d top(0, 0, 0.5 * l);
    const Link link(tumble::MassProperties<>::about_centroid(
        m, Eigen::Vector3d(m * (l * l + s * s) / 12, m * (l * l + s * s) / 12, m * s * s / 6)
               .asDiagonal()));
    std::vector<tumble::BodyId<Link>> ids;
    for (int k = 0; k < n; ++k) {
      ids.push_back(scene.add(
          link, {.position = Eigen::Vector3d(0, 0, -(k + 0.5) * l), .omega = 0.5 * random3()}));
      scene.add_load(ids.back(), tumble::UniformGravity(Eigen::Vector3d(0, 0, -9.81)));
      const Eigen::Vector3d axis = random3().normalized();
      if (k == 0) {
        scene.add_joint(ids[0], tumble::ground,
                        tumble::Revolute(top, axis, Eigen::Vector3d::Zero(), axis));
      } else {
        scene.add_joint(ids[static_cast<std::size_t>(k)], ids[static_cast<std::size_t>(k - 1)],
                        tumble::Revolute(top, axis, -top, axis));
      }
    }
    state = scene.initial_state();
    tumble::assemble(scene, state);
  }
};

void BM_ChainRhs(benchmark::State& st) {
  const int n = static_cast<int>(st.range(0));
  const ChainCase c(n);
  tumble::SceneWorkspace<Chain> ws(c.scene);
  Eigen::VectorXd ydot(c.scene.size());
  for (auto _ : st) {
    tumble::rhs(c.scene, ws, 0.0, c.state, ydot);
    benchmark::DoNotOptimize(ydot.data());
    benchmark::ClobberMemory();
  }
  st.counters["bodies"] = n;
  st.counters["ns_per_body"] =
      benchmark::Counter(static_cast<double>(n), benchmark::Counter::kIsIterationInvariantRate |
                                                     benchmark::Counter::kInvert);
}

void BM_ChainProjection(benchmark::State& st) {
  const int n = static_cast<int>(st.range(0));
  const ChainCase c(n);
  tumble::SceneWorkspace<Chain> ws(c.scene);
  Eigen::VectorXd y = c.state.y;
  std::mt19937_64 gen(1);
  std::normal_distribution<double> normal;
  Eigen::VectorXd noise(y.size());
  for (Eigen::Index i = 0; i < y.size(); ++i) {
    noise(i) = 1e-9 * normal(gen);  // what a step leaves: the local error
  }
  for (auto _ : st) {
    st.PauseTiming();
    y = c.state.y + noise;
    st.ResumeTiming();
    int iterations = 0;
    const auto r = tumble::detail::project_constraints(
        c.scene, ws, y, std::span<const Eigen::Matrix3d>(c.state.base), 1e-13, 8,
        [](int) { return true; }, iterations);
    benchmark::DoNotOptimize(r);
  }
  st.counters["bodies"] = n;
}

}  // namespace

// Names chain_rhs/<n> and chain_projection/<n> (micro/summarize.py reads the slope from them).
// 3 and 6 links as well: below 4 (bandwidth + 1) <= rows, where a chain took the dense solve
// until 2026-11-28 (docs/benchmarks/mechanisms.md).
BENCHMARK(BM_ChainRhs)
    ->Name("chain_rhs")
    ->RangeMultiplier(10)
    ->Range(1, 10000)
    ->Arg(3)
    ->Arg(6)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ChainProjection)
    ->Name("chain_projection")
    ->RangeMultiplier(10)
    ->Range(1, 10000)
    ->Unit(benchmark::kMicrosecond);
