// tumble_bench, study (e): an open spatial chain (tests/joint/chain_reference.hpp states it): six
// rods of 0.3 m, 1 kg and 3 cm square section hinged end to end, the first to the ground, about
// axes that alternate between x and y with two oblique ones, swinging under gravity (9.81 m/s^2
// along -z) from a bent start with every hinge turning, for 5 s with 100 outputs (every 0.05 s).
// tumble's model is in absolute coordinates (tests/joint/chain_scene.hpp: 36 coordinates, 30
// rows). The reference is a second model in the six joint angles, written for the tests by the
// recursive Newton-Euler algorithm, independent of tumble and of the peers, integrated by
// Boost.Odeint's Fehlberg 7(8) at rtol = atol = 1e-14 in long double; its own error is estimated
// by the same at 1e-13. The error: the largest distance of the last rod's far end (the tip) from
// the reference's over the outputs (m). Beside tumble's rows: Pinocchio's aba in Odeint's
// Fehlberg 7(8) over the same tolerances, MuJoCo's RK4 and Exudyn's implicit solvers over their
// step ladders, each built from the same data (SpatialLinkage) and measured by the same `tip`.

#include <algorithm>
#include <array>
#include <cstddef>
#include <functional>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "common/format.hpp"
#include "joint/chain_reference.hpp"
#include "joint/chain_scene.hpp"
#include "mechanisms/mechanisms.hpp"
#include "mechanisms/run.hpp"
#include "mechanisms/track.hpp"
#include "tumble/integrate.hpp"

namespace tumble::bench {
namespace {

using L = long double;

/// The chain as the peers build it, from the second model's start: each rod's centroid,
/// attitude, velocity and mass properties (its frame at the centroid, as tumble's), hinge i at
/// p_i about u_i from rod i to rod i - 1 (the ground for i = 0) turning at theta_i', and the tip
/// at (0, 0, -L/2) of the last rod's frame.
SpatialLinkage peer_linkage() {
  namespace ct = chain_test;
  const ct::Chain<L> second;
  const ct::Chain<L>::State y0 = ct::Chain<L>::start();
  const ct::Chain<L>::Kinematics k = second.kinematics(y0);
  SpatialLinkage l;
  for (int i = 0; i < ct::data::n; ++i) {
    const auto ui = static_cast<std::size_t>(i);
    l.bodies.push_back({.centroid = k.centroid[ui].cast<double>(),
                        .rotation = k.rotation[ui].cast<double>(),
                        .mass = ct::data::mass,
                        .inertia = ct::rod_inertia<double>(),
                        .velocity = k.velocity[ui].cast<double>(),
                        .omega = k.omega[ui].cast<double>()});
    l.hinges.push_back({.a = i,
                        .b = i - 1,
                        .at = k.hinge[ui].cast<double>(),
                        .axis = k.axis[ui].cast<double>(),
                        .rate = static_cast<double>(y0[ui + ct::data::n])});
  }
  l.gravity = Eigen::Vector3d(0, 0, -ct::data::g);
  l.track_body = ct::data::n - 1;
  l.track_point = Eigen::Vector3d(0, 0, -0.5 * ct::data::length);
  return l;
}

}  // namespace

MechanismResult run_mechanism_chain(const MechanismPlan& plan, const std::function<void()>& step) {
  // The second model runs from t = 0 and gives its state at each time; the runs are measured at
  // the outputs after the start: 0.05, 0.1, ..., 5 s.
  std::vector<L> from_zero;
  for (int k = 0; k <= 100; ++k) {
    from_zero.push_back(L(0.05) * k);
  }
  const chain_test::Chain<L> second;
  const Stopwatch reference_watch;
  const std::vector<chain_test::Chain<L>::State> ref = second.run(from_zero, L(1e-14));
  const double reference_seconds = reference_watch.wall();
  // Its own error, estimated by the second model at 1e-13 (ten times looser).
  const std::vector<chain_test::Chain<L>::State> looser = second.run(from_zero, L(1e-13));
  std::vector<double> times;
  std::vector<Eigen::Vector3d> tips;
  double uncertainty = 0;
  for (std::size_t k = 1; k < ref.size(); ++k) {
    times.push_back(static_cast<double>(from_zero[k]));
    const Eigen::Matrix<L, 3, 1> p = second.kinematics(ref[k]).hinge.back();
    tips.push_back(p.cast<double>());
    uncertainty = std::max(
        uncertainty, static_cast<double>((second.kinematics(looser[k]).hinge.back() - p).norm()));
  }

  const chain_test::TumbleChain chain;
  PointTrackError tip(std::move(tips));
  auto record = [&](std::size_t k, const SceneState& s) { tip.record(k, chain.tip(s)); };
  auto measure = [&] { return tip.measure(); };
  MechanismResult r;
  r.id = "chain";
  r.title = "An open spatial chain: 6 rods of 0.3 m and 1 kg, 6 hinges about axes not all "
            "parallel, swinging under gravity, 5 s";
  r.measure = "max |tip - tip_ref| of the last rod's far end over 100 outputs, every 0.05 s (m)";
  r.reference = "a second model in the 6 joint angles (recursive Newton-Euler), Fehlberg 7(8) at "
                "1e-14 in long double (" +
                duration(reference_seconds) + "); at 1e-13 it is " + sci(uncertainty) +
                " m from it: errors near that are not resolved";
  r.rows = mechanism_sweep(plan, chain.scene, times, record, measure, step);
  // The peers, when installed: the same linkage, output times and `tip`.
  const SpatialLinkage l = peer_linkage();
  const auto add = [&](const std::vector<MechanismRow>& peer) {
    r.rows.insert(r.rows.end(), peer.begin(), peer.end());
  };
  if (runs_peer(plan, "Pinocchio")) {
    add(pinocchio_chain_rows(l, times, plan.tolerances, tip, plan.timing));
  }
  if (runs_peer(plan, "MuJoCo")) {
    add(mujoco_spatial_rows(l, times, tip, plan.timing));
  }
  if (runs_peer(plan, "Exudyn")) {
    add(exudyn_chain_rows(l, times, tip, plan.timing));
  }
  return r;
}

}  // namespace tumble::bench
