// tumble_bench, study (e): IFToMM A01, the simple pendulum, as tests/joint/iftomm.test.cpp models
// it: a point mass of 1 kg (a small ball, inertia 4e-5 kg m^2, whose centre hangs on a Distance
// joint of 1 m from the origin: a massless bar with spherical ends) under gravity 9.81 m/s^2
// along -y, released at rest at x = +1 m, for 10 s with 40 outputs (every 0.25 s; the test's
// 400, every 0.025 s, cut Fehlberg's steps to one per output at every tolerance from 1e-4 to
// 1e-11, 1.2e-11 m each: the outputs, not the tolerance, decided the work). The
// reference is the closed form (tests/support/pendulum.hpp): theta(t) = 2 asin(k sn(K - w0 t |
// k^2)), k = sin(pi / 4), w0 = sqrt(g / l), and the bob at (sin theta, -cos theta, 0). The error:
// the largest distance of the bob from the exact position over the outputs (m).

#include "support/pendulum.hpp"

#include <cmath>
#include <cstddef>
#include <functional>
#include <numbers>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "mechanisms/mechanisms.hpp"
#include "mechanisms/run.hpp"
#include "tumble/integrate.hpp"

namespace tumble::bench {

MechanismResult run_mechanism_a01(const MechanismPlan& plan, const std::function<void()>& step) {
  using Eigen::Matrix3d;
  using Eigen::Vector3d;
  constexpr double g = 9.81;
  // The data, as the peers get it too (Exudyn builds its model from it).
  const BarPendulum data{.mass = 1.0,
                         .inertia = 4e-5,
                         .pivot = Vector3d::Zero(),
                         .start = Vector3d(1, 0, 0),
                         .gravity = Vector3d(0, -g, 0)};
  using Ball = RigidBody<EulerParameters>;
  Mechanism<Bodies<Ball>, Joints<Distance>, Loads<UniformGravity>> scene;
  const auto ball = scene.add(
      Ball(MassProperties<>::about_centroid(data.mass, Matrix3d::Identity() * data.inertia)),
      {.position = data.start});
  scene.add_load(ball, UniformGravity(data.gravity));
  scene.add_joint(ball, ground,
                  Distance(Vector3d::Zero(), data.pivot, (data.start - data.pivot).norm()));

  std::vector<double> times;
  std::vector<Vector3d> exact;
  const double theta0 = std::numbers::pi / 2, w0 = std::sqrt(g);
  for (int i = 1; i <= 40; ++i) {
    times.push_back(0.25 * i);
    const double theta = test::pendulum_angle(theta0, w0, times.back());
    exact.emplace_back(std::sin(theta), -std::cos(theta), 0.0);
  }
  PointTrackError bob(std::move(exact));
  auto record = [&](std::size_t k, const SceneState& s) {
    bob.record(k, position(scene, ball, s));
  };
  auto measure = [&] { return bob.measure(); };
  MechanismResult r;
  r.id = "a01";
  r.title = "IFToMM A01, the simple pendulum: a 1 kg point mass on a massless 1 m bar (Distance "
            "joint), released horizontally, 10 s";
  r.measure = "max |r - r_exact| of the bob over 40 outputs, every 0.25 s (m)";
  r.reference = "closed form, theta(t) = 2 asin(k sn(K - w0 t | k^2))";
  r.rows = mechanism_sweep(plan, scene, times, record, measure, step);
  // MuJoCo, when installed: the same output times, measured by the same `bob`.
  if (runs_peer(plan, "MuJoCo")) {
    const std::vector<MechanismRow> peer = mujoco_a01_rows(times, bob, plan.timing);
    r.rows.insert(r.rows.end(), peer.begin(), peer.end());
  }
  // Exudyn, when installed: its model from `data`, the same output times, the same `bob`.
  if (runs_peer(plan, "Exudyn")) {
    const std::vector<MechanismRow> exudyn = exudyn_a01_rows(data, times, bob, plan.timing);
    r.rows.insert(r.rows.end(), exudyn.begin(), exudyn.end());
  }
  return r;
}

}  // namespace tumble::bench
