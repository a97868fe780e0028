// An open spatial chain of six rods on hinges about axes not all parallel (chain_reference.hpp
// states it): tumble's mechanism in absolute coordinates (chain_scene.hpp: 36 coordinates, 30
// constraint rows) against a second model written in the six joint angles by the recursive
// Newton-Euler algorithm, independent of tumble. Agreement of the two over a swing, and each
// keeping the energy, is the check that they are the same physics; study (e) of the main job
// measures tumble's integrators and its peers against the same second model
// (benchmarks/mechanisms/chain.cpp). The banded solve on chains: chain.test.cpp.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "chain_reference.hpp"
#include "chain_scene.hpp"
#include "support/catch.hpp"
#include "tumble/integrate.hpp"

namespace {

using chain_test::Chain;
using chain_test::TumbleChain;
using Eigen::Vector3d;
using L = long double;

/// Output times 0, dt, ..., t_end (s).
std::vector<double> output_times(double t_end, double dt) {
  std::vector<double> t;
  for (int k = 0; k * dt <= t_end + 1e-12; ++k) {
    t.push_back(k * dt);
  }
  return t;
}

}  // namespace

TEST_CASE("open spatial chain: tumble's start against the second model's", "[joint][chain]") {
  const TumbleChain c;
  const tumble::SceneState s0 = c.scene.initial_state();
  // Six rods of six coordinates, six hinges of five rows each, all independent: 6 degrees of
  // freedom, the joint angles. The start is placed on the constraints to rounding.
  const tumble::ConstraintResidual r = tumble::constraint_residual(c.scene, s0);
  CHECK(c.scene.constraint_count() == 30);
  CHECK(r.rank == 30);
  CHECK(r.position <= 1e-15);
  CHECK(r.velocity <= 1e-14);
  // The same tip, and the same energy summed two ways (tumble's observables, the second model's
  // joint-space kinematics).
  const Chain<L> second;
  const Chain<L>::State y0 = Chain<L>::start();
  const double e_second = static_cast<double>(second.energy(y0));
  INFO("E: tumble " << tumble::energy(c.scene, s0) << " J, second model " << e_second << " J");
  CHECK(std::abs(tumble::energy(c.scene, s0) - e_second) <= 1e-14 * std::abs(e_second));
  CHECK((c.tip(s0) - second.kinematics(y0).hinge.back().cast<double>()).norm() <= 1e-15);
}

TEST_CASE("open spatial chain: the front door against the second model", "[joint][chain]") {
  // The first 1.5 s (the chain's first swing back, every hinge moving), outputs every 0.05 s,
  // the second model at 1e-14 in long double.
  const std::vector<double> times = output_times(1.5, 0.05);
  const Chain<L> second;
  const std::vector<Chain<L>::State> ref =
      second.run(std::vector<L>(times.begin(), times.end()), 1e-14L);
  REQUIRE(ref.size() == times.size());
  const TumbleChain c;
  const double e0 = tumble::energy(c.scene, c.scene.initial_state());
  double tip = 0, centroid = 0, de = 0, closure = 0, travel = 0;
  std::size_t k = 0;
  const tumble::AutoStatistics st = tumble::integrate(
      c.scene, 0.0, times,
      [&](double, const tumble::SceneState& s) {
        const Chain<L>::Kinematics y = second.kinematics(ref[k]);
        const Vector3d p = y.hinge.back().cast<double>();
        tip = std::max(tip, (c.tip(s) - p).norm());
        for (std::size_t i = 0; i < c.rods.size(); ++i) {
          centroid = std::max(
              centroid,
              (tumble::position(c.scene, c.rods[i], s) - y.centroid[i].cast<double>()).norm());
        }
        de = std::max(de, std::abs(tumble::energy(c.scene, s) - e0));
        closure = std::max(closure, tumble::constraint_residual(c.scene, s).position);
        travel =
            std::max(travel, (p - second.kinematics(ref[0]).hinge.back().cast<double>()).norm());
        ++k;
      },
      {.rtol = 1e-11, .atol = 1e-11});
  INFO(tumble::name(st.choices.front().method)
       << ", " << st.steps << " steps: tip " << tip << " m, centroids " << centroid << " m, E - E0 "
       << de << " J of " << e0 << " J, |C| " << closure << " m, tip travel " << travel << " m");
  CHECK(k == times.size());
  CHECK(travel >= 0.5);  // the chain swings
  // At 1e-11 (measured: tip 2.8e-11 m, centroids 9.3e-12 m, E 9.1e-11 J of 37 J, |C| 1.6e-13 m;
  // Fehlberg 7(8), 178 steps).
  CHECK(tip <= 3e-10);
  CHECK(centroid <= 3e-10);
  CHECK(de <= 1e-9);
  CHECK(closure <= 1e-12);
}

TEST_CASE("open spatial chain: the second model keeps its energy", "[joint][chain]") {
  // Over study (e)'s 5 s: in long double at 1e-14 (the reference), and in double at 1e-12, which
  // stays near it (no chaos over the span: the two differ by about the looser tolerance).
  const std::vector<double> times = output_times(5.0, 0.05);
  const Chain<L> ld;
  const Chain<double> d;
  const std::vector<Chain<L>::State> ref =
      ld.run(std::vector<L>(times.begin(), times.end()), 1e-14L);
  const std::vector<Chain<double>::State> run = d.run(times, 1e-12);
  REQUIRE(ref.size() == times.size());
  REQUIRE(run.size() == times.size());
  const L e0 = ld.energy(ref[0]);
  double de_ref = 0, de = 0, tip = 0;
  for (std::size_t k = 0; k < times.size(); ++k) {
    de_ref = std::max(de_ref, static_cast<double>(std::abs(ld.energy(ref[k]) - e0)));
    de = std::max(de, std::abs(d.energy(run[k]) - static_cast<double>(e0)));
    tip = std::max(
        tip, (d.kinematics(run[k]).hinge.back() - ld.kinematics(ref[k]).hinge.back().cast<double>())
                 .norm());
  }
  // Measured: 2.2e-13 J and 3.5e-11 J of 37 J; 8.9e-12 m apart.
  INFO("E0 " << static_cast<double>(e0) << " J: long double E - E0 " << de_ref << " J, double "
             << de << " J; tip apart " << tip << " m");
  CHECK(de_ref <= 1e-12);
  CHECK(de <= 1e-10);
  CHECK(tip <= 1e-10);
}
