#pragma once
// The options and statistics of tumble::Cvode, without SUNDIALS: the method (CvodeMethod), the
// linear solver of BDF's Newton iteration (CvodeLinearSolver, CvodePreconditioning), CVODE's own
// step, iteration and projection options (CvodeSolverOptions), those with the shared tolerances
// and step budget of integrate/common.hpp (CvodeOptions), the counters
// (CvodeStatistics), and validate(), which checks every option that does not depend on the system
// before anything is integrated and names a bad one in a std::invalid_argument.
//
// Most options map to one CVODE setter, named beside it; defaults are CVODE's own unless the
// comment says otherwise. Source: the CVODE user guide (SUNDIALS 6.4 / 7.x), "Optional input
// functions" and "Optional output functions".

#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <variant>

#include <Eigen/Core>

#include "tumble/core/format.hpp"
#include "tumble/integrate/common.hpp"

namespace tumble {

/// Linear multistep method (CVodeCreate's lmm).
enum class CvodeMethod {
  adams,  ///< Adams-Moulton, orders 1-12, fixed-point iteration: nonstiff problems
  bdf,    ///< BDF, orders 1-5, Newton iteration with a linear solver: stiff problems
};

/// Linear solver of the Newton iteration (BDF only).
enum class CvodeLinearSolver {
  dense,  ///< dense LU; uses the system's jacobian() when it has one
  band,   ///< banded LU with the half-bandwidths of CvodeOptions; uses the system's band
          ///< jacobian() when it has one, else banded difference quotients
  gmres,  ///< matrix-free GMRES (difference-quotient J v), optionally preconditioned
};

/// Side of the system's preconditioner in GMRES (ignored when the system has none).
enum class CvodePreconditioning { none, left, right };

/// CVODE's own options, apart from the vocabulary both integrators share (integrate/common.hpp)
/// and the method: what SceneIntegratorOptions::cvode holds, and what CvodeOptions adds to the
/// shared options. Defaults are CVODE's own.
struct CvodeSolverOptions {
  int max_order = 0;  ///< 0: the method's maximum (Adams 12, BDF 5)
  double min_step = 0.0;
  std::optional<double> stop_time;  ///< never step past it (CVodeSetStopTime)

  CvodeLinearSolver linear_solver = CvodeLinearSolver::dense;  ///< BDF only
  int upper_bandwidth = -1;  ///< band: half-bandwidths, in [0, n - 1]
  int lower_bandwidth = -1;
  int krylov_dimension = 0;  ///< GMRES: maximum Krylov subspace dimension, 0: SUNDIALS' 5
  CvodePreconditioning preconditioning = CvodePreconditioning::left;  ///< GMRES
  /// dense and band: use System::jacobian() when the system has one (false: CVODE's difference
  /// quotients)
  bool use_system_jacobian = true;

  int max_error_test_failures = 7;    ///< per step (CVodeSetMaxErrTestFails)
  int max_nonlinear_iterations = 3;   ///< per nonlinear solve (CVodeSetMaxNonlinIters)
  int max_convergence_failures = 10;  ///< per step (CVodeSetMaxConvFails)

  bool project_error = true;          ///< project the error estimate too (CVodeSetProjErrEst)
  double projection_tolerance = 0.1;  ///< epsProj handed to project() (CVodeSetEpsProj)
  long projection_frequency = 1;      ///< project every this many steps (CVodeSetProjFrequency)

  /// Fused vector operations of the serial N_Vector (N_VEnableFusedOps_Serial): CVODE's linear
  /// combinations of many vectors (the Nordsieck history, the error test) in one pass over
  /// memory instead of one N_VLinearSum per pair. Same results to rounding; false: SUNDIALS'
  /// default (one operation per call).
  bool fused_vector_operations = true;
};

/// Options of a Cvode integrator: the shared vocabulary (integrate/common.hpp), the method, the
/// projection switch and CVODE's own options (the base). Defaults are CVODE's own, except the
/// method (BDF), the tolerances (the shared defaults) and the step budget (none; CVODE's is 500).
/// Every option is validated when the integrator is constructed, before anything is integrated;
/// a bad one throws std::invalid_argument naming it.
struct CvodeOptions : CvodeSolverOptions {
  CvodeMethod method = CvodeMethod::bdf;
  double rtol = SharedDefaults::rtol;  ///< relative tolerance, > 0
  /// absolute tolerance: one value > 0, or one per component (all > 0)
  AbsoluteTolerance atol = SharedDefaults::atol;
  /// Internal steps allowed in one call of CVode(), i.e. in one advance() or between two output
  /// times of integrate() (CVodeSetMaxNumSteps); more throws CvodeError CV_TOO_MUCH_WORK
  /// (IntegrationFailure::step_budget) naming this limit. 0 (the default): no limit, however
  /// long the interval. Without a limit an integration still ends: one that cannot succeed
  /// stops on CVODE's error-test or convergence failures, and one that stalls (steps at the
  /// rounding level of t) is stopped by tumble with CV_TOO_MUCH_WORK. Set this to bound the work
  /// of one call, e.g. of Adams on a stiff problem, which progresses but with tiny steps.
  long max_steps = SharedDefaults::max_steps;
  double initial_step = 0.0;  ///< 0: estimated by CVODE
  double max_step = std::numeric_limits<double>::infinity();

  bool projection = false;  ///< project with System::project() (BDF only)

  /// The CVODE-only part (the base), e.g. to copy into SceneIntegratorOptions::cvode.
  [[nodiscard]] CvodeSolverOptions& solver() { return *this; }
  [[nodiscard]] const CvodeSolverOptions& solver() const { return *this; }
};

/// Counters of a Cvode integrator, totals since construction (across reinitializations).
struct CvodeStatistics {
  long steps = 0;
  long rhs_evals = 0;         ///< by the integrator (not counting linear_rhs_evals)
  long linear_rhs_evals = 0;  ///< for difference-quotient Jacobians or J v products
  long error_test_failures = 0;
  long nonlinear_iterations = 0;
  long nonlinear_convergence_failures = 0;
  long jacobian_evals = 0;
  long linear_solver_setups = 0;
  long linear_iterations = 0;  ///< GMRES iterations
  long preconditioner_setups = 0;
  long preconditioner_solves = 0;
  long root_evals = 0;   ///< evaluations of the root functions
  long roots_found = 0;  ///< returns of CVODE at a root
  long projections = 0;
  long projection_failures = 0;
  long reinits = 0;       ///< CVodeReInit calls (events that changed y, reset())
  int last_order = 0;     ///< of the last step taken
  int current_order = 0;  ///< to be tried on the next step
  double last_step = 0.0;
  double current_step = 0.0;
};

/// Validates the options that do not depend on the system (throws std::invalid_argument).
/// `n` is the system size, `t0` the initial time.
inline void validate(const CvodeOptions& o, int n, double t0) {
  auto fail = [](const std::string& what) {
    throw std::invalid_argument("tumble::CvodeOptions: " + what);
  };
  const auto num = detail::format_double;
  if (n <= 0) {
    fail("the system size must be > 0 (got " + std::to_string(n) + ")");
  }
  if (!std::isfinite(t0)) {
    fail("the initial time must be finite (got " + num(t0) + ")");
  }
  if (o.method != CvodeMethod::adams && o.method != CvodeMethod::bdf) {
    fail("'method' is not a CvodeMethod");
  }
  detail::validate_shared("tumble::CvodeOptions", o.rtol, o.atol, o.max_steps, o.initial_step,
                          o.max_step, n, /*atol_may_be_zero=*/false);
  const int order_limit = o.method == CvodeMethod::adams ? 12 : 5;
  if (o.max_order < 0 || o.max_order > order_limit) {
    fail("'max_order' must be in [1, " + std::to_string(order_limit) + "] for " +
         (o.method == CvodeMethod::adams ? "Adams" : "BDF") + ", or 0 for the maximum (got " +
         std::to_string(o.max_order) + ")");
  }
  if (!(std::isfinite(o.min_step) && o.min_step >= 0.0)) {
    fail("'min_step' must be finite and >= 0 (got " + num(o.min_step) + ")");
  }
  if (o.min_step > o.max_step) {
    fail("'min_step' (" + num(o.min_step) + ") must not exceed 'max_step' (" + num(o.max_step) +
         ")");
  }
  if (o.initial_step > 0.0 && (o.initial_step < o.min_step || o.initial_step > o.max_step)) {
    fail("'initial_step' (" + num(o.initial_step) + ") must lie in [min_step, max_step]");
  }
  if (o.stop_time && !(std::isfinite(*o.stop_time) && *o.stop_time > t0)) {
    fail("'stop_time' must be finite and after the initial time " + num(t0) + " (got " +
         num(*o.stop_time) + ")");
  }
  if (o.method == CvodeMethod::bdf) {
    switch (o.linear_solver) {
      case CvodeLinearSolver::dense:
        break;
      case CvodeLinearSolver::band:
        if (o.upper_bandwidth < 0 || o.upper_bandwidth > n - 1) {
          fail("'upper_bandwidth' must be in [0, " + std::to_string(n - 1) + "] (got " +
               std::to_string(o.upper_bandwidth) + ")");
        }
        if (o.lower_bandwidth < 0 || o.lower_bandwidth > n - 1) {
          fail("'lower_bandwidth' must be in [0, " + std::to_string(n - 1) + "] (got " +
               std::to_string(o.lower_bandwidth) + ")");
        }
        break;
      case CvodeLinearSolver::gmres:
        if (o.krylov_dimension < 0) {
          fail("'krylov_dimension' must be >= 0 (got " + std::to_string(o.krylov_dimension) + ")");
        }
        if (o.preconditioning != CvodePreconditioning::none &&
            o.preconditioning != CvodePreconditioning::left &&
            o.preconditioning != CvodePreconditioning::right) {
          fail("'preconditioning' is not a CvodePreconditioning");
        }
        break;
      default:
        fail("'linear_solver' is not a CvodeLinearSolver");
    }
  }
  if (o.max_error_test_failures <= 0) {
    fail("'max_error_test_failures' must be > 0 (got " + std::to_string(o.max_error_test_failures) +
         ")");
  }
  if (o.max_nonlinear_iterations <= 0) {
    fail("'max_nonlinear_iterations' must be > 0 (got " +
         std::to_string(o.max_nonlinear_iterations) + ")");
  }
  if (o.max_convergence_failures <= 0) {
    fail("'max_convergence_failures' must be > 0 (got " +
         std::to_string(o.max_convergence_failures) + ")");
  }
  if (o.projection) {
    if (o.method != CvodeMethod::bdf) {
      // CVodeSetProjFn: "projection is only supported with BDF methods".
      fail("'projection' needs method = CvodeMethod::bdf (CVODE projects only with BDF)");
    }
    if (!(std::isfinite(o.projection_tolerance) && o.projection_tolerance > 0.0)) {
      fail("'projection_tolerance' must be finite and > 0 (got " + num(o.projection_tolerance) +
           ")");
    }
    if (o.projection_frequency < 1) {
      fail("'projection_frequency' must be >= 1 (got " + std::to_string(o.projection_frequency) +
           "); set 'projection' = false to disable");
    }
  }
}

}  // namespace tumble
