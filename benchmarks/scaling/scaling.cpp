// tumble_bench: the scaling study. A chain of N bodies (Euler parameters, framed at their
// centroids) joined end to end by spring-dampers (SpringDamperBetween), the first one hung from a
// fixed point by a SpringDamper, so that every body carries exactly one spring whatever N is.
// Measured:
//  - the cost of one right-hand side (tumble::rhs) per body, for N = 1 ... 10,000: the scene loops
//    over bodies and loads with the types known at compile time, so this should be flat in N;
//  - the cost of one BDF step (construction of the integrator and the first `bdf_steps` steps,
//    divided by the steps) with CVODE's dense LU (an O(N^3) factorization), its band LU (the
//    chain couples body i only to i - 1 and i + 1, so with 14 state entries per body the Jacobian
//    has half-bandwidths 2 * 14 - 1 = 27 whatever N is, which SceneIntegrator takes from
//    Scene::half_bandwidth: an O(N) factorization), and matrix-free GMRES (difference-quotient
//    J v products, with the scene's block-Jacobi preconditioner, one LU of I - gamma J_kk per
//    body). Dense and band use the scene's exact Jacobian (tumble::jacobian, automatic
//    differentiation, O(N)); the band LU is also run with CVODE's banded difference quotients
//    ("bdf-band-dq", use_system_jacobian = false: 55 right-hand sides per Jacobian), the cost
//    before the scene had a Jacobian. By difference quotients the dense Jacobian would cost N
//    right-hand sides of N bodies.

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "common/bench.hpp"
#include "tumble/cvode.hpp"

namespace tumble::bench {

namespace {

using Link = RigidBody<EulerParameters>;
using Chain = Scene<Bodies<Link>, Loads<SpringDamper, SpringDamperBetween>>;

/// Builds the chain of n bodies along x, at rest length, with deterministic small velocities
/// and angular velocities (a formula rather than a random generator: the same on every
/// platform).
void build_chain(Chain& chain, int n) {
  const MassProperties<> mp =
      MassProperties<>::about_centroid(1.0, Eigen::Vector3d(0.02, 0.06, 0.07).asDiagonal());
  const SpringDamperParameters spring{.stiffness = 100.0, .damping = 0.5, .rest_length = 0.2};
  BodyId<Link> previous{};
  for (int i = 0; i < n; ++i) {
    const double x = i;
    const BodyId<Link> id =
        chain.add(Link(mp), {.position = {x, 0.0, 0.0},
                             .velocity = 0.1 * Eigen::Vector3d(std::sin(1.3 * x), std::cos(0.7 * x),
                                                               std::sin(2.1 * x + 0.5)),
                             .omega = 0.5 * Eigen::Vector3d(std::cos(1.1 * x), std::sin(0.9 * x),
                                                            std::cos(1.7 * x + 0.2))});
    if (i == 0) {
      chain.add_load(id, SpringDamper({-0.4, 0.0, 0.0}, {-0.6, 0.0, 0.0}, spring));
    } else {
      chain.add_load(previous, id, SpringDamperBetween({0.4, 0.0, 0.0}, {-0.4, 0.0, 0.0}, spring));
    }
    previous = id;
  }
}

std::string label(const std::string& what, int n) { return what + " N=" + std::to_string(n); }

ScalingRow measure_rhs(int n, const ScalingPlan& plan) {
  ScalingRow row;
  row.bodies = n;
  row.what = "rhs";
  Chain chain;
  build_chain(chain, n);
  SceneWorkspace ws(chain);
  const SceneState& y = chain.initial_state();
  Eigen::VectorXd ydot(y.y.size());
  // Calls per timed batch: about plan.rhs_seconds worth, from a short calibration.
  long calls = 1;
  for (;;) {
    const Stopwatch watch;
    for (long i = 0; i < calls; ++i) {
      rhs(chain, ws, 0.0, y, ydot);
    }
    const double s = watch.elapsed(plan.base);
    if (s > 0.2 * plan.rhs_seconds || calls > (1L << 40)) {
      calls = std::max(1L, static_cast<long>(static_cast<double>(calls) * plan.rhs_seconds / s));
      break;
    }
    calls *= 4;
  }
  double best = std::numeric_limits<double>::infinity();
  for (int r = 0; r < plan.rhs_batches; ++r) {
    const Stopwatch watch;
    for (long i = 0; i < calls; ++i) {
      rhs(chain, ws, 0.0, y, ydot);
    }
    best = std::min(best, watch.elapsed(plan.base) / static_cast<double>(calls));
  }
  row.seconds = best;
  row.per_body = best / n;
  row.calls = calls;
  if (!ydot.allFinite()) {
    row.ok = false;
    row.error = "non-finite right-hand side";
  }
  return row;
}

ScalingRow measure_bdf(int n, CvodeLinearSolver solver, const ScalingPlan& plan,
                       bool exact_jacobian = true) {
  ScalingRow row;
  row.bodies = n;
  row.what = solver == CvodeLinearSolver::dense  ? "bdf-dense"
             : solver == CvodeLinearSolver::band ? (exact_jacobian ? "bdf-band" : "bdf-band-dq")
                                                 : "bdf-gmres";
  SceneIntegratorOptions o;
  o.method = CvodeMethod::bdf;
  o.rtol = 1e-6;
  o.atol = 1e-8;
  o.cvode.linear_solver = solver;
  o.cvode.use_system_jacobian = exact_jacobian;
  // band: the half-bandwidths are left at -1, so SceneIntegrator takes the scene's own
  // (Scene::half_bandwidth: 27 for this chain, 13 for one body).
  double best = std::numeric_limits<double>::infinity();
  try {
    for (int r = 0; r < plan.reps; ++r) {
      Chain chain;
      build_chain(chain, n);
      const Stopwatch watch;
      SceneIntegrator integrator(chain, 0.0, o);
      for (int k = 0; k < plan.bdf_steps; ++k) {
        integrator.step();
      }
      const double s = watch.elapsed(plan.base);
      best = std::min(best, s / plan.bdf_steps);
      const SceneStatistics st = integrator.statistics();
      row.calls = st.steps;
      row.rhs_evals = st.rhs_evals + st.linear_rhs_evals;
      row.jacobian_evals = st.jacobian_evals;
      row.linear_iterations = st.linear_iterations;
      if (s > 2.0) {
        break;  // one slow run is measured well enough
      }
    }
  } catch (const std::exception& e) {
    row.ok = false;
    row.error = e.what();
  }
  row.seconds = best;
  row.per_body = best / n;
  return row;
}

}  // namespace

int scaling_measurements(const ScalingPlan& plan) {
  int count = static_cast<int>(plan.rhs_sizes.size());
  for (int n : plan.bdf_sizes) {
    count += 3 + (n <= plan.dense_limit ? 1 : 0);
  }
  return count;
}

std::vector<ScalingRow> run_scaling(const ScalingPlan& plan, const ScalingProgress& progress) {
  std::vector<ScalingRow> rows;
  auto record = [&](ScalingRow row) {
    progress.done(row);
    rows.push_back(std::move(row));
  };
  for (int n : plan.rhs_sizes) {
    progress.start(label("scaling rhs", n));
    record(measure_rhs(n, plan));
  }
  for (int n : plan.bdf_sizes) {
    if (n <= plan.dense_limit) {
      progress.start(label("scaling BDF step, dense LU", n));
      record(measure_bdf(n, CvodeLinearSolver::dense, plan));
    }
    progress.start(label("scaling BDF step, band LU", n));
    record(measure_bdf(n, CvodeLinearSolver::band, plan));
    progress.start(label("scaling BDF step, band LU, difference quotients", n));
    record(measure_bdf(n, CvodeLinearSolver::band, plan, false));
    progress.start(label("scaling BDF step, GMRES", n));
    record(measure_bdf(n, CvodeLinearSolver::gmres, plan));
  }
  return rows;
}

}  // namespace tumble::bench
