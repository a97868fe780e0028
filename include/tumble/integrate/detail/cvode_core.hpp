#pragma once
// The machinery behind tumble::Cvode (integrate/cvode.hpp): detail::CvodeCore owns the SUNContext,
// the state vector, the matrix, the linear and nonlinear solvers and the CVODE memory (RAII
// handles from detail/sundials.hpp, destroyed in the reverse order of creation); it sets CVODE up
// from CvodeOptions and the system's optional members, calls CVode() and turns its failure flags
// into CvodeError (causes in words: detail/cvode_flags.hpp), restarts CVODE when an event or
// the step action changed the state, and sums the counters across restarts.
//
// The callbacks CVODE calls are static members with C linkage semantics: they view CVODE's vectors
// through Eigen maps (nothing allocated), and never let an exception cross into C. A
// RecoverableError, or a non-finite derivative or Jacobian, becomes CVODE's "recoverable failure"
// (it retries with a smaller step); any other exception is stored, CVODE is told to stop, and the
// CvodeError carries it as cause(). CVODE's own messages are captured (ErrorCapture) instead
// of being printed. Source: the CVODE user guide (SUNDIALS 6.4 / 7.x), "Using CVODE for IVP
// solution" and "User-supplied functions".

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
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
#include "tumble/core/cache_line.hpp"
#include "tumble/core/format.hpp"
#include "tumble/integrate/detail/cvode_flags.hpp"
#include "tumble/integrate/detail/cvode_report.hpp"
#include "tumble/integrate/detail/sundials.hpp"
#include "tumble/integrate/errors.hpp"
#include "tumble/integrate/options.hpp"
#include "tumble/integrate/system.hpp"

namespace tumble::detail {

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
                             format_double(*options_.stop_time) + " has been reached");
    }
    // With CV_ONE_STEP, tout only gives the direction and, on the first step, an upper bound
    // for CVODE's estimate of the initial step.
    const double tout = options_.stop_time ? *options_.stop_time : t_ + 1.0;
    const int flag = call_cvode(tout, CV_ONE_STEP);
    after_return(flag);
    return t_;
  }

  template <class Times, class Observer> void integrate(const Times& times, Observer& observer) {
    check_output_times("tumble::Cvode::integrate", t_, times);
    for (const auto& value : times) {
      const double tk = static_cast<double>(value);
      if (options_.stop_time && tk > *options_.stop_time) {
        throw std::invalid_argument("tumble::Cvode::integrate: output time " + format_double(tk) +
                                    " is after the stop time " +
                                    format_double(*options_.stop_time));
      }
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
      throw std::invalid_argument("tumble::Cvode::reset: the time " + format_double(t) +
                                  " is not before the stop time " +
                                  format_double(*options_.stop_time));
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
  /// Steps per call of CVode() at most (see call_cvode()).
  static constexpr long kStepChunk = 10000;

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
      throw CvodeError(what, flag, name, IntegrationFailure::solver, t_);
    }
  }

  void setup(const Eigen::Ref<const Eigen::VectorXd>& y0) {
    context_ = make_context(errors_);
    SUNContext ctx = context_.get();
    // Fused operations on y_ before CVodeInit: CVODE's work vectors are clones of it.
    y_ = make_serial_vector(n_, ctx, options_.fused_vector_operations);
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
                                  format_double(t_out) + " is not finite");
    }
    if (t_out < t_) {
      throw std::invalid_argument(std::string("tumble::Cvode::") + who + ": the time " +
                                  format_double(t_out) + " is behind the current time " +
                                  format_double(t_));
    }
    if (options_.stop_time && t_out > *options_.stop_time) {
      throw std::invalid_argument(std::string("tumble::Cvode::") + who + ": the time " +
                                  format_double(t_out) + " is after the stop time " +
                                  format_double(*options_.stop_time));
    }
  }

  /// One call of CVode(); throws CvodeError on a failure flag.
  ///
  /// CVODE runs in chunks of at most kStepChunk steps (CVodeSetMaxNumSteps) and is called again
  /// when a chunk ends with CV_TOO_MUCH_WORK (its state is intact then; the next call continues
  /// the same step sequence), until the options' per-call budget max_steps is spent (0: none).
  /// Disabling CVODE's limit (CVodeSetMaxNumSteps < 0) would let it loop for ever when its step
  /// falls to the rounding level of t (t + h == t: CVODE only warns), and a large budget would
  /// be spent in place (10^6 steps at a load's wall: 6 s); the chunks let tumble see that and
  /// stop with a CvodeError instead. Each chunk ends with a CVODE error message, captured;
  /// SUNDIALS 7 formats it on the heap, so a call of more than kStepChunk steps is the one place
  /// where advance() may allocate there.
  int call_cvode(double tout, int task) {
    report_.clear();
    const long budget = options_.max_steps;
    long taken = 0;  // steps of this call
    for (;;) {
      errors_.clear();
      const long chunk = budget > 0 ? std::min(kStepChunk, budget - taken) : kStepChunk;  // > 0
      check(CVodeSetMaxNumSteps(mem_.get(), chunk), "CVodeSetMaxNumSteps");  // a store in CVODE
      const double before = t_;
      sun_real reached = t_;
      const int flag = CVode(mem_.get(), tout, y_.get(), &reached, task);
      segment_started_ = true;
      if (std::isfinite(reached)) {
        t_ = reached;  // on failure CVODE returns the last time reached and the state there
      }
      if (flag == CV_TOO_MUCH_WORK) {
        // `chunk` steps moved t by at most a few units in its last place each: CVODE's step is at
        // the rounding level of t and the integration cannot reach tout.
        const double rounding =
            4.0 * std::numeric_limits<double>::epsilon() * std::max(std::abs(before), std::abs(t_));
        if (std::abs(t_ - before) <= static_cast<double>(chunk) * rounding) {
          throw stalled(before, chunk);
        }
        taken += chunk;
        if (budget == 0 || taken < budget) {
          continue;
        }
      }
      if (flag == CV_RTFUNC_FAIL) {
        // CVODE returns from a failed root check without setting tret (SUNDIALS 6 and 7), so
        // `reached` is still the last return: take the time it had stepped to, tn, and the state
        // there, as on its other failures, so that time() is the time reached.
        sun_real tn = t_;
        if (CVodeGetCurrentTime(mem_.get(), &tn) == CV_SUCCESS && std::isfinite(tn) && tn != t_ &&
            CVodeGetDky(mem_.get(), tn, 0, y_.get()) == CV_SUCCESS) {
          t_ = tn;
        }
      }
      if (flag < 0) {
        throw failure(flag);
      }
      if (flag == CV_SUCCESS && task == CV_NORMAL) {
        sun_real tn = tout;
        (void)CVodeGetCurrentTime(mem_.get(), &tn);
        if (tn < tout) {  // stepping past tout, CVODE never returns behind it but by underflow
          sun_real h = 0.0;
          (void)CVodeGetCurrentStep(mem_.get(), &h);
          (void)CVodeGetDky(mem_.get(), tn, 0, y_.get());  // the state where it stopped
          t_ = tn;
          throw underflow_failure(tout, tn, h, report_);
        }
      }
      return flag;
    }
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

  CvodeError failure(int flag) const { return cvode_failure(flag, t_, options_, report_, errors_); }

  /// The integration made no progress in time over `steps` steps (see call_cvode()).
  CvodeError stalled(double before, long steps) const {
    sun_real h = 0.0;
    (void)CVodeGetCurrentStep(mem_.get(), &h);
    return stalled_failure(before, t_, h, steps, report_);
  }

  /// Adds CVODE's counters of the current segment (since the last (re)initialization) to s.
  void add_segment(CvodeStatistics& s) const {
    add_counters(mem_.get(), linear_solver_ != nullptr, root_count_ > 0, projecting(), s);
  }

  [[nodiscard]] bool projecting() const noexcept {
    return CvodeHasProjection<SystemType> && options_.projection;
  }

  // ---- callbacks (C calling convention; nothing may throw out of them) ----------------------
  /// Runs f, turning exceptions into CVODE return values: RecoverableError -> 1 (retry with a
  /// smaller step) where CVODE supports recovery, anything else -> -1 (stop), stored for the
  /// CvodeError.
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
  CacheLineVector<int> root_info_;  ///< written at each root found: lines of its own
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

}  // namespace tumble::detail
