#pragma once
// The causes of CVODE's failure flags in words, for tumble::CvodeError's message, and
// the shared IntegrationFailure code of each.
// Source: the CVODE user guide, "CVODE solver function" (return values of CVode) and the
// descriptions of the user-supplied functions (right-hand side, root, projection, Jacobian,
// preconditioner), SUNDIALS 6.4 / 7.x.

#include <cvode/cvode.h>

#include "tumble/integrate/errors.hpp"

namespace tumble::detail {

/// What a negative CVode() return flag means and what the user can do about it.
[[nodiscard]] inline const char* flag_cause(int flag) noexcept {
  switch (flag) {
    case CV_TOO_MUCH_WORK:
      return "the solver took the per-call step limit of internal steps without reaching the "
             "requested time; raise max_steps (0: no limit), or, if the "
             "steps are tiny because the problem is stiff, use CvodeMethod::bdf";
    case CV_TOO_MUCH_ACC:
      return "the requested accuracy is beyond what double precision can deliver here; loosen "
             "rtol/atol";
    case CV_ERR_FAILURE:
      return "the local error test failed max_error_test_failures times in one step or with "
             "|h| = min_step; the solution may have a singularity or a discontinuity, or "
             "min_step is too large for the tolerances";
    case CV_CONV_FAILURE:
      return "the nonlinear solver failed to converge repeatedly in one step or with "
             "|h| = min_step; for a stiff problem use BDF (Newton), check a user Jacobian";
    case CV_LINIT_FAIL:
      return "the linear solver's initialization failed";
    case CV_LSETUP_FAIL:
      return "the linear solver setup failed unrecoverably (the Jacobian or the preconditioner "
             "setup failed)";
    case CV_LSOLVE_FAIL:
      return "the linear solve failed unrecoverably (e.g. the preconditioner solve failed)";
    case CV_RHSFUNC_FAIL:
      return "the right-hand side failed unrecoverably (the system's rhs() threw)";
    case CV_FIRST_RHSFUNC_ERR:
      return "the right-hand side reported a recoverable error at its very first call, at the "
             "initial state, where a smaller step cannot help; check the initial state";
    case CV_REPTD_RHSFUNC_ERR:
      return "the right-hand side reported recoverable errors (RecoverableError or a "
             "non-finite derivative) repeatedly, and reducing the step did not avoid them";
    case CV_UNREC_RHSFUNC_ERR:
      return "the right-hand side reported a recoverable error that could not be recovered "
             "from (it came after an error-test failure at order 1)";
    case CV_RTFUNC_FAIL:
      return "the root function failed (the system's roots() threw)";
    case CV_NLS_INIT_FAIL:
      return "the nonlinear solver's initialization failed";
    case CV_NLS_SETUP_FAIL:
      return "the nonlinear solver's setup failed";
    case CV_NLS_FAIL:
      return "the nonlinear solver failed unrecoverably";
    case CV_CONSTR_FAIL:
      return "the inequality constraints could not be met";
    case CV_MEM_FAIL:
      return "a memory allocation inside SUNDIALS failed";
    case CV_ILL_INPUT:
      return "an input to CVODE was illegal (see the CVODE message)";
    case CV_TOO_CLOSE:
      return "the output time is too close to the start time to begin the integration";
    case CV_BAD_T:
      return "the requested time is outside the last step taken";
    case CV_VECTOROP_ERR:
      return "a vector operation failed";
    case CV_PROJFUNC_FAIL:
      return "the projection failed unrecoverably (the system's project() threw)";
    case CV_REPTD_PROJFUNC_ERR:
      return "the projection reported recoverable errors repeatedly";
    default:
      return "CVODE failed (see the CVODE message)";
  }
}

/// The shared IntegrationFailure code of a negative CVode() return flag.
[[nodiscard]] inline IntegrationFailure flag_reason(int flag) noexcept {
  switch (flag) {
    case CV_TOO_MUCH_WORK:
      return IntegrationFailure::step_budget;
    case CV_TOO_MUCH_ACC:
    case CV_TOO_CLOSE:
      return IntegrationFailure::step_size;
    case CV_ERR_FAILURE:
      return IntegrationFailure::error_test;
    case CV_CONV_FAILURE:
    case CV_NLS_FAIL:
      return IntegrationFailure::convergence;
    case CV_RHSFUNC_FAIL:
    case CV_FIRST_RHSFUNC_ERR:
    case CV_REPTD_RHSFUNC_ERR:
    case CV_UNREC_RHSFUNC_ERR:
    case CV_RTFUNC_FAIL:
    case CV_PROJFUNC_FAIL:
    case CV_REPTD_PROJFUNC_ERR:
      return IntegrationFailure::callback;
    default:
      return IntegrationFailure::solver;
  }
}

}  // namespace tumble::detail
