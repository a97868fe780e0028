// tumble_bench, study (e): IFToMM A02, the N-four-bar, as tests/joint/iftomm.test.cpp models it
// (tests/joint/n_four_bar_reference.hpp, NFourBar): N = 2, so 3 cranks hinged to the ground at
// x = 0, 1, 2 m and 2 couplers joining their tips, every link a 1 m, 1 kg rod of 1 cm square
// section, under gravity 9.81 m/s^2 along -y. The benchmark's own start: the cranks up (+y), B0
// (the first crank's tip) moving at 1 m/s along +x, the couplers translating with the tips; for
// 10 s with 100 outputs, every 0.1 s. The motion has one degree of freedom (the cranks stay
// parallel) and turns the cranks through their singular position (every link on the ground
// line, N + 1 degrees of freedom for an instant) twice per turn: theta reaches 31.8 rad at 10 s,
// 10 crossings.
// The reference is the tests' second model in the cranks' angle theta (from +y towards +x):
// I_eff theta'' = G sin theta, integrated by Odeint's Fehlberg 7(8) at 1e-13. The error: the
// largest |theta - theta_ref| over the outputs (rad, modulo 2 pi), theta read off the first
// crank's body x axis as the test reads it. Near the crossings the constraint solve is
// ill-conditioned; tumble's runs may fail there at tight tolerances (stopped by the stiffness
// test, or an ExplicitIntegrationError), which the sweep records as failed rows
// (iftomm.test.cpp's notes give the test's measurements).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <numbers>
#include <vector>

#include <Eigen/Core>

#include "common/format.hpp"
#include "joint/n_four_bar_reference.hpp"
#include "mechanisms/mechanisms.hpp"
#include "mechanisms/run.hpp"
#include "tumble/integrate.hpp"

namespace tumble::bench {
namespace {

constexpr int kN = 2;  // as the A02 test through the singular positions (iftomm.test.cpp)

/// The mechanism as the peers build it (mechanisms.hpp, PlanarLinkage), read off the scene's
/// starting state: the cranks as links from the ground (each hinged at its lower end), each
/// coupler hanging from its crank's tip and closed onto the next crank's tip by a loop hinge;
/// the rates are the bodies' (omega about z: -1 rad/s on the cranks, 0 on the couplers).
PlanarLinkage peer_linkage(const n_four_bar_test::NFourBar& m) {
  const SceneState s0 = m.scene.initial_state();
  PlanarLinkage l;
  l.gravity = Eigen::Vector2d(0, -n_four_bar_test::data::g);
  // A link from body b: its centroid, its angle (of its body x axis, along the rod), its ends.
  // In scalars: GCC 12 at -O3 reports the packet loads of Eigen::Vector2d expressions here as
  // maybe uninitialized (a false positive, where this lambda is inlined).
  const auto link = [&](BodyId<n_four_bar_test::Bar> b, int parent) {
    const Eigen::Vector3d p = position(m.scene, b, s0);
    const Eigen::Matrix3d r = rotation(m.scene, b, s0);
    const double half = 0.5 * n_four_bar_test::data::length, ux = r(0, 0), uy = r(1, 0);
    const auto& mp = m.scene.body(b).mass_properties();
    l.links.push_back({.parent = parent,
                       .hinge = Eigen::Vector2d(p.x() - half * ux, p.y() - half * uy),
                       .centroid = Eigen::Vector2d(p.x(), p.y()),
                       .angle = std::atan2(uy, ux),
                       .mass = mp.mass(),
                       .inertia = mp.inertia_centroid()(2, 2),
                       .rate = omega(m.scene, b, s0).z()});
    return Eigen::Vector2d(p.x() + half * ux, p.y() + half * uy);  // the far end
  };
  for (const auto crank : m.cranks) {
    link(crank, -1);
  }
  for (std::size_t i = 0; i < m.couplers.size(); ++i) {
    const Eigen::Vector2d tip = link(m.couplers[i], int(i));
    l.loops.push_back({.a = int(l.links.size()) - 1, .b = int(i) + 1, .at = tip});
  }
  return l;
}

}  // namespace

MechanismResult run_mechanism_a02(const MechanismPlan& plan, const std::function<void()>& step) {
  std::vector<double> times, theta_ref;
  const Stopwatch reference_watch;
  for (int k = 1; k <= 100; ++k) {
    times.push_back(0.1 * k);
    theta_ref.push_back(n_four_bar_test::crank_angle(kN, false, times.back()));
  }
  const double reference_seconds = reference_watch.wall();
  const n_four_bar_test::NFourBar m(kN, false);

  // The first crank's angle at every output (NaN: not reached), kept for the measure.
  std::vector<double> theta(times.size(), std::numeric_limits<double>::quiet_NaN());
  auto record = [&](std::size_t k, const SceneState& s) { theta[k] = m.crank_angle(s); };
  auto measure = [&] {
    const double e = n_four_bar_test::crank_angle_error(theta, theta_ref);
    std::fill(theta.begin(), theta.end(), std::numeric_limits<double>::quiet_NaN());
    return e;
  };
  MechanismResult r;
  r.id = "a02";
  r.title = "IFToMM A02, the N-four-bar (N = 2): 3 cranks, 2 couplers, 7 hinges, under gravity, "
            "cranks up and B0 at 1 m/s, 10 s (singular twice per turn)";
  r.measure = "max |theta - theta_ref| of the first crank's angle over 100 outputs, every 0.1 s "
              "(rad)";
  r.reference = "a second model in the cranks' angle, I_eff theta'' = G sin theta, Fehlberg "
                "7(8) at 1e-13 (" +
                duration(reference_seconds) + ")";
  r.rows = mechanism_sweep(plan, m.scene, times, record, measure, step);
  // The peers, when installed: the same linkage, output times and measure, the first crank's
  // absolute angle phi (from +x, anticlockwise) read as theta = pi/2 - phi.
  const PlanarMeasure peer_measure = [&](const std::vector<std::vector<double>>& angles) {
    std::vector<double> first;
    for (const std::vector<double>& a : angles) {
      first.push_back(std::numbers::pi / 2 - a[0]);
    }
    return n_four_bar_test::crank_angle_error(first, theta_ref);
  };
  const PlanarLinkage linkage = peer_linkage(m);
  if (runs_peer(plan, "MuJoCo")) {
    const std::vector<MechanismRow> peer =
        mujoco_planar_rows("a02", linkage, times, peer_measure, plan.timing);
    r.rows.insert(r.rows.end(), peer.begin(), peer.end());
  }
  if (runs_peer(plan, "Exudyn")) {
    const std::vector<MechanismRow> exudyn =
        exudyn_planar_rows("a02", linkage, times, peer_measure, plan.timing);
    r.rows.insert(r.rows.end(), exudyn.begin(), exudyn.end());
  }
  return r;
}

}  // namespace tumble::bench
