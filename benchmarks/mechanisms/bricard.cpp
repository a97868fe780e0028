// tumble_bench, study (e): IFToMM A04, Bricard's mechanism (examples/bricard.cpp): five rods of
// 1 m and 1 kg and six hinges in a closed loop along edges of the unit cube, 30 constraint rows
// of rank 29 (redundant by Gruebler's count, mobile in fact), released at rest under gravity for
// the benchmark's 10 s, 200 outputs (every 0.05 s). There is no closed form: the reference is a
// run at tight tolerance, OdeintIntegrator's Fehlberg 7(8) at rtol = atol = 1e-13 on the
// non-redundant twin of the example (the hinge at P5 made a universal joint: 29 independent
// rows, the same motion), so it shares tumble's equations but not the redundant row's handling.
// The error: the largest distance of P3 (the tip of the middle rod) from the reference's over the
// outputs (m); errors near the reference's own (estimated by the twin at 1e-12, reported) are
// not resolved.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "common/format.hpp"
#include "mechanisms/mechanisms.hpp"
#include "mechanisms/run.hpp"
#include "tumble/integrate.hpp"

#define main tumble_bench_bricard_example_main  // the example's program: not run here
#include "../../examples/bricard.cpp"           // NOLINT(bugprone-suspicious-include)
#undef main

namespace tumble::bench {
namespace {

/// The linkage as the peers build it (mechanisms.hpp, SpatialLinkage), from the example's scene
/// at the start: each rod's centroid, attitude and mass properties; its ends at -+0.5 m along
/// its body x (as the example's joints hold them), so P0..P5; the hinge at P_k perpendicular to
/// the two links that meet there (the ground's link P5 P0 among them); P3 the middle rod's tip.
SpatialLinkage peer_linkage(const bricard::Bricard<>& six) {
  using Eigen::Vector3d;
  const SceneState s0 = six.scene.initial_state();
  SpatialLinkage l;
  std::vector<Vector3d> p;  // P0 .. P5
  for (const auto& rod : six.rods) {
    const auto& mp = six.scene.body(rod).mass_properties();
    const Eigen::Matrix3d r = rotation(six.scene, rod, s0);
    const Vector3d x = position(six.scene, rod, s0);
    l.bodies.push_back({.centroid = x + r * mp.centroid(),
                        .rotation = r,
                        .mass = mp.mass(),
                        .inertia = mp.inertia_centroid()});
    p.push_back(x - r * Vector3d(0.5, 0, 0));
    if (p.size() == six.rods.size()) {
      p.push_back(x + r * Vector3d(0.5, 0, 0));
    }
  }
  const int n = static_cast<int>(six.rods.size());
  for (int k = 0; k <= n; ++k) {
    const auto at = static_cast<std::size_t>(k);
    const Vector3d before = k == 0 ? p[0] - p[static_cast<std::size_t>(n)] : p[at] - p[at - 1];
    const Vector3d after = k == n ? p[0] - p[at] : p[at + 1] - p[at];
    l.hinges.push_back({.a = k == n ? n - 1 : k,
                        .b = k == 0 || k == n ? -1 : k - 1,
                        .at = p[at],
                        .axis = before.cross(after).normalized()});
  }
  const auto& g = bricard::Bricard<>::kGravity;
  l.gravity = Vector3d(g[0], g[1], g[2]);
  l.track_body = 2;
  l.track_point = Vector3d(0.5, 0, 0);
  return l;
}

}  // namespace

MechanismResult run_mechanism_a04(const MechanismPlan& plan, const std::function<void()>& step) {
  using Eigen::Vector3d;
  std::vector<double> times;
  for (int k = 1; k <= 200; ++k) {
    times.push_back(0.05 * k);
  }
  // The reference: the twin at 1e-13.
  const Stopwatch reference_watch;
  const bricard::Bricard<Universal> twin;
  std::vector<Vector3d> reference;
  reference.reserve(times.size());
  OdeintOptions tight;
  tight.rtol = 1e-13;
  tight.atol = 1e-13;
  OdeintIntegrator<bricard::Bricard<Universal>::SceneT> integrator(twin.scene, 0.0, tight);
  integrator.integrate(times,
                       [&](double, const SceneState& s) { reference.push_back(twin.p3(s)); });
  const double reference_seconds = reference_watch.wall();
  // Its own error, estimated by the twin at 1e-12 (ten times looser).
  double uncertainty = 0;
  {
    OdeintOptions looser = tight;
    looser.rtol = 1e-12;
    looser.atol = 1e-12;
    OdeintIntegrator<bricard::Bricard<Universal>::SceneT> check(twin.scene, 0.0, looser);
    std::size_t k = 0;
    check.integrate(times, [&](double, const SceneState& s) {
      uncertainty = std::max(uncertainty, (twin.p3(s) - reference[k++]).norm());
    });
  }

  const bricard::Bricard<> six;
  PointTrackError p3(std::move(reference));
  auto record = [&](std::size_t k, const SceneState& s) { p3.record(k, six.p3(s)); };
  auto measure = [&] { return p3.measure(); };
  MechanismResult r;
  r.id = "a04";
  r.title = "IFToMM A04, Bricard's mechanism: 5 rods, 6 hinges, 30 rows of rank 29 (redundant), "
            "under gravity, 10 s";
  r.measure = "max |P3 - P3_ref| of the middle rod's tip over 200 outputs (m)";
  r.reference = "no closed form: a run at tight tolerance, OdeintIntegrator F78 at 1e-13 on the "
                "non-redundant twin (a universal joint at P5), " +
                duration(reference_seconds) + "; the twin at 1e-12 is " + sci(uncertainty) +
                " m from it: errors near that are not resolved";
  r.rows = mechanism_sweep(plan, six.scene, times, record, measure, step);
  // MuJoCo, when installed: the same linkage (five hinges its tree, the sixth two <connect>s),
  // output times and `p3`.
  if (runs_peer(plan, "MuJoCo")) {
    const std::vector<MechanismRow> peer =
        mujoco_spatial_rows(peer_linkage(six), times, p3, plan.timing);
    r.rows.insert(r.rows.end(), peer.begin(), peer.end());
  }
  // Exudyn, when installed: the same six hinges (redundant), outputs and `p3`.
  if (runs_peer(plan, "Exudyn")) {
    const std::vector<MechanismRow> exudyn =
        exudyn_a04_rows(peer_linkage(six), times, p3, plan.timing);
    r.rows.insert(r.rows.end(), exudyn.begin(), exudyn.end());
  }
  return r;
}

}  // namespace tumble::bench
