// tumble_bench, study (e): IFToMM A05, the stiff flyball governor (examples/flyball.cpp): a
// spinning shaft, a slider on it and two rods with balls hinged to both, held by two stiff
// spring-dampers (8e5 N/m, 4e4 N s/m), for the benchmark's 10 s with outputs every 0.05 s. The
// reference is the tests' second model in minimal coordinates (psi, s, beta_1, beta_2;
// tests/joint/flyball_reference.hpp), integrated by Odeint's Fehlberg 7(8) at 1e-12. The error:
// the largest distance of the slider's height s from the reference's over the 200 outputs (m),
// the quantity the benchmark asks for. The dampers make the scene stiff: the front door chooses
// BDF with the exact Jacobian, and Fehlberg 7(8) at loose tolerances is held at its stability
// bound (or throws StiffSceneError, a failed row). When SUNDIALS' IDA is found, the rows of a
// study of the index-2 formulation in IDA (mechanisms/ida_ggl.hpp) join them.

#include <cstddef>
#include <functional>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "common/format.hpp"
#include "mechanisms/mechanisms.hpp"
#if TUMBLE_BENCH_HAVE_IDA
#include "mechanisms/ida_ggl.hpp"
#endif
#include "mechanisms/run.hpp"
#include "mechanisms/track.hpp"
#include "tumble/integrate.hpp"

#define main tumble_bench_flyball_example_main  // the example's program: not run here
#include "../../examples/flyball.cpp"           // NOLINT(bugprone-suspicious-include)
#undef main

#include "joint/flyball_reference.hpp"

namespace tumble::bench {

MechanismResult run_mechanism_a05(const MechanismPlan& plan, const std::function<void()>& step) {
  // The second model runs from the first time it is given (t = 0) and gives its state at each;
  // tumble's runs are measured at the outputs after the start: 0.05, 0.1, ..., 10 s.
  std::vector<double> times = flyball::output_times();
  const Stopwatch reference_watch;
  const std::vector<flyball_test::Minimal::State> second = flyball_test::Minimal{}.run(times);
  const double reference_seconds = reference_watch.wall();
  times.erase(times.begin());
  // The slider's height as a point on a line, so that the shared measure takes it.
  std::vector<Eigen::Vector3d> heights;
  heights.reserve(times.size());
  for (std::size_t k = 1; k < second.size(); ++k) {
    heights.emplace_back(second[k][1], 0.0, 0.0);
  }
  const flyball::Governor g;
  PointTrackError slider(std::move(heights));
  auto record = [&](std::size_t k, const SceneState& s) {
    slider.record(k, Eigen::Vector3d(g.s(s), 0.0, 0.0));
  };
  auto measure = [&] { return slider.measure(); };
  MechanismResult r;
  r.id = "a05";
  r.title = "IFToMM A05, the stiff flyball governor: shaft, slider, 2 rods with balls, 2 stiff "
            "spring-dampers, 10 s";
  r.measure = "max |s - s_ref| of the slider's height over 200 outputs, every 0.05 s (m)";
  r.reference = "a second model in the 4 minimal coordinates (Lagrange's equations), Fehlberg "
                "7(8) at 1e-12 (" +
                duration(reference_seconds) + ")";
  r.rows = mechanism_sweep(plan, g.scene, times, record, measure, step);
#if TUMBLE_BENCH_HAVE_IDA
  // The study of a stabilized index-2 formulation in SUNDIALS IDA (the alternative to BDF for
  // stiff mechanisms, docs/mechanisms.md), on the same outputs and measured by the same `slider`.
  const std::vector<MechanismRow> ida = ida_ggl_rows(plan, g.scene, times, record, measure);
  r.rows.insert(r.rows.end(), ida.begin(), ida.end());
#endif
  // MuJoCo, when installed: its model from the example's data, measured by the same `slider`.
  using namespace flyball;
  const FlyballGovernor data{
      .gravity = kG,
      .shaft_mass = kBarMass,
      .shaft_length = kBar,
      .shaft_inertia = Eigen::Vector3d(kBarMass * (kBar * kBar + kSide * kSide) / 12,
                                       kBarMass * (kBar * kBar + kSide * kSide) / 12,
                                       kBarMass * 2 * kSide * kSide / 12),
      .slider_mass = kCubeMass,
      .slider_inertia = kCubeMass * 2 * kCube * kCube / 12,
      .rod_mass = kRodMass,
      .rod_length = kBar,
      .rod_centroid = kRodCentroid,
      .rod_axial = kRodAxial,
      .rod_transverse = kRodTransverse,
      .offset = kOffset,
      .top = kBar,
      .stiffness = kK,
      .damping = kC,
      .rest_length = kRest,
      .s0 = kS0,
      .alpha = kAlpha,
      .spin = kSpin};
  if (runs_peer(plan, "MuJoCo")) {
    const std::vector<MechanismRow> peer = mujoco_a05_rows(data, times, slider, plan.timing);
    r.rows.insert(r.rows.end(), peer.begin(), peer.end());
  }
  // Exudyn, when installed: the same data, outputs and `slider`.
  if (runs_peer(plan, "Exudyn")) {
    const std::vector<MechanismRow> peer = exudyn_a05_rows(data, times, slider, plan.timing);
    r.rows.insert(r.rows.end(), peer.begin(), peer.end());
  }
  return r;
}

}  // namespace tumble::bench
