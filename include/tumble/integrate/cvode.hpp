#pragma once
// tumble::Cvode: a generic C++ front end to SUNDIALS CVODE for y' = f(t, y), y in R^n.
//
// CVODE integrates with variable-order, variable-step linear multistep methods: Adams-Moulton
// (orders 1-12, nonstiff, here with fixed-point iteration) or BDF (orders 1-5, stiff, here with
// Newton iteration and a dense, band or matrix-free GMRES linear solver). Source: the CVODE user
// guide (SUNDIALS 6.4 / 7.x), "Mathematical considerations" and "Using CVODE for IVP solution";
// every CVODE function called here is described there.
//
// A *system* is any type that models `CvodeSystem` (below): it has a size and a right-hand side
// written into Eigen views of CVODE's own vectors, so that evaluating f allocates nothing. Optional
// members, detected at compile time, add an analytic Jacobian, a projection onto a constraint
// manifold, root functions (events) with actions, and a preconditioner; what a system does not
// provide costs nothing.
//
// Callbacks never let an exception cross into C: a RecoverableError, or a non-finite derivative,
// becomes CVODE's "recoverable failure" (it retries with a smaller step); any other exception is
// stored, CVODE is told to stop, and advance()/step() throw an IntegrationError whose cause() is
// the original exception. CVODE's own messages are captured into the IntegrationError instead of
// being printed.
//
// \warning The state views handed to callbacks are only valid during the call.
// \warning If on_root() or on_step() changes y it must return true: the integrator then restarts
//          CVODE from the changed state (CVodeReInit). A change without `true` is overwritten.

#include <algorithm>
#include <array>
#include <cmath>
#include <concepts>
#include <cstdio>
#include <exception>
#include <initializer_list>
#include <limits>
#include <memory>
#include <optional>
#include <ranges>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include <Eigen/Core>
#include <cvode/cvode.h>
#include <cvode/cvode_ls.h>
#include <cvode/cvode_proj.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_band.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunlinsol/sunlinsol_spgmr.h>
#include <sunmatrix/sunmatrix_band.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include "tumble/core/band_matrix.hpp"
#include "tumble/integrate/detail/cvode_flags.hpp"
#include "tumble/integrate/detail/sundials.hpp"
#include "tumble/integrate/errors.hpp"

namespace tumble {

/// Read-only view of a CVODE vector (y, f(t, y), ...) inside a callback.
using ConstVectorMap = Eigen::Map<const Eigen::VectorXd>;
/// Writable view of a CVODE vector (ydot, a correction, root values, ...) inside a callback.
using VectorMap = Eigen::Map<Eigen::VectorXd>;
/// Writable column-major view of CVODE's dense Jacobian matrix.
using MatrixMap = Eigen::Map<Eigen::MatrixXd>;

// clang-format off
/// The required interface of a system y' = f(t, y):
///   int size() const;                                      // n, fixed for the system's life
///   void rhs(double t, ConstVectorMap y, VectorMap ydot);  // ydot = f(t, y)
/// rhs() may throw RecoverableError to make CVODE retry with a smaller step.
template <class S>
concept CvodeSystem = requires(std::remove_cvref_t<S>& s, const std::remove_cvref_t<S>& cs,
                               double t, ConstVectorMap y, VectorMap ydot) {
  { cs.size() } -> std::convertible_to<int>;
  s.rhs(t, y, ydot);
};

/// Optional: the dense Jacobian J = df/dy at (t, y), fy = f(t, y). J arrives zeroed.
/// Used with the BDF dense linear solver (otherwise CVODE's difference quotients).
template <class S>
concept CvodeHasJacobian = requires(std::remove_cvref_t<S>& s, double t, ConstVectorMap y,
                                    ConstVectorMap fy, MatrixMap jac) {
  s.jacobian(t, y, fy, jac);
};

/// Optional: the same into CVODE's band matrix (BandMatrixMap: write only entries in_band(i, j)),
/// used with the BDF band linear solver. A system may provide both, or one template for both.
template <class S>
concept CvodeHasBandJacobian = requires(std::remove_cvref_t<S>& s, double t, ConstVectorMap y,
                                        ConstVectorMap fy, BandMatrixMap jac) {
  s.jacobian(t, y, fy, jac);
};

/// Optional: projection onto the constraint manifold after each step (CVodeSetProjFn, BDF only).
/// Write into corr the correction that puts y + corr on the manifold; err (size 0 when error
/// projection is off) is the local error estimate, to be replaced by its projection. epsProj is
/// the tolerance (WRMS norm of the update) for an iterative projection.
template <class S>
concept CvodeHasProjection = requires(std::remove_cvref_t<S>& s, double t, ConstVectorMap y,
                                      VectorMap corr, double eps, VectorMap err) {
  s.project(t, y, corr, eps, err);
};

/// Optional: root functions g_i(t, y), i < root_count(), whose zeros CVODE locates (events).
template <class S>
concept CvodeHasRoots = requires(std::remove_cvref_t<S>& s, const std::remove_cvref_t<S>& cs,
                                 double t, ConstVectorMap y, VectorMap g) {
  { cs.root_count() } -> std::convertible_to<int>;
  s.roots(t, y, g);
};

/// Optional: the direction of the zero crossings to report, one int per root function:
/// +1 only increasing g_i, -1 only decreasing, 0 both (the default).
template <class S>
concept CvodeHasRootDirections = requires(const std::remove_cvref_t<S>& cs) {
  { cs.root_directions() } -> std::ranges::input_range;
};

/// Optional: the action at a root. which[i] is +1 (g_i crossed upward), -1 (downward) or 0.
/// The system may change y; it returns true when it did, so that CVODE is reinitialized.
template <class S>
concept CvodeHasRootAction = requires(std::remove_cvref_t<S>& s, double t, VectorMap y,
                                      std::span<const int> which) {
  { s.on_root(t, y, which) } -> std::convertible_to<bool>;
};

/// Optional: called whenever advance() or step() returns (at the output time, after each
/// internal step, at roots after on_root). The system may change y (e.g. switch the chart of an
/// orientation parameterization) and returns true when it did, to reinitialize CVODE.
template <class S>
concept CvodeHasStepAction = requires(std::remove_cvref_t<S>& s, double t, VectorMap y) {
  { s.on_step(t, y) } -> std::convertible_to<bool>;
};

/// Optional: a preconditioner P ~ I - gamma J for GMRES (CVodeSetPreconditioner).
///   bool precondition_setup(t, y, fy, jacobian_ok, gamma): prepare P; jacobian_ok says that
///        saved Jacobian data may be reused; return true when Jacobian data was recomputed.
///   void precondition_solve(t, y, fy, r, z, gamma, delta, lr): solve P z = r (to the tolerance
///        delta if iterative; lr is 1 for the left, 2 for the right preconditioner).
template <class S>
concept CvodeHasPreconditioner = requires(std::remove_cvref_t<S>& s, double t, ConstVectorMap y,
                                          ConstVectorMap fy, ConstVectorMap r, VectorMap z,
                                          bool jok, double gamma, double delta, int lr) {
  { s.precondition_setup(t, y, fy, jok, gamma) } -> std::convertible_to<bool>;
  s.precondition_solve(t, y, fy, r, z, gamma, delta, lr);
};
// clang-format on

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

/// Options of a Cvode integrator. Defaults are CVODE's own, except the method (BDF).
/// Every option is validated when the integrator is constructed, before anything is integrated;
/// a bad one throws std::invalid_argument naming it.
struct CvodeOptions {
  CvodeMethod method = CvodeMethod::bdf;
  double rtol = 1e-6;  ///< relative tolerance, > 0
  /// absolute tolerance: one value > 0, or one per component (all > 0)
  std::variant<double, Eigen::VectorXd> atol = 1e-8;
  int max_order = 0;          ///< 0: the method's maximum (Adams 12, BDF 5)
  long max_steps = 500;       ///< internal steps allowed per call of CVODE (CVodeSetMaxNumSteps)
  double initial_step = 0.0;  ///< 0: estimated by CVODE
  double min_step = 0.0;
  double max_step = std::numeric_limits<double>::infinity();
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

  bool projection = false;            ///< project with System::project() (BDF only)
  bool project_error = true;          ///< project the error estimate too (CVodeSetProjErrEst)
  double projection_tolerance = 0.1;  ///< epsProj handed to project() (CVodeSetEpsProj)
  long projection_frequency = 1;      ///< project every this many steps (CVodeSetProjFrequency)
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
  auto num = [](double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", x);
    return std::string(buf);
  };
  if (n <= 0) {
    fail("the system size must be > 0 (got " + std::to_string(n) + ")");
  }
  if (!std::isfinite(t0)) {
    fail("the initial time must be finite (got " + num(t0) + ")");
  }
  if (o.method != CvodeMethod::adams && o.method != CvodeMethod::bdf) {
    fail("'method' is not a CvodeMethod");
  }
  if (!(std::isfinite(o.rtol) && o.rtol > 0.0)) {
    fail("'rtol' must be finite and > 0 (got " + num(o.rtol) + ")");
  }
  if (const auto* a = std::get_if<double>(&o.atol)) {
    if (!(std::isfinite(*a) && *a > 0.0)) {
      fail("'atol' must be finite and > 0 (got " + num(*a) + ")");
    }
  } else {
    const auto& v = std::get<Eigen::VectorXd>(o.atol);
    if (v.size() != n) {
      fail("'atol' per component must have the system size " + std::to_string(n) + " (got " +
           std::to_string(v.size()) + ")");
    }
    for (Eigen::Index i = 0; i < v.size(); ++i) {
      if (!(std::isfinite(v[i]) && v[i] > 0.0)) {
        fail("'atol' component " + std::to_string(i) + " must be finite and > 0 (got " + num(v[i]) +
             ")");
      }
    }
  }
  const int order_limit = o.method == CvodeMethod::adams ? 12 : 5;
  if (o.max_order < 0 || o.max_order > order_limit) {
    fail("'max_order' must be in [1, " + std::to_string(order_limit) + "] for " +
         (o.method == CvodeMethod::adams ? "Adams" : "BDF") + ", or 0 for the maximum (got " +
         std::to_string(o.max_order) + ")");
  }
  if (o.max_steps <= 0) {
    fail("'max_steps' must be > 0 (got " + std::to_string(o.max_steps) + ")");
  }
  if (!(std::isfinite(o.initial_step) && o.initial_step >= 0.0)) {
    fail("'initial_step' must be finite and >= 0 (got " + num(o.initial_step) + ")");
  }
  if (!(std::isfinite(o.min_step) && o.min_step >= 0.0)) {
    fail("'min_step' must be finite and >= 0 (got " + num(o.min_step) + ")");
  }
  if (!(o.max_step > 0.0)) {  // also rejects NaN; +inf means no bound
    fail("'max_step' must be > 0 (got " + num(o.max_step) + ")");
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

namespace detail {

/// What a callback reported: an unrecoverable exception (rethrown as the IntegrationError's
/// cause) and the last recoverable failure (for the message when CVODE gives up). Filling it
/// never allocates: exception_ptr only shares the thrown object, messages go to a fixed buffer.
struct CallbackReport {
  std::exception_ptr exception;
  const char* exception_where = "";
  double exception_time = 0.0;

  bool has_recoverable = false;
  const char* recoverable_where = "";
  double recoverable_time = 0.0;
  std::array<char, 256> recoverable_message{};

  void clear() noexcept {
    exception = nullptr;
    has_recoverable = false;
  }
  void note_recoverable(const char* where, double t, const char* message) noexcept {
    has_recoverable = true;
    recoverable_where = where;
    recoverable_time = t;
    std::snprintf(recoverable_message.data(), recoverable_message.size(), "%s", message);
  }
};

inline std::string format_number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", x);
  return buf;
}

inline std::string exception_message(const std::exception_ptr& e) {
  try {
    std::rethrow_exception(e);
  } catch (const std::exception& x) {
    return x.what();
  } catch (...) {
    return "an exception not derived from std::exception";
  }
}

/// The integrator's state. Lives on the heap (Cvode holds a unique_ptr), so the pointer CVODE
/// hands back to the callbacks (user_data) stays valid when a Cvode is moved.
template <class System> class CvodeCore {
 public:
  using SystemType = std::remove_cvref_t<System>;

  CvodeCore(System&& system, double t0, const Eigen::Ref<const Eigen::VectorXd>& y0,
            CvodeOptions options)
      : system_(std::forward<System>(system)),
        options_(std::move(options)),
        n_(static_cast<sunindextype>(y0.size())),
        t_(t0) {
    setup(y0);
  }
  CvodeCore(const CvodeCore&) = delete;
  CvodeCore& operator=(const CvodeCore&) = delete;
  CvodeCore(CvodeCore&&) = delete;
  CvodeCore& operator=(CvodeCore&&) = delete;
  ~CvodeCore() = default;

  [[nodiscard]] SystemType& system() noexcept { return system_; }
  [[nodiscard]] const SystemType& system() const noexcept { return system_; }
  [[nodiscard]] const CvodeOptions& options() const noexcept { return options_; }
  [[nodiscard]] double time() const noexcept { return t_; }
  [[nodiscard]] int size() const noexcept { return static_cast<int>(n_); }
  [[nodiscard]] void* memory() const noexcept { return mem_.get(); }
  [[nodiscard]] ConstVectorMap state() const noexcept { return cview(y_.get()); }

  ConstVectorMap advance(double t_out) {
    check_output_time(t_out, "advance");
    while (t_ < t_out) {
      // CVODE refuses to start (CV_TOO_CLOSE) when t_out - t0 is at rounding level; over such an
      // interval y does not change in double precision, so report the current state.
      if (!segment_started_ && t_out - t_ <= 4.0 * std::numeric_limits<double>::epsilon() *
                                                 std::max(std::abs(t_), std::abs(t_out))) {
        t_ = t_out;
        break;
      }
      const int flag = call_cvode(t_out, CV_NORMAL);
      after_return(flag);
      if (flag == CV_SUCCESS || flag == CV_TSTOP_RETURN) {
        break;
      }
    }
    return state();
  }

  double step() {
    if (options_.stop_time && t_ >= *options_.stop_time) {
      throw std::logic_error("tumble::Cvode::step: the stop time " +
                             format_number(*options_.stop_time) + " has been reached");
    }
    // With CV_ONE_STEP, tout only gives the direction and, on the first step, an upper bound
    // for CVODE's estimate of the initial step.
    const double tout = options_.stop_time ? *options_.stop_time : t_ + 1.0;
    const int flag = call_cvode(tout, CV_ONE_STEP);
    after_return(flag);
    return t_;
  }

  template <class Times, class Observer> void integrate(const Times& times, Observer& observer) {
    bool first = true;
    double previous = t_;
    for (const auto& value : times) {  // validate every output time before integrating
      const double tk = static_cast<double>(value);
      if (!std::isfinite(tk)) {
        throw std::invalid_argument("tumble::Cvode::integrate: output time " + format_number(tk) +
                                    " is not finite");
      }
      if (first ? tk < t_ : tk <= previous) {
        throw std::invalid_argument(
            "tumble::Cvode::integrate: output times must be increasing and not behind the "
            "current time " +
            format_number(t_) + " (got " + format_number(tk) + " after " + format_number(previous) +
            ")");
      }
      if (options_.stop_time && tk > *options_.stop_time) {
        throw std::invalid_argument("tumble::Cvode::integrate: output time " + format_number(tk) +
                                    " is after the stop time " +
                                    format_number(*options_.stop_time));
      }
      previous = tk;
      first = false;
    }
    for (const auto& value : times) {
      const double tk = static_cast<double>(value);
      advance(tk);
      observer(tk, state());
    }
  }

  void reset(double t, const Eigen::Ref<const Eigen::VectorXd>& y) {
    if (!std::isfinite(t)) {
      throw std::invalid_argument("tumble::Cvode::reset: the time must be finite");
    }
    if (y.size() != n_) {
      throw std::invalid_argument("tumble::Cvode::reset: the state has size " +
                                  std::to_string(y.size()) + ", the system " + std::to_string(n_));
    }
    if (!y.allFinite()) {
      throw std::invalid_argument("tumble::Cvode::reset: the state has a non-finite component");
    }
    if (options_.stop_time && t >= *options_.stop_time) {
      throw std::invalid_argument("tumble::Cvode::reset: the time " + format_number(t) +
                                  " is not before the stop time " +
                                  format_number(*options_.stop_time));
    }
    view(y_.get()) = y;
    t_ = t;
    reinitialize();
  }

  [[nodiscard]] CvodeStatistics statistics() const {
    CvodeStatistics s = accumulated_;
    if (segment_started_) {
      add_segment(s);
    }
    s.roots_found = roots_found_;
    s.reinits = reinits_;
    return s;
  }

 private:
  // ---- views of SUNDIALS vectors -----------------------------------------------------------
  [[nodiscard]] ConstVectorMap cview(N_Vector v) const noexcept {
    return ConstVectorMap(N_VGetArrayPointer(v), static_cast<Eigen::Index>(n_));
  }
  [[nodiscard]] VectorMap view(N_Vector v) const noexcept {
    return VectorMap(N_VGetArrayPointer(v), static_cast<Eigen::Index>(n_));
  }

  // ---- setup -------------------------------------------------------------------------------
  void check(int flag, const char* call) const {
    if (flag < 0) {
      const std::string name = flag_name(flag);
      std::string what = "tumble::Cvode: " + std::string(call) + " failed with " + name;
      if (errors_.has_message) {
        what += " [" + std::string(errors_.message.data()) + "]";
      }
      throw IntegrationError(what, flag, name, t_);
    }
  }

  void setup(const Eigen::Ref<const Eigen::VectorXd>& y0) {
    context_ = make_context(errors_);
    SUNContext ctx = context_.get();
    y_.reset(require_allocated(N_VNew_Serial(n_, ctx)));
    view(y_.get()) = y0;

    const bool adams = options_.method == CvodeMethod::adams;
    mem_.reset(require_allocated(CVodeCreate(adams ? CV_ADAMS : CV_BDF, ctx)));
    void* mem = mem_.get();
    install_error_handler(mem, errors_);
    check(CVodeInit(mem, &CvodeCore::rhs_callback, t_, y_.get()), "CVodeInit");
    check(CVodeSetUserData(mem, this), "CVodeSetUserData");

    if (const auto* a = std::get_if<double>(&options_.atol)) {
      check(CVodeSStolerances(mem, options_.rtol, *a), "CVodeSStolerances");
    } else {
      atol_.reset(require_allocated(N_VNew_Serial(n_, ctx)));
      view(atol_.get()) = std::get<Eigen::VectorXd>(options_.atol);
      check(CVodeSVtolerances(mem, options_.rtol, atol_.get()), "CVodeSVtolerances");
    }

    if (adams) {
      // Adams with fixed-point (functional) iteration, no Anderson acceleration (m = 0).
      nonlinear_solver_.reset(require_allocated(SUNNonlinSol_FixedPoint(y_.get(), 0, ctx)));
      check(CVodeSetNonlinearSolver(mem, nonlinear_solver_.get()), "CVodeSetNonlinearSolver");
    } else {
      setup_linear_solver(mem, ctx);  // BDF with CVODE's default Newton iteration
    }

    if (options_.max_order > 0) {
      check(CVodeSetMaxOrd(mem, options_.max_order), "CVodeSetMaxOrd");
    }
    check(CVodeSetMaxNumSteps(mem, options_.max_steps), "CVodeSetMaxNumSteps");
    if (options_.initial_step > 0.0) {
      check(CVodeSetInitStep(mem, options_.initial_step), "CVodeSetInitStep");
    }
    if (options_.min_step > 0.0) {
      check(CVodeSetMinStep(mem, options_.min_step), "CVodeSetMinStep");
    }
    if (std::isfinite(options_.max_step)) {
      check(CVodeSetMaxStep(mem, options_.max_step), "CVodeSetMaxStep");
    }
    if (options_.stop_time) {
      check(CVodeSetStopTime(mem, *options_.stop_time), "CVodeSetStopTime");
    }
    check(CVodeSetMaxErrTestFails(mem, options_.max_error_test_failures),
          "CVodeSetMaxErrTestFails");
    check(CVodeSetMaxNonlinIters(mem, options_.max_nonlinear_iterations), "CVodeSetMaxNonlinIters");
    check(CVodeSetMaxConvFails(mem, options_.max_convergence_failures), "CVodeSetMaxConvFails");

    if constexpr (CvodeHasRoots<SystemType>) {
      const int count = static_cast<int>(system_.root_count());
      if (count > 0) {
        root_count_ = count;
        root_info_.assign(static_cast<std::size_t>(count), 0);
        check(CVodeRootInit(mem, count, &CvodeCore::root_callback), "CVodeRootInit");
        if constexpr (CvodeHasRootDirections<SystemType>) {
          std::vector<int> directions;
          for (const auto& d : system_.root_directions()) {
            directions.push_back(static_cast<int>(d));
          }
          check(CVodeSetRootDirection(mem, directions.data()), "CVodeSetRootDirection");
        }
        // After a reinitialization at an event, g_i is often exactly 0 at the new initial time;
        // CVODE then keeps g_i inactive until it moves away from 0, which is what we want.
        check(CVodeSetNoInactiveRootWarn(mem), "CVodeSetNoInactiveRootWarn");
      }
    }

    if constexpr (CvodeHasProjection<SystemType>) {
      if (options_.projection) {
        check(CVodeSetProjFn(mem, &CvodeCore::projection_callback), "CVodeSetProjFn");
        check(CVodeSetProjErrEst(mem, options_.project_error ? SUNTRUE : SUNFALSE),
              "CVodeSetProjErrEst");
        check(CVodeSetEpsProj(mem, options_.projection_tolerance), "CVodeSetEpsProj");
        check(CVodeSetProjFrequency(mem, options_.projection_frequency), "CVodeSetProjFrequency");
      }
    }
  }

  void setup_linear_solver(void* mem, SUNContext ctx) {
    switch (options_.linear_solver) {
      case CvodeLinearSolver::dense:
        matrix_.reset(require_allocated(SUNDenseMatrix(n_, n_, ctx)));
        linear_solver_.reset(require_allocated(SUNLinSol_Dense(y_.get(), matrix_.get(), ctx)));
        check(CVodeSetLinearSolver(mem, linear_solver_.get(), matrix_.get()),
              "CVodeSetLinearSolver");
        if constexpr (CvodeHasJacobian<SystemType>) {
          if (options_.use_system_jacobian) {
            check(CVodeSetJacFn(mem, &CvodeCore::jacobian_callback), "CVodeSetJacFn");
          }
        }
        break;
      case CvodeLinearSolver::band:
        matrix_.reset(require_allocated(
            SUNBandMatrix(n_, options_.upper_bandwidth, options_.lower_bandwidth, ctx)));
        linear_solver_.reset(require_allocated(SUNLinSol_Band(y_.get(), matrix_.get(), ctx)));
        check(CVodeSetLinearSolver(mem, linear_solver_.get(), matrix_.get()),
              "CVodeSetLinearSolver");
        if constexpr (CvodeHasBandJacobian<SystemType>) {
          if (options_.use_system_jacobian) {
            check(CVodeSetJacFn(mem, &CvodeCore::jacobian_callback), "CVodeSetJacFn");
          }
        }
        break;
      case CvodeLinearSolver::gmres: {
        int side = SUN_PREC_NONE;
        if constexpr (CvodeHasPreconditioner<SystemType>) {
          if (options_.preconditioning == CvodePreconditioning::left) {
            side = SUN_PREC_LEFT;
          } else if (options_.preconditioning == CvodePreconditioning::right) {
            side = SUN_PREC_RIGHT;
          }
        }
        linear_solver_.reset(
            require_allocated(SUNLinSol_SPGMR(y_.get(), side, options_.krylov_dimension, ctx)));
        check(CVodeSetLinearSolver(mem, linear_solver_.get(), nullptr), "CVodeSetLinearSolver");
        if constexpr (CvodeHasPreconditioner<SystemType>) {
          if (side != SUN_PREC_NONE) {
            check(CVodeSetPreconditioner(mem, &CvodeCore::preconditioner_setup_callback,
                                         &CvodeCore::preconditioner_solve_callback),
                  "CVodeSetPreconditioner");
          }
        }
        break;
      }
    }
  }

  // ---- stepping ----------------------------------------------------------------------------
  void check_output_time(double t_out, const char* who) const {
    if (!std::isfinite(t_out)) {
      throw std::invalid_argument(std::string("tumble::Cvode::") + who + ": the time " +
                                  format_number(t_out) + " is not finite");
    }
    if (t_out < t_) {
      throw std::invalid_argument(std::string("tumble::Cvode::") + who + ": the time " +
                                  format_number(t_out) + " is behind the current time " +
                                  format_number(t_));
    }
    if (options_.stop_time && t_out > *options_.stop_time) {
      throw std::invalid_argument(std::string("tumble::Cvode::") + who + ": the time " +
                                  format_number(t_out) + " is after the stop time " +
                                  format_number(*options_.stop_time));
    }
  }

  /// One call of CVode(); throws IntegrationError on a failure flag.
  int call_cvode(double tout, int task) {
    report_.clear();
    errors_.clear();
    sun_real reached = t_;
    const int flag = CVode(mem_.get(), tout, y_.get(), &reached, task);
    segment_started_ = true;
    if (std::isfinite(reached)) {
      t_ = reached;  // on failure CVODE returns the last time reached and the state there
    }
    if (flag < 0) {
      throw failure(flag);
    }
    return flag;
  }

  /// Events and the system's step action after CVode() returned successfully.
  void after_return(int flag) {
    bool changed = false;
    if (flag == CV_ROOT_RETURN) {
      ++roots_found_;
      check(CVodeGetRootInfo(mem_.get(), root_info_.data()), "CVodeGetRootInfo");
      if constexpr (CvodeHasRootAction<SystemType>) {
        changed = static_cast<bool>(
            system_.on_root(t_, view(y_.get()), std::span<const int>(root_info_)));
      }
    }
    if constexpr (CvodeHasStepAction<SystemType>) {
      changed = static_cast<bool>(system_.on_step(t_, view(y_.get()))) || changed;
    }
    if (changed) {
      reinitialize();
    }
  }

  void reinitialize() {
    if (segment_started_) {
      add_segment(accumulated_);  // CVodeReInit resets CVODE's counters
    }
    segment_started_ = false;
    check(CVodeReInit(mem_.get(), t_, y_.get()), "CVodeReInit");
    if (options_.stop_time && t_ < *options_.stop_time) {
      check(CVodeSetStopTime(mem_.get(), *options_.stop_time), "CVodeSetStopTime");
    }
    ++reinits_;
  }

  IntegrationError failure(int flag) const {
    const std::string name = flag_name(flag);
    std::string what = "tumble::Cvode: CVODE failed with " + name + " at t = " + format_number(t_) +
                       ": " + flag_cause(flag);
    if (flag == CV_TOO_MUCH_WORK) {
      what += " (max_steps = " + std::to_string(options_.max_steps) + ")";
    }
    if (report_.exception) {
      what += "; " + std::string(report_.exception_where) +
              " threw at t = " + format_number(report_.exception_time) + ": " +
              exception_message(report_.exception);
    } else if (report_.has_recoverable) {
      what += "; last recoverable failure: " + std::string(report_.recoverable_where) +
              " at t = " + format_number(report_.recoverable_time) + ": " +
              report_.recoverable_message.data();
    }
    if (errors_.has_message) {
      what += " [" + std::string(errors_.message.data()) + "]";
    }
    return IntegrationError(what, flag, name, t_, report_.exception);
  }

  /// Adds CVODE's counters of the current segment (since the last (re)initialization) to s.
  void add_segment(CvodeStatistics& s) const {
    void* mem = mem_.get();
    long steps = 0, rhs = 0, setups = 0, etf = 0;
    int qlast = 0, qcur = 0;
    sun_real h0 = 0, hlast = 0, hcur = 0, tcur = 0;
    if (CVodeGetIntegratorStats(mem, &steps, &rhs, &setups, &etf, &qlast, &qcur, &h0, &hlast, &hcur,
                                &tcur) == CV_SUCCESS) {
      s.steps += steps;
      s.rhs_evals += rhs;
      s.linear_solver_setups += setups;
      s.error_test_failures += etf;
      s.last_order = qlast;
      s.current_order = qcur;
      s.last_step = hlast;
      s.current_step = hcur;
    }
    long nni = 0, nncf = 0;
    if (CVodeGetNonlinSolvStats(mem, &nni, &nncf) == CV_SUCCESS) {
      s.nonlinear_iterations += nni;
      s.nonlinear_convergence_failures += nncf;
    }
    // The getters below fail (and leave 0) when the feature is not in use, e.g. no linear
    // solver with Adams, no projection, no roots.
    auto add = [](long& total, auto getter, void* m) {
      long value = 0;
      if (getter(m, &value) >= 0) {
        total += value;
      }
    };
    if (linear_solver_) {
      add(s.jacobian_evals, &CVodeGetNumJacEvals, mem);
      add(s.linear_rhs_evals, &CVodeGetNumLinRhsEvals, mem);
      add(s.linear_iterations, &CVodeGetNumLinIters, mem);
      add(s.preconditioner_setups, &CVodeGetNumPrecEvals, mem);
      add(s.preconditioner_solves, &CVodeGetNumPrecSolves, mem);
    }
    if (root_count_ > 0) {
      add(s.root_evals, &CVodeGetNumGEvals, mem);
    }
    if (projecting()) {
      add(s.projections, &CVodeGetNumProjEvals, mem);
      add(s.projection_failures, &CVodeGetNumProjFails, mem);
    }
  }

  [[nodiscard]] bool projecting() const noexcept {
    return CvodeHasProjection<SystemType> && options_.projection;
  }

  // ---- callbacks (C calling convention; nothing may throw out of them) ----------------------
  /// Runs f, turning exceptions into CVODE return values: RecoverableError -> 1 (retry with a
  /// smaller step) where CVODE supports recovery, anything else -> -1 (stop), stored for the
  /// IntegrationError.
  template <class F> int guarded(const char* where, double t, bool recoverable, F&& f) noexcept {
    try {
      return f();
    } catch (const RecoverableError& e) {
      if (recoverable) {
        report_.note_recoverable(where, t, e.what());
        return 1;
      }
      report_.exception = std::current_exception();
    } catch (...) {
      report_.exception = std::current_exception();
    }
    report_.exception_where = where;
    report_.exception_time = t;
    return -1;
  }

  static int rhs_callback(sun_real t, N_Vector y, N_Vector ydot, void* data) noexcept {
    auto& self = *static_cast<CvodeCore*>(data);
    return self.guarded("rhs()", t, true, [&] {
      VectorMap out = self.view(ydot);
      self.system_.rhs(t, self.cview(y), out);
      // One reduction catches NaN and inf in any component (inf - inf and NaN propagate).
      if (!std::isfinite(out.sum())) {
        self.report_.note_recoverable("rhs()", t,
                                      "the derivative has a non-finite component (NaN or inf)");
        return 1;
      }
      return 0;
    });
  }

  static int jacobian_callback(sun_real t, N_Vector y, N_Vector fy, SUNMatrix jac, void* data,
                               N_Vector, N_Vector, N_Vector) noexcept {
    auto& self = *static_cast<CvodeCore*>(data);
    return self.guarded("jacobian()", t, true, [&] {
      const auto n = static_cast<Eigen::Index>(self.n_);
      double sum = 0.0;
      if (SUNMatGetID(jac) == SUNMATRIX_BAND) {
        if constexpr (CvodeHasBandJacobian<SystemType>) {
          const BandMatrixMap j(SUNBandMatrix_Data(jac), n, SUNBandMatrix_LDim(jac),
                                SUNBandMatrix_StoredUpperBandwidth(jac),
                                SUNBandMatrix_UpperBandwidth(jac),
                                SUNBandMatrix_LowerBandwidth(jac));
          self.system_.jacobian(t, self.cview(y), self.cview(fy), j);
          sum = ConstVectorMap(SUNBandMatrix_Data(jac), SUNBandMatrix_LDim(jac) * n).sum();
        }
      } else {
        if constexpr (CvodeHasJacobian<SystemType>) {
          MatrixMap j(SUNDenseMatrix_Data(jac), n, n);
          self.system_.jacobian(t, self.cview(y), self.cview(fy), j);
          sum = j.sum();
        }
      }
      if (!std::isfinite(sum)) {
        self.report_.note_recoverable("jacobian()", t,
                                      "the Jacobian has a non-finite entry (NaN or inf)");
        return 1;
      }
      return 0;
    });
  }

  static int root_callback(sun_real t, N_Vector y, sun_real* gout, void* data) noexcept {
    auto& self = *static_cast<CvodeCore*>(data);
    // CVODE has no recoverable root-function failure: any exception stops (CV_RTFUNC_FAIL).
    return self.guarded("roots()", t, false, [&] {
      if constexpr (CvodeHasRoots<SystemType>) {
        VectorMap g(gout, self.root_count_);
        self.system_.roots(t, self.cview(y), g);
      }
      return 0;
    });
  }

  static int projection_callback(sun_real t, N_Vector ycur, N_Vector corr, sun_real eps,
                                 N_Vector err, void* data) noexcept {
    auto& self = *static_cast<CvodeCore*>(data);
    return self.guarded("project()", t, true, [&] {
      if constexpr (CvodeHasProjection<SystemType>) {
        VectorMap e = err != nullptr ? self.view(err) : VectorMap(nullptr, 0);
        self.system_.project(t, self.cview(ycur), self.view(corr), eps, e);
      }
      return 0;
    });
  }

  static int preconditioner_setup_callback(sun_real t, N_Vector y, N_Vector fy, sun_bool jok,
                                           sun_bool* jcur, sun_real gamma, void* data) noexcept {
    auto& self = *static_cast<CvodeCore*>(data);
    return self.guarded("precondition_setup()", t, true, [&] {
      if constexpr (CvodeHasPreconditioner<SystemType>) {
        const bool recomputed = static_cast<bool>(self.system_.precondition_setup(
            t, self.cview(y), self.cview(fy), jok != SUNFALSE, gamma));
        *jcur = recomputed ? SUNTRUE : SUNFALSE;
      }
      return 0;
    });
  }

  static int preconditioner_solve_callback(sun_real t, N_Vector y, N_Vector fy, N_Vector r,
                                           N_Vector z, sun_real gamma, sun_real delta, int lr,
                                           void* data) noexcept {
    auto& self = *static_cast<CvodeCore*>(data);
    return self.guarded("precondition_solve()", t, true, [&] {
      if constexpr (CvodeHasPreconditioner<SystemType>) {
        self.system_.precondition_solve(t, self.cview(y), self.cview(fy), self.cview(r),
                                        self.view(z), gamma, delta, lr);
      }
      return 0;
    });
  }

  // Declaration order is construction order; destruction runs backwards: the CVODE memory
  // first, then the solvers and vectors it uses, the SUNContext last, and the error capture
  // (which the SUNContext's handler points at) after that.
  System system_;
  CvodeOptions options_;
  sunindextype n_;
  double t_;
  int root_count_ = 0;
  ErrorCapture errors_;
  CallbackReport report_;
  std::vector<int> root_info_;
  CvodeStatistics accumulated_{};
  long roots_found_ = 0;
  long reinits_ = 0;
  bool segment_started_ = false;
  ContextHandle context_;
  NVectorHandle y_;
  NVectorHandle atol_;
  MatrixHandle matrix_;
  LinearSolverHandle linear_solver_;
  NonlinearSolverHandle nonlinear_solver_;
  CvodeMemoryHandle mem_;
};

}  // namespace detail

/// CVODE integrator of a system y' = f(t, y) (see CvodeSystem and the optional members above).
///
/// `System` is held by value (the integrator owns the system; reach it through system()), or by
/// reference when instantiated as Cvode<MySystem&>. Cvode is move-only; a moved-from Cvode may
/// only be destroyed or assigned to.
template <class System>
requires CvodeSystem<System>
class Cvode {
 public:
  using SystemType = std::remove_cvref_t<System>;

  /// Validates the options and the initial state (std::invalid_argument on a bad one), then
  /// creates and initializes CVODE at (t0, y0).
  Cvode(System system, double t0, const Eigen::Ref<const Eigen::VectorXd>& y0,
        CvodeOptions options = {}) {
    const int n = static_cast<int>(std::as_const(system).size());
    validate(options, n, t0);
    if (y0.size() != n) {
      throw std::invalid_argument("tumble::Cvode: the initial state has size " +
                                  std::to_string(y0.size()) + " but the system has size " +
                                  std::to_string(n));
    }
    if (!y0.allFinite()) {
      throw std::invalid_argument("tumble::Cvode: the initial state has a non-finite component");
    }
    if (options.projection && !CvodeHasProjection<SystemType>) {
      throw std::invalid_argument("tumble::CvodeOptions: 'projection' is on but the system has no "
                                  "project(t, y, corr, epsProj, err)");
    }
    if constexpr (CvodeHasRoots<SystemType>) {
      const int count = static_cast<int>(std::as_const(system).root_count());
      if (count < 0) {
        throw std::invalid_argument("tumble::Cvode: root_count() must be >= 0 (got " +
                                    std::to_string(count) + ")");
      }
      if constexpr (CvodeHasRootDirections<SystemType>) {
        int k = 0;
        for (const auto& d : std::as_const(system).root_directions()) {
          const int v = static_cast<int>(d);
          if (v < -1 || v > 1) {
            throw std::invalid_argument(
                "tumble::Cvode: root_directions() entries must be -1, 0 or +1 (got " +
                std::to_string(v) + ")");
          }
          ++k;
        }
        if (k != count) {
          throw std::invalid_argument("tumble::Cvode: root_directions() has " + std::to_string(k) +
                                      " entries for " + std::to_string(count) + " root functions");
        }
      }
    }
    core_ = std::make_unique<detail::CvodeCore<System>>(std::forward<System>(system), t0, y0,
                                                        std::move(options));
  }

  Cvode(const Cvode&) = delete;
  Cvode& operator=(const Cvode&) = delete;
  Cvode(Cvode&&) noexcept = default;
  Cvode& operator=(Cvode&&) noexcept = default;
  ~Cvode() = default;

  /// Integrates to t_out (CV_NORMAL: CVODE steps past t_out and interpolates) and returns the
  /// state there. Events on the way call on_root(). t_out must not be behind time() nor after
  /// the stop time. Throws IntegrationError when CVODE fails.
  ConstVectorMap advance(double t_out) { return core_->advance(t_out); }

  /// Takes one internal step (CV_ONE_STEP), or stops at a root or the stop time; returns the
  /// time reached. The state there is state().
  double step() { return core_->step(); }

  /// Advances to each output time in turn and calls observer(t, state()) there. The times must
  /// be increasing, the first not behind time() (it may equal it); all are checked before
  /// integrating (std::invalid_argument).
  template <class Times, class Observer>
  requires std::ranges::forward_range<const Times&> &&
      std::convertible_to < std::ranges::range_value_t<const Times&>,
  double > &&std::invocable<Observer&, double, ConstVectorMap> void integrate(const Times& times,
                                                                              Observer&& observer) {
    core_->integrate(times, observer);
  }
  template <class Observer>
  requires std::invocable<Observer&, double, ConstVectorMap>
  void integrate(std::initializer_list<double> times, Observer&& observer) {
    core_->integrate(times, observer);
  }

  /// The current state (a view of CVODE's vector; valid until the next call on this Cvode).
  [[nodiscard]] ConstVectorMap state() const noexcept { return core_->state(); }
  /// The current time.
  [[nodiscard]] double time() const noexcept { return core_->time(); }
  /// Restarts the integration from (t, y) (CVodeReInit), e.g. after the user changed the state.
  void reset(double t, const Eigen::Ref<const Eigen::VectorXd>& y) { core_->reset(t, y); }
  /// Counters since construction, summed over reinitializations.
  [[nodiscard]] CvodeStatistics statistics() const { return core_->statistics(); }

  [[nodiscard]] const CvodeOptions& options() const noexcept { return core_->options(); }
  [[nodiscard]] int size() const noexcept { return core_->size(); }
  [[nodiscard]] SystemType& system() noexcept { return core_->system(); }
  [[nodiscard]] const SystemType& system() const noexcept { return core_->system(); }
  /// CVODE's memory block, for CVodeSet*/CVodeGet* calls tumble does not wrap.
  [[nodiscard]] void* cvode_memory() const noexcept { return core_->memory(); }

 private:
  std::unique_ptr<detail::CvodeCore<System>> core_;
};

}  // namespace tumble
