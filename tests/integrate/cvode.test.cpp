// Tests of tumble::Cvode (include/tumble/integrate/cvode.hpp), each against an independent
// expectation: closed-form solutions (oscillator, decay, linear systems, a bouncing ball, a
// rotating unit vector), conservation laws (Robertson's y1 + y2 + y3 = 1), a second method on the
// same problem (analytic versus difference-quotient Jacobian; dense, band and GMRES), and
// published reference values (Robertson at t = 40, from the CVODE examples).
//
// The allocation test counts operator new calls with integrate/alloc_counter.hpp (the counting
// operator new/delete of the whole test executable) and builds Eigen with EIGEN_RUNTIME_NO_MALLOC,
// to prove that the callbacks CVODE calls during a run allocate nothing.

// Must precede every Eigen include: lets the allocation test forbid Eigen heap allocations.
#define EIGEN_RUNTIME_NO_MALLOC

#include "tumble/integrate/cvode.hpp"

#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "integrate/alloc_counter.hpp"
#include "support/catch.hpp"
#include "tumble/integrate/errors.hpp"

using tumble::ConstVectorMap;
using tumble::Cvode;
using tumble::CvodeError;
using tumble::CvodeLinearSolver;
using tumble::CvodeMethod;
using tumble::CvodeOptions;
using tumble::IntegrationError;
using tumble::MatrixMap;
using tumble::VectorMap;
using tumble::test::AllocationCounter;

namespace {

constexpr double pi = std::numbers::pi;

// ---- systems -----------------------------------------------------------------------------------

/// x'' = -omega^2 x as y = (x, v). From (1, 0): x = cos(omega t), v = -omega sin(omega t).
struct Oscillator {
  double omega = 1.0;
  [[nodiscard]] int size() const { return 2; }
  void rhs(double /*t*/, ConstVectorMap y, VectorMap ydot) const {
    ydot[0] = y[1];
    ydot[1] = -omega * omega * y[0];
  }
};

struct OscillatorWithJacobian : Oscillator {
  void jacobian(double, ConstVectorMap, ConstVectorMap, MatrixMap j) const {
    j(0, 1) = 1.0;
    j(1, 0) = -omega * omega;
  }
};

/// Euler's equations of a torque-free rigid body, y = omega (body frame), principal inertia
/// (1, 2, 3): I1 w1' = (I2 - I3) w2 w3 and cyclic. Started near the intermediate axis it tumbles
/// (flips over and back again); 2T = omega . I omega and |L|^2 = |I omega|^2 are conserved.
struct TumblingBody {
  Eigen::Vector3d inertia{1.0, 2.0, 3.0};
  [[nodiscard]] int size() const { return 3; }
  void rhs(double, ConstVectorMap w, VectorMap wdot) const {
    const Eigen::Vector3d& i = inertia;
    wdot[0] = (i[1] - i[2]) / i[0] * w[1] * w[2];
    wdot[1] = (i[2] - i[0]) / i[1] * w[2] * w[0];
    wdot[2] = (i[0] - i[1]) / i[2] * w[0] * w[1];
  }
  [[nodiscard]] double energy(const Eigen::Vector3d& w) const {
    return w.dot(inertia.cwiseProduct(w));
  }
  [[nodiscard]] double momentum(const Eigen::Vector3d& w) const {
    return inertia.cwiseProduct(w).squaredNorm();
  }
};

/// y' = -k y.
struct Decay {
  double k = 2.0;
  [[nodiscard]] int size() const { return 1; }
  void rhs(double, ConstVectorMap y, VectorMap ydot) const { ydot[0] = -k * y[0]; }
};

/// y' = A y with A = V diag(-1, -lambda) V^-1, V = [[1, 1], [1, -1]]: eigenvalue -1 on (1, 1)
/// and -lambda on (1, -1). From y0 = a (1, 1) + b (1, -1):
///   y(t) = a e^-t (1, 1) + b e^(-lambda t) (1, -1).
struct StiffLinear {
  double lambda = 1e6;
  [[nodiscard]] int size() const { return 2; }
  void rhs(double, ConstVectorMap y, VectorMap ydot) const {
    const double p = -0.5 * (1.0 + lambda), m = -0.5 * (1.0 - lambda);
    ydot[0] = p * y[0] + m * y[1];
    ydot[1] = m * y[0] + p * y[1];
  }
  [[nodiscard]] Eigen::Vector2d exact(double t, double a, double b) const {
    return a * std::exp(-t) * Eigen::Vector2d(1, 1) +
           b * std::exp(-lambda * t) * Eigen::Vector2d(1, -1);
  }
};

/// Robertson's chemical kinetics (the classic stiff test; CVODE example cvRoberts_dns).
struct Robertson {
  [[nodiscard]] int size() const { return 3; }
  void rhs(double, ConstVectorMap y, VectorMap ydot) const {
    ydot[0] = -0.04 * y[0] + 1e4 * y[1] * y[2];
    ydot[2] = 3e7 * y[1] * y[1];
    ydot[1] = -ydot[0] - ydot[2];
  }
};
struct RobertsonWithJacobian : Robertson {
  void jacobian(double, ConstVectorMap y, ConstVectorMap, MatrixMap j) const {
    j(0, 0) = -0.04;
    j(0, 1) = 1e4 * y[2];
    j(0, 2) = 1e4 * y[1];
    j(2, 1) = 6e7 * y[1];
    j(1, 0) = 0.04;
    j(1, 1) = -1e4 * y[2] - 6e7 * y[1];
    j(1, 2) = -1e4 * y[1];
  }
};

/// A ball dropped from height h under gravity g, bouncing with restitution e: y = (x, v).
/// Root g0 = x, falling crossings only; the bounce reverses and scales v and restarts CVODE.
struct BouncingBall {
  double g = 9.81;
  double e = 0.8;
  std::vector<double>* impacts = nullptr;  // where to record the impact times (may be null)
  long bounces = 0;

  [[nodiscard]] int size() const { return 2; }
  void rhs(double, ConstVectorMap y, VectorMap ydot) const {
    ydot[0] = y[1];
    ydot[1] = -g;
  }
  [[nodiscard]] int root_count() const { return 1; }
  void roots(double, ConstVectorMap y, VectorMap out) const { out[0] = y[0]; }
  [[nodiscard]] std::array<int, 1> root_directions() const { return {-1}; }
  bool on_root(double t, VectorMap y, std::span<const int> which) {
    REQUIRE(which.size() == 1);
    REQUIRE(which[0] == -1);
    if (impacts != nullptr) {
      impacts->push_back(t);
    }
    ++bounces;
    y[0] = 0.0;
    y[1] = -e * y[1];
    return true;
  }
};

/// Impact times of BouncingBall from height h at rest: t1 = sqrt(2h/g), then flights of
/// 2 e^k v1 / g with v1 = g t1.
std::vector<double> bounce_times(double h, double g, double e, double t_end) {
  std::vector<double> t{std::sqrt(2.0 * h / g)};
  const double v1 = g * t.front();
  for (int k = 1; t.back() < t_end; ++k) {
    t.push_back(t.back() + 2.0 * std::pow(e, k) * v1 / g);
  }
  t.pop_back();
  return t;
}

/// x = sin t (x'' = -x from (0, 1)); roots g0 = x (direction chosen by the test) and
/// g1 = x - 1/2 (both directions). Records each root: time and which[].
struct SineEvents {
  int direction0 = 0;
  std::vector<std::pair<double, std::array<int, 2>>> events;
  [[nodiscard]] int size() const { return 2; }
  void rhs(double, ConstVectorMap y, VectorMap ydot) const {
    ydot[0] = y[1];
    ydot[1] = -y[0];
  }
  [[nodiscard]] int root_count() const { return 2; }
  void roots(double, ConstVectorMap y, VectorMap g) const {
    g[0] = y[0];
    g[1] = y[0] - 0.5;
  }
  [[nodiscard]] std::vector<int> root_directions() const { return {direction0, 0}; }
  bool on_root(double t, VectorMap, std::span<const int> which) {
    events.push_back({t, {which[0], which[1]}});
    return false;
  }
};

/// y' = w x y: a vector rotating rigidly about w. |y| = 1 is an invariant; project() restores it
/// (corr = y/|y| - y) and removes the radial part of the error estimate.
struct RotatingUnitVector {
  Eigen::Vector3d w{0.3, -0.5, 1.1};
  [[nodiscard]] int size() const { return 3; }
  void rhs(double, ConstVectorMap y, VectorMap ydot) const { ydot = w.cross(Eigen::Vector3d(y)); }
  void project(double, ConstVectorMap y, VectorMap corr, double, VectorMap err) const {
    const double norm = y.norm();
    corr = y / norm - y;
    if (err.size() > 0) {
      const Eigen::Vector3d n = y / norm;
      err -= n.dot(err) * n;
    }
  }
  [[nodiscard]] Eigen::Vector3d exact(double t, const Eigen::Vector3d& y0) const {
    return Eigen::AngleAxisd(w.norm() * t, w.normalized()) * y0;
  }
};

/// Semi-discrete heat equation u_t = u_xx on (0, 1), u = 0 at both ends, n interior points:
/// tridiagonal. From u_i = sin(pi x_i) the exact solution is exp(-mu t) u_i(0) with the discrete
/// eigenvalue mu = 4/dx^2 sin^2(pi dx / 2). PreconditionedHeat adds the Jacobi preconditioner
/// P = diag(1 + 2 gamma/dx^2) of I - gamma J.
struct Heat {
  int n = 40;
  [[nodiscard]] int size() const { return n; }
  [[nodiscard]] double dx() const { return 1.0 / (n + 1); }
  void rhs(double, ConstVectorMap u, VectorMap du) const {
    const double c = 1.0 / (dx() * dx());
    for (int i = 0; i < n; ++i) {
      const double left = i > 0 ? u[i - 1] : 0.0;
      const double right = i < n - 1 ? u[i + 1] : 0.0;
      du[i] = c * (left - 2.0 * u[i] + right);
    }
  }
  [[nodiscard]] Eigen::VectorXd initial() const {
    Eigen::VectorXd u(n);
    for (int i = 0; i < n; ++i) {
      u[i] = std::sin(pi * (i + 1) * dx());
    }
    return u;
  }
  [[nodiscard]] double mu() const {
    const double s = std::sin(pi * dx() / 2.0);
    return 4.0 / (dx() * dx()) * s * s;
  }
};
struct PreconditionedHeat : Heat {
  double diagonal = 1.0;
  bool precondition_setup(double, ConstVectorMap, ConstVectorMap, bool, double gamma) {
    diagonal = 1.0 + 2.0 * gamma / (dx() * dx());
    return true;
  }
  void precondition_solve(double, ConstVectorMap, ConstVectorMap, ConstVectorMap r, VectorMap z,
                          double, double, int) const {
    z = r / diagonal;
  }
};

/// theta' = omega, kept in (-pi, pi] by on_step (a "chart switch" that changes y without a
/// root); the number of wraps reconstructs the unwrapped angle omega t.
struct WrappedAngle {
  double omega = 2.0;
  long wraps = 0;
  [[nodiscard]] int size() const { return 1; }
  void rhs(double, ConstVectorMap, VectorMap ydot) const { ydot[0] = omega; }
  bool on_step(double, VectorMap y) {
    if (y[0] > pi) {
      y[0] -= 2.0 * pi;
      ++wraps;
      return true;
    }
    return false;
  }
};

/// Every optional member, to instantiate every branch of the integrator.
struct FullSystem {
  [[nodiscard]] int size() const { return 3; }
  void rhs(double, ConstVectorMap y, VectorMap ydot) const {
    ydot = Eigen::Vector3d(0.0, 0.0, 1.0).cross(Eigen::Vector3d(y));
  }
  void jacobian(double, ConstVectorMap, ConstVectorMap, MatrixMap j) const {
    j(0, 1) = -1.0;
    j(1, 0) = 1.0;
  }
  void project(double, ConstVectorMap y, VectorMap corr, double, VectorMap) const {
    corr = y / y.norm() - y;
  }
  [[nodiscard]] int root_count() const { return 1; }
  void roots(double, ConstVectorMap y, VectorMap g) const { g[0] = y[0]; }
  [[nodiscard]] std::vector<int> root_directions() const { return {0}; }
  bool on_root(double, VectorMap, std::span<const int>) { return false; }
  bool on_step(double, VectorMap) { return false; }
  bool precondition_setup(double, ConstVectorMap, ConstVectorMap, bool, double) { return false; }
  void precondition_solve(double, ConstVectorMap, ConstVectorMap, ConstVectorMap r, VectorMap z,
                          double, double, int) const {
    z = r;
  }
};

static_assert(tumble::CvodeSystem<Oscillator>);
static_assert(!tumble::CvodeHasJacobian<Oscillator>);
static_assert(tumble::CvodeHasJacobian<OscillatorWithJacobian>);
static_assert(tumble::CvodeHasRoots<BouncingBall> && tumble::CvodeHasRootAction<BouncingBall> &&
              tumble::CvodeHasRootDirections<BouncingBall>);
static_assert(tumble::CvodeHasProjection<RotatingUnitVector>);
static_assert(tumble::CvodeHasPreconditioner<PreconditionedHeat>);
static_assert(!tumble::CvodeHasPreconditioner<Heat>);
static_assert(tumble::CvodeHasStepAction<WrappedAngle>);
static_assert(!std::is_copy_constructible_v<Cvode<Oscillator>>);
static_assert(!std::is_copy_assignable_v<Cvode<Oscillator>>);
static_assert(std::is_nothrow_move_constructible_v<Cvode<Oscillator>>);
static_assert(std::is_nothrow_move_assignable_v<Cvode<Oscillator>>);

CvodeOptions tolerances(CvodeMethod method, double tol) {
  CvodeOptions o;
  o.method = method;
  o.rtol = tol;
  o.atol = tol;
  return o;
}

/// Largest |y(t) - (cos t, -sin t)| over outputs every 0.5 up to 10, and the steps taken.
std::pair<double, long> oscillator_error(CvodeMethod method, double tol) {
  CvodeOptions o = tolerances(method, tol);
  o.max_steps = 100000;
  Cvode cvode(Oscillator{}, 0.0, Eigen::Vector2d(1.0, 0.0), o);
  std::vector<double> times;
  for (int k = 1; k <= 20; ++k) {
    times.push_back(0.5 * k);
  }
  double worst = 0.0;
  cvode.integrate(times, [&](double t, ConstVectorMap y) {
    worst = std::max(worst, (y - Eigen::Vector2d(std::cos(t), -std::sin(t))).cwiseAbs().maxCoeff());
  });
  return {worst, cvode.statistics().steps};
}

}  // namespace

// Every member of the integrator compiles, for a system with every optional member.
template class tumble::Cvode<FullSystem>;

// ---- accuracy ----------------------------------------------------------------------------------

TEST_CASE("harmonic oscillator: error follows the tolerance, Adams and BDF", "[integrate][cvode]") {
  for (const auto method : {CvodeMethod::adams, CvodeMethod::bdf}) {
    const auto [loose, loose_steps] = oscillator_error(method, 1e-6);
    const auto [tight, tight_steps] = oscillator_error(method, 1e-10);
    INFO("method " << (method == CvodeMethod::adams ? "Adams" : "BDF") << ": error " << loose
                   << " (" << loose_steps << " steps) at tol 1e-6, " << tight << " (" << tight_steps
                   << " steps) at tol 1e-10");
    // CVODE bounds the local error of each step: |e|_WRMS <= 1 with weights
    // 1/(rtol |y_i| + atol) <= 1/tol here... so |e|_max <= sqrt(2) * 2 tol (|y_i| <= 1). The flow
    // is an isometry, so local errors add up without amplification: the global error is at most
    // steps * 2 sqrt(2) tol. (Global error is not bounded by tol itself: it accumulates.)
    const double per_step = 2.0 * std::sqrt(2.0);
    CHECK(loose < per_step * static_cast<double>(loose_steps) * 1e-6);
    CHECK(tight < per_step * static_cast<double>(tight_steps) * 1e-10);
    CHECK(loose > 1e-6);  // not accidentally exact: the comparison above means something
    // Four orders of magnitude of tolerance buy at least two orders of accuracy.
    CHECK(tight < 1e-2 * loose);
  }
}

TEST_CASE("exponential decay matches exp(-k t)", "[integrate][cvode]") {
  for (const auto method : {CvodeMethod::adams, CvodeMethod::bdf}) {
    CvodeOptions o;
    o.method = method;
    o.rtol = 1e-9;
    o.atol = 1e-14;
    Decay decay;
    Cvode cvode(decay, 0.0, Eigen::VectorXd::Constant(1, 3.0), o);
    for (const double t : {0.1, 1.0, 2.5, 5.0}) {
      const double y = cvode.advance(t)[0];
      const double exact = 3.0 * std::exp(-decay.k * t);
      // Each step's local error is at most rtol |y| + atol, and the decaying flow shrinks it
      // in proportion to y: the relative error is at most the number of steps times
      // (rtol + atol / |y|).
      const auto steps = static_cast<double>(cvode.statistics().steps);
      INFO("t = " << t << ": relative error " << (y - exact) / exact << " after " << steps
                  << " steps");
      CHECK(std::abs(y - exact) <= steps * (1e-9 * exact + 1e-14));
      CHECK(cvode.time() == t);
    }
  }
}

TEST_CASE("stiff linear system: BDF needs far fewer steps than Adams", "[integrate][cvode]") {
  const StiffLinear system;
  const double a = 1.0, b = 0.5;
  const Eigen::Vector2d y0 = system.exact(0.0, a, b);
  const double t_end = 0.05;

  CvodeOptions bdf = tolerances(CvodeMethod::bdf, 1e-8);
  Cvode implicit(system, 0.0, y0, bdf);
  const Eigen::Vector2d y_bdf = implicit.advance(t_end);

  CvodeOptions adams = tolerances(CvodeMethod::adams, 1e-8);
  adams.max_steps = 1000000;
  Cvode explicit_(system, 0.0, y0, adams);
  const Eigen::Vector2d y_adams = explicit_.advance(t_end);

  const Eigen::Vector2d exact = system.exact(t_end, a, b);
  CHECK((y_bdf - exact).norm() < 1e-6);
  CHECK((y_adams - exact).norm() < 1e-6);

  const auto s_bdf = implicit.statistics();
  const auto s_adams = explicit_.statistics();
  INFO("steps: BDF " << s_bdf.steps << ", Adams " << s_adams.steps);
  // Adams' stability region bounds its step by ~1/lambda = 1e-6: thousands of steps over 0.05.
  CHECK(s_adams.steps > 5000);
  CHECK(s_bdf.steps * 20 < s_adams.steps);
  CHECK(s_bdf.jacobian_evals > 0);
  CHECK(s_adams.jacobian_evals == 0);  // fixed-point iteration, no linear solver
}

TEST_CASE("Robertson: analytic and difference-quotient Jacobians agree", "[integrate][cvode]") {
  CvodeOptions o;
  o.method = CvodeMethod::bdf;
  o.rtol = 1e-6;
  o.atol = Eigen::Vector3d(1e-10, 1e-14, 1e-8);  // per component, as in cvRoberts_dns
  o.max_steps = 5000;
  const Eigen::Vector3d y0(1.0, 0.0, 0.0);

  Cvode analytic(RobertsonWithJacobian{}, 0.0, y0, o);
  Cvode quotients(Robertson{}, 0.0, y0, o);
  CvodeOptions no_jac = o;
  no_jac.use_system_jacobian = false;
  Cvode ignored(RobertsonWithJacobian{}, 0.0, y0, no_jac);

  for (const double t : {0.4, 4.0, 40.0, 400.0, 4e4, 4e6}) {
    const Eigen::Vector3d ya = analytic.advance(t);
    const Eigen::Vector3d yq = quotients.advance(t);
    INFO("t = " << t << ": " << ya.transpose() << " vs " << yq.transpose());
    // Conservation: y1 + y2 + y3 = 1 (the three rates sum to zero).
    CHECK(std::abs(ya.sum() - 1.0) < 1e-6);
    CHECK(std::abs(yq.sum() - 1.0) < 1e-6);
    // Both are within the tolerance of the true solution, hence of each other.
    for (int i = 0; i < 3; ++i) {
      CHECK(std::abs(ya[i] - yq[i]) <= 20 * (1e-6 * std::abs(ya[i]) + o.rtol * 1e-8));
    }
    if (t == 40.0) {
      // Published values at t = 40 (CVODE example cvRoberts_dns output).
      CHECK(ya[0] == Approx(7.1583e-01).epsilon(1e-4));
      CHECK(ya[1] == Approx(9.1855e-06).epsilon(1e-3));
      CHECK(ya[2] == Approx(2.8416e-01).epsilon(1e-3));
    }
  }
  const auto sa = analytic.statistics();
  const auto sq = quotients.statistics();
  const auto si = ignored.statistics();
  CHECK(sa.jacobian_evals > 0);
  CHECK(sq.jacobian_evals > 0);
  // Difference quotients cost n = 3 extra rhs evaluations per Jacobian; the analytic one none.
  CHECK(sa.linear_rhs_evals == 0);
  CHECK(sq.linear_rhs_evals == 3 * sq.jacobian_evals);
  CHECK(si.linear_rhs_evals == 3 * si.jacobian_evals);
}

TEST_CASE("dense, band and GMRES linear solvers agree with the exact heat solution",
          "[integrate][cvode]") {
  const Heat heat;
  const double t_end = 0.1;
  const Eigen::VectorXd exact = std::exp(-heat.mu() * t_end) * heat.initial();

  auto run = [&](auto system, CvodeLinearSolver solver, tumble::CvodeStatistics& stats) {
    CvodeOptions o = tolerances(CvodeMethod::bdf, 1e-8);
    o.linear_solver = solver;
    o.upper_bandwidth = 1;
    o.lower_bandwidth = 1;
    o.max_steps = 5000;
    Cvode cvode(std::move(system), 0.0, heat.initial(), o);
    const Eigen::VectorXd u = cvode.advance(t_end);
    stats = cvode.statistics();
    return (u - exact).cwiseAbs().maxCoeff() / exact.cwiseAbs().maxCoeff();
  };
  tumble::CvodeStatistics dense, band, gmres, preconditioned;
  CHECK(run(heat, CvodeLinearSolver::dense, dense) < 1e-5);
  CHECK(run(heat, CvodeLinearSolver::band, band) < 1e-5);
  CHECK(run(heat, CvodeLinearSolver::gmres, gmres) < 1e-5);
  CHECK(run(PreconditionedHeat{}, CvodeLinearSolver::gmres, preconditioned) < 1e-5);
  // Banded difference quotients need mu + ml + 1 = 3 rhs evaluations per Jacobian, dense n.
  CHECK(band.linear_rhs_evals == 3 * band.jacobian_evals);
  CHECK(dense.linear_rhs_evals == heat.n * dense.jacobian_evals);
  CHECK(gmres.linear_iterations > 0);
  CHECK(gmres.preconditioner_setups == 0);
  CHECK(preconditioned.preconditioner_solves > 0);
  INFO("GMRES iterations: " << gmres.linear_iterations << " plain, "
                            << preconditioned.linear_iterations << " preconditioned");
  CHECK(preconditioned.linear_iterations < gmres.linear_iterations);
}

// ---- events ------------------------------------------------------------------------------------

TEST_CASE("bouncing ball: impact times match the closed form", "[integrate][cvode]") {
  for (const auto method : {CvodeMethod::adams, CvodeMethod::bdf}) {
    std::vector<double> impacts;
    BouncingBall ball;
    ball.impacts = &impacts;
    const double h = 10.0, t_end = 8.0;
    CvodeOptions o = tolerances(method, 1e-10);
    o.max_steps = 10000;
    Cvode cvode(ball, 0.0, Eigen::Vector2d(h, 0.0), o);
    cvode.advance(t_end);

    const auto expected = bounce_times(h, ball.g, ball.e, t_end);
    REQUIRE(expected.size() >= 4);
    REQUIRE(impacts.size() == expected.size());
    for (std::size_t k = 0; k < expected.size(); ++k) {
      CHECK(std::abs(impacts[k] - expected[k]) < 1e-8);
    }
    const auto s = cvode.statistics();
    CHECK(s.roots_found == static_cast<long>(expected.size()));
    CHECK(s.reinits == static_cast<long>(expected.size()));
    CHECK(cvode.system().bounces == static_cast<long>(expected.size()));
    CHECK(s.root_evals > 0);
    // The ball stays above ground (to the tolerance) between bounces.
    CHECK(cvode.state()[0] > -1e-8);
  }
}

TEST_CASE("root directions select the crossings reported", "[integrate][cvode]") {
  auto run = [](int direction) {
    SineEvents sine;
    sine.direction0 = direction;
    Cvode cvode(std::move(sine), 0.0, Eigen::Vector2d(0.0, 1.0),
                tolerances(CvodeMethod::adams, 1e-10));
    cvode.advance(13.0);
    return cvode.system().events;
  };
  using Event = std::pair<double, std::array<int, 2>>;
  auto check = [](const std::vector<Event>& got, const std::vector<Event>& want) {
    REQUIRE(got.size() == want.size());
    for (std::size_t k = 0; k < want.size(); ++k) {
      CHECK(got[k].first == Approx(want[k].first).margin(1e-8));
      CHECK(got[k].second == want[k].second);
    }
  };
  // sin t = 0 at k pi (rising at even k; t = 0 is the initial point, not a crossing);
  // sin t = 1/2 at pi/6, 5pi/6 (+ 2 pi k), rising then falling.
  check(run(+1), {{pi / 6, {0, 1}},
                  {5 * pi / 6, {0, -1}},
                  {2 * pi, {1, 0}},
                  {13 * pi / 6, {0, 1}},
                  {17 * pi / 6, {0, -1}},
                  {4 * pi, {1, 0}}});
  check(run(-1), {{pi / 6, {0, 1}},
                  {5 * pi / 6, {0, -1}},
                  {pi, {-1, 0}},
                  {13 * pi / 6, {0, 1}},
                  {17 * pi / 6, {0, -1}},
                  {3 * pi, {-1, 0}}});
  const auto both = run(0);
  CHECK(both.size() == 8);
}

TEST_CASE("on_step can change the state without a root (chart switch)", "[integrate][cvode]") {
  WrappedAngle angle;
  CvodeOptions o = tolerances(CvodeMethod::adams, 1e-10);
  Cvode cvode(angle, 0.0, Eigen::VectorXd::Zero(1), o);
  for (int k = 1; k <= 40; ++k) {
    const double t = 0.25 * k;
    const double theta = cvode.advance(t)[0];
    CHECK(theta <= pi);
    CHECK(theta > -pi);
    CHECK(theta + 2.0 * pi * static_cast<double>(cvode.system().wraps) ==
          Approx(angle.omega * t).margin(1e-8));
  }
  CHECK(cvode.system().wraps == 3);  // 2 * 10 = 20 rad: wrapped at pi, 3 pi, 5 pi
  CHECK(cvode.statistics().reinits == 3);
}

// ---- projection --------------------------------------------------------------------------------

TEST_CASE("projection keeps a rotating unit vector on the sphere", "[integrate][cvode]") {
  const RotatingUnitVector system;
  const Eigen::Vector3d y0 = Eigen::Vector3d(1.0, 2.0, -0.5).normalized();
  CvodeOptions o = tolerances(CvodeMethod::bdf, 1e-5);
  o.max_steps = 100000;
  const double t_end = 100.0;

  CvodeOptions with = o;
  with.projection = true;
  Cvode projected(system, 0.0, y0, with);
  Cvode free(system, 0.0, y0, o);

  // After every internal step the projected solution is on the sphere to rounding.
  double worst_step_norm = 0.0;
  while (projected.time() < 10.0) {
    projected.step();
    worst_step_norm = std::max(worst_step_norm, std::abs(projected.state().norm() - 1.0));
  }
  CHECK(worst_step_norm < 1e-14);

  const Eigen::Vector3d yp = projected.advance(t_end);
  const Eigen::Vector3d yf = free.advance(t_end);
  const double drift_projected = std::abs(yp.norm() - 1.0);
  const double drift_free = std::abs(yf.norm() - 1.0);
  INFO("|norm - 1| at t = 100: " << drift_projected << " projected, " << drift_free << " free");
  // At an output time the state is interpolated between projected steps, so the norm error is
  // at the tolerance level; without projection BDF's damping makes it grow with time.
  CHECK(drift_projected < 10 * o.rtol);
  CHECK(drift_free > 10 * drift_projected);
  CHECK(projected.statistics().projections >= projected.statistics().steps);
  CHECK(free.statistics().projections == 0);
  // Both follow the exact rotation: the flow is an isometry, so the global error is at most the
  // sum of the local errors, each |e| <= sqrt(3) (rtol |y|_max + atol) = sqrt(3) * 2e-5.
  const double per_step = std::sqrt(3.0) * 2.0 * o.rtol;
  CHECK((yp - system.exact(t_end, y0)).norm() <
        per_step * static_cast<double>(projected.statistics().steps));
  CHECK((yf - system.exact(t_end, y0)).norm() <
        per_step * static_cast<double>(free.statistics().steps));
}

// ---- options and errors ------------------------------------------------------------------------

TEST_CASE("bad options throw std::invalid_argument naming them, before integrating",
          "[integrate][cvode]") {
  const Eigen::Vector2d y0(1.0, 0.0);
  auto rejects = [&](const CvodeOptions& o, const std::string& name) {
    INFO("option " << name);
    try {
      Cvode cvode(Oscillator{}, 0.0, y0, o);
      FAIL("no exception");
    } catch (const std::invalid_argument& e) {
      CHECK(std::string(e.what()).find(name) != std::string::npos);
    }
  };
  auto with = [](auto change) {
    CvodeOptions o;
    change(o);
    return o;
  };
  rejects(with([](CvodeOptions& o) { o.rtol = 0.0; }), "'rtol'");
  rejects(with([](CvodeOptions& o) { o.rtol = -1e-6; }), "'rtol'");
  rejects(with([](CvodeOptions& o) { o.rtol = std::nan(""); }), "'rtol'");
  rejects(with([](CvodeOptions& o) { o.atol = 0.0; }), "'atol'");
  rejects(with([](CvodeOptions& o) { o.atol = Eigen::Vector3d(1, 1, 1); }), "'atol'");
  rejects(with([](CvodeOptions& o) { o.atol = Eigen::Vector2d(1e-8, -1e-8); }), "'atol'");
  rejects(with([](CvodeOptions& o) {
            o.method = CvodeMethod::adams;
            o.max_order = 13;
          }),
          "'max_order'");
  rejects(with([](CvodeOptions& o) { o.max_order = 6; }), "'max_order'");  // BDF
  rejects(with([](CvodeOptions& o) { o.max_order = -1; }), "'max_order'");
  rejects(with([](CvodeOptions& o) { o.max_steps = -1; }), "'max_steps'");
  rejects(with([](CvodeOptions& o) { o.initial_step = -0.1; }), "'initial_step'");
  rejects(with([](CvodeOptions& o) { o.min_step = -0.1; }), "'min_step'");
  rejects(with([](CvodeOptions& o) { o.max_step = 0.0; }), "'max_step'");
  rejects(with([](CvodeOptions& o) {
            o.min_step = 1.0;
            o.max_step = 0.5;
          }),
          "'min_step'");
  rejects(with([](CvodeOptions& o) {
            o.max_step = 0.5;
            o.initial_step = 1.0;
          }),
          "'initial_step'");
  rejects(with([](CvodeOptions& o) { o.stop_time = 0.0; }), "'stop_time'");
  rejects(with([](CvodeOptions& o) { o.stop_time = -1.0; }), "'stop_time'");
  rejects(with([](CvodeOptions& o) {
            o.linear_solver = CvodeLinearSolver::band;
            o.upper_bandwidth = 2;  // n - 1 = 1
            o.lower_bandwidth = 0;
          }),
          "'upper_bandwidth'");
  rejects(with([](CvodeOptions& o) {
            o.linear_solver = CvodeLinearSolver::band;
            o.upper_bandwidth = 1;
          }),
          "'lower_bandwidth'");
  rejects(with([](CvodeOptions& o) {
            o.linear_solver = CvodeLinearSolver::gmres;
            o.krylov_dimension = -1;
          }),
          "'krylov_dimension'");
  rejects(with([](CvodeOptions& o) { o.max_error_test_failures = 0; }),
          "'max_error_test_failures'");
  rejects(with([](CvodeOptions& o) { o.max_nonlinear_iterations = 0; }),
          "'max_nonlinear_iterations'");
  rejects(with([](CvodeOptions& o) { o.max_convergence_failures = -2; }),
          "'max_convergence_failures'");
  rejects(with([](CvodeOptions& o) { o.projection = true; }), "'projection'");  // no project()

  // Projection is BDF-only in CVODE.
  CvodeOptions adams_projection;
  adams_projection.method = CvodeMethod::adams;
  adams_projection.projection = true;
  CHECK_THROWS_AS(Cvode(RotatingUnitVector{}, 0.0, Eigen::Vector3d(1, 0, 0), adams_projection),
                  std::invalid_argument);
  CvodeOptions bad_projection_tolerance;
  bad_projection_tolerance.projection = true;
  bad_projection_tolerance.projection_tolerance = 0.0;
  CHECK_THROWS_AS(
      Cvode(RotatingUnitVector{}, 0.0, Eigen::Vector3d(1, 0, 0), bad_projection_tolerance),
      std::invalid_argument);

  // The initial state and time.
  CHECK_THROWS_AS(Cvode(Oscillator{}, 0.0, Eigen::Vector3d(1, 0, 0)), std::invalid_argument);
  CHECK_THROWS_AS(Cvode(Oscillator{}, 0.0, Eigen::Vector2d(std::nan(""), 0.0)),
                  std::invalid_argument);
  CHECK_THROWS_AS(Cvode(Oscillator{}, std::numeric_limits<double>::infinity(), y0),
                  std::invalid_argument);

  // Root directions must match the root functions.
  struct BadDirections : SineEvents {
    [[nodiscard]] std::vector<int> root_directions() const { return {1}; }
  };
  CHECK_THROWS_AS(Cvode(BadDirections{}, 0.0, y0), std::invalid_argument);

  // Band options are ignored by Adams (no linear solver).
  CvodeOptions adams_band;
  adams_band.method = CvodeMethod::adams;
  adams_band.linear_solver = CvodeLinearSolver::band;
  CHECK_NOTHROW(Cvode(Oscillator{}, 0.0, y0, adams_band));
}

TEST_CASE("too much work: IntegrationError names CV_TOO_MUCH_WORK, the limit and the time",
          "[integrate][cvode]") {
  const StiffLinear system;
  CvodeOptions o = tolerances(CvodeMethod::adams, 1e-8);
  o.max_steps = 200;
  const std::string limit = "(max_steps = 200)";
  Cvode cvode(system, 0.0, system.exact(0.0, 1.0, 0.5), o);
  try {
    cvode.advance(10.0);
    FAIL("no exception");
  } catch (const CvodeError& e) {
    const std::string what = e.what();
    INFO(what);
    CHECK(e.flag() == CV_TOO_MUCH_WORK);
    CHECK(e.flag_name() == "CV_TOO_MUCH_WORK");
    CHECK(what.find("CV_TOO_MUCH_WORK") != std::string::npos);
    CHECK(what.find(limit) != std::string::npos);
    CHECK(what.find("bdf") != std::string::npos);
    CHECK(cvode.statistics().steps == 200);
    CHECK(e.time() > 0.0);
    CHECK(e.time() < 10.0);
    CHECK(e.time() == cvode.time());
    CHECK(what.find("t = " + tumble::detail::format_double(e.time())) != std::string::npos);
    CHECK(!e.cause());
  }
}

TEST_CASE("no per-call step limit by default: one long advance of a tumbling body",
          "[integrate][cvode]") {
  const TumblingBody body;
  const Eigen::Vector3d w0(0.05, 2.0, 0.05);  // near the intermediate axis
  CvodeOptions o = tolerances(CvodeMethod::bdf, 1e-10);
  CHECK(o.max_steps == 0);
  SECTION("the default: the whole interval in one call") {
    Cvode cvode(body, 0.0, w0, o);
    const Eigen::Vector3d w = cvode.advance(50.0);
    // CVODE's own default limit (500 steps per call) stopped this run part of the way.
    CHECK(cvode.statistics().steps > 500);
    CHECK(cvode.time() == 50.0);
    CHECK(std::abs(body.energy(w) / body.energy(w0) - 1.0) < 1e-6);
    CHECK(std::abs(body.momentum(w) / body.momentum(w0) - 1.0) < 1e-6);
  }
  SECTION("an explicit limit stops it with an IntegrationError naming the limit") {
    o.max_steps = 100;
    Cvode cvode(body, 0.0, w0, o);
    try {
      cvode.advance(50.0);
      FAIL("no exception");
    } catch (const CvodeError& e) {
      INFO(e.what());
      CHECK(e.flag_name() == "CV_TOO_MUCH_WORK");
      CHECK(std::string(e.what()).find("(max_steps = 100)") != std::string::npos);
      CHECK(e.time() > 0.0);
      CHECK(e.time() < 50.0);
      CHECK(cvode.statistics().steps == 100);
    }
  }
}

TEST_CASE("without a step limit, an integration that cannot progress stops, not hangs",
          "[integrate][cvode]") {
  // At t = 1e12 a unit of the last place of t is 1.2e-4, while the oscillator (period 6e-4)
  // needs steps of about 1e-5: t + h == t, CVODE takes steps that never move t (it only warns).
  const Oscillator fast{.omega = 1e4};
  const double t0 = 1e12;
  Cvode cvode(fast, t0, Eigen::Vector2d(1.0, 0.0), tolerances(CvodeMethod::adams, 1e-8));
  try {
    cvode.advance(t0 + 1.0);
    FAIL("no exception");
  } catch (const CvodeError& e) {
    const std::string what = e.what();
    INFO(what);
    CHECK(e.flag_name() == "CV_TOO_MUCH_WORK");
    CHECK(what.find("stalled") != std::string::npos);
    CHECK(what.find("rounding level of t") != std::string::npos);
    CHECK(e.time() == t0);
    CHECK(!e.cause());
  }
}

TEST_CASE("a non-finite right-hand side is recoverable, then a clear failure",
          "[integrate][cvode]") {
  // A single NaN (one evaluation) is retried with a smaller step and the result is unharmed.
  struct FlakyDecay : Decay {
    mutable int calls = 0;
    void rhs(double t, ConstVectorMap y, VectorMap ydot) const {
      Decay::rhs(t, y, ydot);
      if (++calls == 20) {
        ydot[0] = std::nan("");
      }
    }
  };
  CvodeOptions o = tolerances(CvodeMethod::bdf, 1e-9);
  Cvode flaky(FlakyDecay{}, 0.0, Eigen::VectorXd::Constant(1, 1.0), o);
  CHECK(flaky.advance(2.0)[0] == Approx(std::exp(-4.0)).epsilon(1e-6));
  CHECK(flaky.system().calls > 20);

  // NaN for every t > 0.5: no step size helps; the error says why.
  struct Poisoned : Decay {
    void rhs(double t, ConstVectorMap y, VectorMap ydot) const {
      Decay::rhs(t, y, ydot);
      if (t > 0.5) {
        ydot[0] = std::numeric_limits<double>::quiet_NaN();
      }
    }
  };
  for (const auto method : {CvodeMethod::adams, CvodeMethod::bdf}) {
    Cvode poisoned(Poisoned{}, 0.0, Eigen::VectorXd::Constant(1, 1.0), tolerances(method, 1e-8));
    try {
      poisoned.advance(1.0);
      FAIL("no exception");
    } catch (const CvodeError& e) {
      const std::string what = e.what();
      INFO(what);
      CHECK(what.find("non-finite") != std::string::npos);
      CHECK(what.find("rhs()") != std::string::npos);
      CHECK(e.time() <= 0.5);
      CHECK(e.time() > 0.4);
      CHECK(!e.cause());
      CHECK(poisoned.time() == e.time());
      CHECK(poisoned.state()[0] == Approx(std::exp(-2.0 * e.time())).epsilon(1e-6));
    }
  }

  // RecoverableError thrown by the system behaves the same and its message is kept.
  struct Refusing : Decay {
    void rhs(double t, ConstVectorMap y, VectorMap ydot) const {
      if (t > 0.5) {
        throw tumble::RecoverableError("state outside the chart");
      }
      Decay::rhs(t, y, ydot);
    }
  };
  Cvode refusing(Refusing{}, 0.0, Eigen::VectorXd::Constant(1, 1.0));
  try {
    refusing.advance(1.0);
    FAIL("no exception");
  } catch (const CvodeError& e) {
    INFO(e.what());
    CHECK(std::string(e.what()).find("state outside the chart") != std::string::npos);
  }
}

TEST_CASE("exceptions thrown by callbacks are rethrown as IntegrationError with the cause",
          "[integrate][cvode]") {
  struct Boom : std::runtime_error {
    using std::runtime_error::runtime_error;
  };
  struct ThrowingRhs : Decay {
    void rhs(double t, ConstVectorMap y, VectorMap ydot) const {
      if (t > 1.0) {
        throw Boom("boom in rhs");
      }
      Decay::rhs(t, y, ydot);
    }
  };
  Cvode cvode(ThrowingRhs{}, 0.0, Eigen::VectorXd::Constant(1, 1.0));
  try {
    cvode.advance(2.0);
    FAIL("no exception");
  } catch (const CvodeError& e) {
    INFO(e.what());
    CHECK(e.flag() == CV_RHSFUNC_FAIL);
    CHECK(e.flag_name() == "CV_RHSFUNC_FAIL");
    CHECK(e.reason() == tumble::IntegrationFailure::callback);
    CHECK(std::string(e.what()).find("boom in rhs") != std::string::npos);
    REQUIRE(e.cause());
    CHECK_THROWS_AS(std::rethrow_exception(e.cause()), Boom);
    CHECK(e.time() <= 1.0);
  }

  struct ThrowingRoots : SineEvents {
    void roots(double t, ConstVectorMap, VectorMap g) const {
      if (t > 1.0) {
        throw Boom("boom in roots");
      }
      g.setOnes();  // no root before; left unwritten, CVODE would read what its memory held
    }
  };
  Cvode roots(ThrowingRoots{}, 0.0, Eigen::Vector2d(0.0, 1.0));
  try {
    roots.advance(2.0);
    FAIL("no exception");
  } catch (const CvodeError& e) {
    CHECK(e.flag() == CV_RTFUNC_FAIL);
    CHECK(std::string(e.what()).find("boom in roots") != std::string::npos);
    REQUIRE(e.cause());
    CHECK_THROWS_AS(std::rethrow_exception(e.cause()), Boom);
  }

  struct ThrowingJacobian : Robertson {
    void jacobian(double, ConstVectorMap, ConstVectorMap, MatrixMap) const {
      throw Boom("boom in jacobian");
    }
  };
  Cvode jacobian(ThrowingJacobian{}, 0.0, Eigen::Vector3d(1.0, 0.0, 0.0));
  try {
    jacobian.advance(1.0);
    FAIL("no exception");
  } catch (const CvodeError& e) {
    CHECK(e.flag() == CV_LSETUP_FAIL);
    CHECK(e.reason() == tumble::IntegrationFailure::callback);  // whatever the flag
    CHECK(std::string(e.what()).find("boom in jacobian") != std::string::npos);
    REQUIRE(e.cause());
    CHECK_THROWS_AS(std::rethrow_exception(e.cause()), Boom);
  }

  // Exceptions from on_root() propagate unchanged (they are thrown from C++, not from CVODE).
  struct ThrowingAction : SineEvents {
    bool on_root(double, VectorMap, std::span<const int>) { throw Boom("boom in on_root"); }
  };
  Cvode action(ThrowingAction{}, 0.0, Eigen::Vector2d(0.0, 1.0));
  CHECK_THROWS_AS(action.advance(2.0), Boom);
}

TEST_CASE("output times must not go backwards", "[integrate][cvode]") {
  Cvode cvode(Decay{}, 0.0, Eigen::VectorXd::Constant(1, 1.0));
  cvode.advance(1.0);
  CHECK_THROWS_AS(cvode.advance(0.5), std::invalid_argument);
  CHECK_THROWS_AS(cvode.advance(std::nan("")), std::invalid_argument);

  int calls = 0;
  auto count = [&](double, ConstVectorMap) { ++calls; };
  CHECK_THROWS_AS(cvode.integrate({0.5, 2.0}, count), std::invalid_argument);  // behind
  CHECK_THROWS_AS(cvode.integrate({2.0, 3.0, 2.5}, count), std::invalid_argument);
  CHECK(calls == 0);           // all times are checked before integrating
  CHECK(cvode.time() == 1.0);  // and nothing was integrated

  std::vector<double> seen;
  cvode.integrate(std::vector<double>{1.0, 1.5, 3.0}, [&](double t, ConstVectorMap y) {
    seen.push_back(t);
    CHECK(y[0] == Approx(std::exp(-2.0 * t)).epsilon(1e-4));
  });
  CHECK(seen == std::vector<double>{1.0, 1.5, 3.0});

  // A stop time bounds the output times.
  CvodeOptions o;
  o.stop_time = 2.0;
  Cvode stopped(Decay{}, 0.0, Eigen::VectorXd::Constant(1, 1.0), o);
  CHECK_THROWS_AS(stopped.advance(2.5), std::invalid_argument);
  stopped.advance(2.0);
  CHECK(stopped.time() == 2.0);
  CHECK_THROWS_AS(stopped.step(), std::logic_error);
}

TEST_CASE("step() takes single internal steps and stops at the stop time", "[integrate][cvode]") {
  CvodeOptions o = tolerances(CvodeMethod::bdf, 1e-8);
  o.stop_time = 1.0;
  Cvode cvode(Decay{}, 0.0, Eigen::VectorXd::Constant(1, 1.0), o);
  double previous = 0.0;
  long steps = 0;
  while (cvode.time() < 1.0) {
    const double t = cvode.step();
    CHECK(t > previous);
    CHECK(t <= 1.0);
    CHECK(cvode.state()[0] == Approx(std::exp(-2.0 * t)).epsilon(1e-6));
    previous = t;
    ++steps;
  }
  CHECK(cvode.time() == 1.0);
  CHECK(cvode.statistics().steps == steps);
}

TEST_CASE("reset() restarts from a new state and statistics add up", "[integrate][cvode]") {
  Cvode cvode(Decay{}, 0.0, Eigen::VectorXd::Constant(1, 1.0), tolerances(CvodeMethod::bdf, 1e-9));
  cvode.advance(1.0);
  const auto before = cvode.statistics();
  cvode.reset(1.0, Eigen::VectorXd::Constant(1, 5.0));
  CHECK(cvode.statistics().steps == before.steps);  // nothing lost by the restart
  CHECK(cvode.statistics().reinits == 1);
  const double y = cvode.advance(2.0)[0];
  CHECK(y == Approx(5.0 * std::exp(-2.0)).epsilon(1e-7));
  const auto after = cvode.statistics();
  CHECK(after.steps > before.steps);
  CHECK(after.rhs_evals > before.rhs_evals);
  CHECK(after.jacobian_evals > before.jacobian_evals);
  CHECK(after.reinits == 1);
  CHECK_THROWS_AS(cvode.reset(2.0, Eigen::VectorXd::Constant(2, 1.0)), std::invalid_argument);
}

TEST_CASE("moving an integrator keeps its state and result", "[integrate][cvode]") {
  const CvodeOptions o = tolerances(CvodeMethod::adams, 1e-9);
  Cvode reference(Oscillator{}, 0.0, Eigen::Vector2d(1.0, 0.0), o);
  reference.advance(2.0);
  const Eigen::Vector2d expected = reference.advance(5.0);

  Cvode first(Oscillator{}, 0.0, Eigen::Vector2d(1.0, 0.0), o);
  first.advance(2.0);
  Cvode second(std::move(first));  // move construction mid-run
  CHECK(second.time() == 2.0);
  Cvode third(Oscillator{}, 0.0, Eigen::Vector2d(0.0, 0.0), o);
  third = std::move(second);  // move assignment releases third's own CVODE objects
  const Eigen::Vector2d y = third.advance(5.0);
  CHECK(y == expected);  // the same sequence of steps, bit for bit
  CHECK(third.statistics().steps == reference.statistics().steps);
}

TEST_CASE("a system can be held by reference", "[integrate][cvode]") {
  BouncingBall ball;
  Cvode<BouncingBall&> cvode(ball, 0.0, Eigen::Vector2d(1.0, 0.0),
                             tolerances(CvodeMethod::bdf, 1e-8));
  cvode.advance(1.0);
  CHECK(ball.bounces == 1);  // the caller's object saw the event
  CHECK(&cvode.system() == &ball);
}

// ---- allocation --------------------------------------------------------------------------------

TEST_CASE("no heap allocation during advance() once set up", "[integrate][cvode]") {
  SECTION("BDF, dense, analytic Jacobian") {
    CvodeOptions o = tolerances(CvodeMethod::bdf, 1e-8);
    o.max_steps = 100000;
    Cvode cvode(OscillatorWithJacobian{}, 0.0, Eigen::Vector2d(1.0, 0.0), o);
    cvode.advance(0.1);  // CVODE finishes its own setup in the first call
    AllocationCounter counter;
    cvode.advance(50.0);
    const long n = counter.stop();
    CHECK(n == 0);
    CHECK(cvode.statistics().jacobian_evals > 0);
  }
  SECTION("Adams, roots, events that restart CVODE") {
    BouncingBall ball;
    CvodeOptions o = tolerances(CvodeMethod::adams, 1e-8);
    Cvode cvode(ball, 0.0, Eigen::Vector2d(10.0, 0.0), o);
    cvode.advance(0.1);
    AllocationCounter counter;
    cvode.advance(8.0);
    const long n = counter.stop();
    CHECK(n == 0);
    CHECK(cvode.system().bounces >= 4);
  }
  SECTION("BDF with projection, band and GMRES") {
    CvodeOptions o = tolerances(CvodeMethod::bdf, 1e-6);
    o.projection = true;
    o.max_steps = 100000;
    Cvode projected(RotatingUnitVector{}, 0.0, Eigen::Vector3d(1.0, 0.0, 0.0), o);
    projected.advance(0.1);
    CvodeOptions g = tolerances(CvodeMethod::bdf, 1e-6);
    g.linear_solver = CvodeLinearSolver::gmres;
    Cvode gmres(PreconditionedHeat{}, 0.0, Heat{}.initial(), g);
    gmres.advance(1e-4);
    CvodeOptions b = g;
    b.linear_solver = CvodeLinearSolver::band;
    b.upper_bandwidth = b.lower_bandwidth = 1;
    Cvode band(Heat{}, 0.0, Heat{}.initial(), b);
    band.advance(1e-4);
    AllocationCounter counter;
    projected.advance(20.0);
    gmres.advance(0.1);
    band.advance(0.1);
    const long n = counter.stop();
    CHECK(n == 0);
    CHECK(projected.statistics().projections > 0);
  }
}
