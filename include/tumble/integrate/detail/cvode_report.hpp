#pragma once
// What tumble::Cvode's core reports, kept apart from its machinery: CallbackReport (what a
// callback failed with, recorded without allocating inside C code), the CvodeError built
// from a CVODE failure flag or from a stalled integration (flag, cause in words, step limit,
// callback report, CVODE's message), and add_counters(), which reads CVODE's counters of one
// integration segment (CVodeGet*, "Optional output functions" of the CVODE user guide) into
// CvodeStatistics.

#include <array>
#include <cstdio>
#include <exception>
#include <string>
#include <utility>

#include <cvode/cvode.h>
#include <cvode/cvode_ls.h>
#include <cvode/cvode_proj.h>

#include "tumble/core/format.hpp"
#include "tumble/integrate/detail/callback_error.hpp"
#include "tumble/integrate/detail/cvode_flags.hpp"
#include "tumble/integrate/detail/sundials.hpp"
#include "tumble/integrate/errors.hpp"
#include "tumble/integrate/options.hpp"

namespace tumble::detail {

/// What a callback reported: an unrecoverable exception (rethrown as the CvodeError's
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

/// "; <what a callback reported>", or "" when it reported nothing.
inline std::string callback_note(const CallbackReport& r) {
  if (r.exception) {
    return "; " + callback_threw(r.exception_where, r.exception_time, r.exception);
  }
  if (r.has_recoverable) {
    return "; last recoverable failure: " + std::string(r.recoverable_where) +
           " at t = " + format_double(r.recoverable_time) + ": " + r.recoverable_message.data();
  }
  return "";
}

/// The CvodeError for a failure flag of CVode() at time t: the flag, its cause in words,
/// the step limit for CV_TOO_MUCH_WORK, what a callback reported, CVODE's own message.
inline CvodeError cvode_failure(int flag, double t, const CvodeOptions& o, const CallbackReport& r,
                                const ErrorCapture& e) {
  const std::string name = flag_name(flag);
  std::string what = "tumble::Cvode: CVODE failed with " + name + " at t = " + format_double(t) +
                     ": " + flag_cause(flag);
  if (flag == CV_TOO_MUCH_WORK) {
    what += " (max_steps = " + std::to_string(o.max_steps) + ")";
  }
  what += callback_note(r);
  if (e.has_message) {
    what += " [" + std::string(e.message.data()) + "]";
  }
  // An exception a callback threw stopped it, whatever flag CVODE returned for it (a Jacobian's
  // is CV_LSETUP_FAIL): reason() callback, as in the explicit integrator.
  const IntegrationFailure reason = r.exception ? IntegrationFailure::callback : flag_reason(flag);
  return CvodeError(what, flag, name, reason, t, r.exception);
}

/// The CvodeError of a stalled integration (CV_TOO_MUCH_WORK, reason step_size) at t, with the
/// callbacks' note; CVODE may retry after an exception of rhs() and cut the step to the rounding
/// level of t (seen with Adams' fixed-point iteration, SUNDIALS 6.4): the exception is then the
/// reason.
inline CvodeError stall_error(std::string what, double t, const CallbackReport& r) {
  what += callback_note(r);
  return CvodeError(what, CV_TOO_MUCH_WORK, flag_name(CV_TOO_MUCH_WORK),
                    r.exception ? IntegrationFailure::callback : IntegrationFailure::step_size, t,
                    r.exception);
}

/// CVODE's step fell below the smallest normal double (a denormal h): its test for having passed
/// tout, (tn - tout) * h >= 0, then underflows to zero and CVode() returns success with the state
/// extrapolated from tn to tout (seen with BDF on Andrews' mechanism at atol = 1e-11: h = 8e-320
/// at tn = 0.010176, "reached" 0.0102, 0.0105, ... with tn unchanged, SUNDIALS 6.4). tumble
/// refuses that state and reports the stall it is.
inline CvodeError underflow_failure(double tout, double tn, double h, const CallbackReport& r) {
  std::string what =
      "tumble::Cvode: the integration stalled at t = " + format_double(tn) +
      ": CVODE's step size fell to h = " + format_double(h) +
      ", far below the rounding level of t, and it returned t = " + format_double(tout) +
      " by extrapolating from there; the solution changes too fast for the "
      "tolerances, or the system has a singularity here";
  return stall_error(std::move(what), tn, r);
}

/// The CvodeError (CV_TOO_MUCH_WORK) for an integration whose last `steps` steps, of size about
/// h, moved t only from `before` to t.
inline CvodeError stalled_failure(double before, double t, double h, long steps,
                                  const CallbackReport& r) {
  std::string what =
      "tumble::Cvode: the integration stalled at t = " + format_double(t) + ": " +
      std::to_string(steps) + " internal steps moved t from " + format_double(before) + " by " +
      format_double(t - before) + " (step h = " + format_double(h) +
      ", at the rounding level of t), so the requested time cannot be reached; the solution "
      "changes too fast for the precision of t (shift the time origin), or the system has a "
      "singularity here";
  return stall_error(std::move(what), t, r);
}

/// Adds CVODE's counters of the current segment (since the last (re)initialization) to s. The
/// flags say which optional counters exist (a linear solver, root functions, projection).
inline void add_counters(void* mem, bool has_linear_solver, bool has_roots, bool projecting,
                         CvodeStatistics& s) {
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
  if (has_linear_solver) {
    add(s.jacobian_evals, &CVodeGetNumJacEvals, mem);
    add(s.linear_rhs_evals, &CVodeGetNumLinRhsEvals, mem);
    add(s.linear_iterations, &CVodeGetNumLinIters, mem);
    add(s.preconditioner_setups, &CVodeGetNumPrecEvals, mem);
    add(s.preconditioner_solves, &CVodeGetNumPrecSolves, mem);
  }
  if (has_roots) {
    add(s.root_evals, &CVodeGetNumGEvals, mem);
  }
  if (projecting) {
    add(s.projections, &CVodeGetNumProjEvals, mem);
    add(s.projection_failures, &CVodeGetNumProjFails, mem);
  }
}

}  // namespace tumble::detail
