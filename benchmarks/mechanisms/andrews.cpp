// tumble_bench, study (e): IFToMM A03, Andrews' squeezing mechanism (examples/andrews.cpp: seven
// planar links in absolute coordinates, 42 coordinates, 50 constraint rows of rank 41, a spring
// and a motor), from rest to t = 0.03 s with outputs every 0.3 ms, as the andrews tests run it.
// The reference is the tests' second model (tests/joint/andrews_reference.hpp): the Test Set's
// seven joint angles with six loop-closure constraints, integrated by Fehlberg 7(8) in long
// double to 1e-17. The error measure is the andrews tests': the seven angles at 0.03 s, the
// largest |q - q_ref| / (1 + |q_ref|) (the Test Set's mixed measure; |q_ref| up to 15.8 rad).
// The Test Set's published reference (RADAU5) is itself 1.1e-9 rad off in beta (reported beside
// the table): errors below that are measured against the second model only.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "common/format.hpp"
#include "mechanisms/mechanisms.hpp"
#include "mechanisms/run.hpp"
#include "tumble/integrate.hpp"

#define main tumble_bench_andrews_example_main  // the example's program: not run here
#include "../../examples/andrews.cpp"           // NOLINT(bugprone-suspicious-include)
#undef main

#include "joint/andrews_reference.hpp"

namespace tumble::bench {
namespace {

/// The mechanism as the peers build it (mechanisms.hpp, PlanarLinkage): the example's links as a
/// tree from the ground (O-crank-rod FE, B-triangle, A-link AG-rod EG, A-link AH-rod EH) and the
/// three hinges at E that close its loops; the points from the Test Set's data, the centroids
/// from the example's scene at the start.
PlanarLinkage peer_linkage(const andrews::Andrews<>& m) {
  using Eigen::Vector2d;
  namespace a = andrews;
  const a::Angles angle = a::absolute(a::kStart);
  const auto turn = [&](int i, double x, double y) {
    return Vector2d(std::cos(angle[i]) * x - std::sin(angle[i]) * y,
                    std::sin(angle[i]) * x + std::cos(angle[i]) * y);
  };
  const Vector2d O(0, 0), A(a::xa, a::ya), B(a::xb, a::yb), C(a::xc, a::yc);
  const Vector2d F = turn(0, a::rr, 0), E = F + turn(1, -a::d, 0);
  const Vector2d G = A + turn(4, a::zt, 0), H = A + turn(6, 0, -a::u);
  const std::array<int, 7> parent{-1, 0, -1, 4, -1, 6, -1};
  const std::array<Vector2d, 7> hinge{O, F, B, G, A, H, A};
  const SceneState s0 = m.scene.initial_state();
  PlanarLinkage l;
  for (std::size_t i = 0; i < 7; ++i) {
    l.links.push_back({.parent = parent[i],
                       .hinge = hinge[i],
                       .centroid = position(m.scene, m.links[i], s0).head<2>(),
                       .angle = angle[i],
                       .mass = a::kMass[i],
                       .inertia = a::kInertia[i]});
  }
  l.loops = {{.a = 1, .b = 2, .at = E}, {.a = 1, .b = 3, .at = E}, {.a = 1, .b = 5, .at = E}};
  l.spring_link = 2;
  l.spring_on_link = B + turn(2, a::sd, -a::sc);  // D
  l.spring_on_ground = C;
  l.stiffness = a::c0;
  l.rest_length = a::l0;
  l.motor_link = 0;
  l.torque = a::mom;
  return l;
}

}  // namespace

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
  // MuJoCo, when installed: the same output times, the links' absolute angles at the last one
  // measured by the same mixed measure against the same q_ref. Exudyn likewise.
  const PlanarMeasure peer_measure = [&](const std::vector<std::vector<double>>& angles) {
    andrews::Angles last{};
    std::copy(angles.back().begin(), angles.back().end(), last.begin());
    return andrews::mixed_error(andrews::relative(last), q_ref);
  };
  const PlanarLinkage linkage = peer_linkage(m);
  if (runs_peer(plan, "MuJoCo")) {
    const std::vector<MechanismRow> peer =
        mujoco_planar_rows("a03", linkage, times, peer_measure, plan.timing);
    r.rows.insert(r.rows.end(), peer.begin(), peer.end());
  }
  // Exudyn, when installed: the same linkage, outputs and measure.
  if (runs_peer(plan, "Exudyn")) {
    const std::vector<MechanismRow> exudyn =
        exudyn_planar_rows("a03", linkage, times, peer_measure, plan.timing);
    r.rows.insert(r.rows.end(), exudyn.begin(), exudyn.end());
  }
  return r;
}

}  // namespace tumble::bench
