#pragma once
// The vocabulary both integrators share (SceneIntegrator over CVODE, OdeintIntegrator over
// Boost.Odeint, and the front door AutoIntegrator), without SUNDIALS or Boost. Each integrator's
// options struct has these members under the same names, with the same meanings and defaults;
// what only one integrator has (its method, CVODE's linear solver, Odeint's dense output) sits
// beside them. Code written for one integrator compiles for the other by changing the type:
//
//   Integrator::Options o;          // OdeintOptions or SceneIntegratorOptions
//   o.rtol = 1e-9;                  // relative tolerance, > 0
//   o.atol = 1e-12;                 // absolute tolerance: one value, or one per entry of y
//   o.max_steps = 10000;            // step attempts per advance(), 0: no limit (the default)
//   o.initial_step = 0.0;           // 0: estimated
//   o.max_step = 0.5;               // upper bound of |h|, +inf: none (the default)
//
// The local error test of a step asks, per entry i of y, for an error estimate e_i below
// atol_i + rtol |y_i| (CVODE: in the weighted root-mean-square norm over i; Odeint: in the
// maximum norm, with |y_i| + h |y'_i| in place of |y_i|). The same tolerances therefore give
// errors of the same order, not equal errors: compare methods by the error they reach
// (docs/benchmarks/work-precision.md), not by their tolerances.
//
// Statistics (IntegratorStatisticsLike): steps, rejected_steps, rhs_evals, chart_switches,
// projections, events under the same names in both. Errors: integrate/errors.hpp.

#include <cmath>
#include <concepts>
#include <limits>
#include <stdexcept>
#include <string>
#include <variant>

#include <Eigen/Core>

#include "tumble/core/format.hpp"

namespace tumble {

/// An absolute tolerance: one value for every entry of y, or one per entry.
using AbsoluteTolerance = std::variant<double, Eigen::VectorXd>;

/// The defaults of the shared options, the same in every integrator.
struct SharedDefaults {
  static constexpr double rtol = 1e-8;
  static constexpr double atol = 1e-8;
  static constexpr long max_steps = 0;  ///< no limit
};

/// The counters every integrator's statistics have, under these names: accepted steps, steps
/// rejected (failed error tests and, CVODE, failed nonlinear solves; Odeint, also non-finite or
/// too-deep trial states), right-hand side evaluations by the integrator, chart switches
/// (re-centerings and MRP shadow switches), projections onto the constraints (Euler parameters'
/// |p| = 1), and user events acted on.
template <class S>
concept IntegratorStatisticsLike = requires(const S& s) {
  { s.steps } -> std::convertible_to<long>;
  { s.rejected_steps } -> std::convertible_to<long>;
  { s.rhs_evals } -> std::convertible_to<long>;
  { s.chart_switches } -> std::convertible_to<long>;
  { s.projections } -> std::convertible_to<long>;
  { s.events } -> std::convertible_to<long>;
};

/// The options every integrator's options have, under these names.
template <class O>
concept IntegratorOptionsLike = requires(O& o) {
  o.rtol = 1e-6;
  o.atol = 1e-6;
  o.atol = Eigen::VectorXd();
  o.max_steps = 0L;
  o.initial_step = 0.0;
  o.max_step = 1.0;
};

namespace detail {

/// Validates the shared options of `who` (e.g. "tumble::OdeintOptions") for a state of size n
/// (n < 0: unknown, the size of a per-entry atol is not checked); throws std::invalid_argument
/// naming the first bad one. atol: > 0 for CVODE, >= 0 for Odeint (`atol_may_be_zero`).
inline void validate_shared(const std::string& who, double rtol, const AbsoluteTolerance& atol,
                            long max_steps, double initial_step, double max_step, long n,
                            bool atol_may_be_zero) {
  const auto fail = [&](const std::string& what) {
    throw std::invalid_argument(who + ": " + what);
  };
  const char* atol_rule = atol_may_be_zero ? ">= 0" : "> 0";
  const auto atol_ok = [&](double a) {
    return std::isfinite(a) && (atol_may_be_zero ? a >= 0.0 : a > 0.0);
  };
  if (!(std::isfinite(rtol) && rtol > 0.0)) {
    fail("'rtol' must be finite and > 0 (got " + format_double(rtol) + ")");
  }
  if (const auto* a = std::get_if<double>(&atol)) {
    if (!atol_ok(*a)) {
      fail("'atol' must be finite and " + std::string(atol_rule) + " (got " + format_double(*a) +
           ")");
    }
  } else {
    const auto& v = std::get<Eigen::VectorXd>(atol);
    if (n >= 0 && v.size() != n) {
      fail("'atol' per entry must have the state's size " + std::to_string(n) + " (got " +
           std::to_string(v.size()) + ")");
    }
    for (Eigen::Index i = 0; i < v.size(); ++i) {
      if (!atol_ok(v[i])) {
        fail("'atol' entry " + std::to_string(i) + " must be finite and " + atol_rule + " (got " +
             format_double(v[i]) + ")");
      }
    }
  }
  if (max_steps < 0) {
    fail("'max_steps' must be >= 0, 0 for no limit (got " + std::to_string(max_steps) + ")");
  }
  if (!(std::isfinite(initial_step) && initial_step >= 0.0)) {
    fail("'initial_step' must be finite and >= 0, 0 to estimate it (got " +
         format_double(initial_step) + ")");
  }
  if (!(max_step > 0.0)) {  // also rejects NaN; +inf means no bound
    fail("'max_step' must be > 0 (got " + format_double(max_step) + ")");
  }
}

/// Every integrator's integrate() (and the ensembles') checks its output times with this before
/// it integrates anything: each finite, none before the one before it, the first not before
/// `t_now` (`when`: "the current time", "the start time"). A time repeated gives the same state
/// twice. \throws std::invalid_argument naming `who` and the first bad time.
template <class Times>
void check_output_times(const char* who, double t_now, const Times& times,
                        const char* when = "the current time") {
  double last = t_now;
  for (const auto& value : times) {
    const double t = static_cast<double>(value);
    if (!std::isfinite(t) || t < last) {
      throw std::invalid_argument(std::string(who) +
                                  ": the output times must be finite, non-decreasing and not "
                                  "before " +
                                  when + " " + format_double(t_now) + "; found " +
                                  format_double(t) + " after " + format_double(last));
    }
    last = t;
  }
}

/// atol_i: the scalar, or entry i of the per-entry tolerance.
[[nodiscard]] inline double atol_at(const AbsoluteTolerance& atol, Eigen::Index i) {
  if (const auto* a = std::get_if<double>(&atol)) {
    return *a;
  }
  return std::get<Eigen::VectorXd>(atol)[i];
}

}  // namespace detail
}  // namespace tumble
