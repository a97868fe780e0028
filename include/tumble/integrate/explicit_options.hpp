#pragma once
// The options and statistics of tumble::OdeintIntegrator (explicit_integrator.hpp), without
// Boost: the method (OdeintMethod), tolerances and step options (OdeintOptions), the counters
// (OdeintStatistics), and validate(), which names a bad option in a std::invalid_argument before
// anything is integrated.

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace tumble {

/// Boost.Odeint's embedded Runge-Kutta pairs, each under Odeint's step-size controller.
enum class OdeintMethod {
  /// runge_kutta_fehlberg78: order 8 with a 7th-order error estimate, 13 stages. The most
  /// accurate per right-hand side at tight tolerances. Odeint has no dense output for it.
  fehlberg78,
  /// runge_kutta_dopri5: Dormand-Prince 5(4), 6 stages plus first-same-as-last, with Odeint's
  /// dense output (its calc_state), which locates events.
  dopri5,
  /// runge_kutta_cash_karp54: Cash-Karp 5(4), 6 stages; no dense output.
  cash_karp54,
};

/// What OdeintIntegrator does. Every option is validated when the integrator is constructed.
struct OdeintOptions {
  OdeintMethod method = OdeintMethod::fehlberg78;
  /// Odeint's error test per component i: |err_i| <= atol + rtol (|y_i| + h |y'_i|).
  double rtol = 1e-8;                                         ///< > 0
  double atol = 1e-8;                                         ///< >= 0
  double max_step = std::numeric_limits<double>::infinity();  ///< > 0
  double initial_step = 0.0;  ///< 0: estimated (Hairer, Norsett and Wanner, Sec. II.4)
  /// Step attempts (accepted and rejected) allowed in one advance(), or between two output times
  /// of integrate(). Past it the integrator throws: StiffSceneError when the steps looked like
  /// those of an explicit method on a stiff scene, ExplicitIntegrationError otherwise.
  long max_steps = 100000;
  /// integrate() with Dormand-Prince on a scene without events: step freely and read the output
  /// times off Odeint's dense output (its continuous extension, order 4) instead of stepping to
  /// each of them. When output times are denser than the steps the accuracy needs, this saves
  /// the extra steps. The state handed to the observer is then interpolated (quaternions
  /// projected onto |p| = 1); the integrator's own state is always a step result, and advance()
  /// always steps to t_out. Ignored for the pairs without dense output (Fehlberg 7(8),
  /// Cash-Karp) and for scenes with events.
  bool interpolate_outputs = true;
  /// Euler parameters: the constraint stabilization terms in the right-hand side
  /// (SceneWorkspace::stabilize_constraints). Off by default: the quaternions are projected onto
  /// |p| = 1 after every step, and the terms, which act on the Runge-Kutta stages off the
  /// manifold, made Fehlberg 7(8) take 400 steps where 268 sufficed for the same error (tumbling
  /// body, quasi-velocities, tol 1e-10; docs/benchmarks.md).
  bool stabilize_quaternions = false;
};

/// Counters since construction.
struct OdeintStatistics {
  long steps = 0;           ///< accepted steps
  long rejected_steps = 0;  ///< failed error tests, non-finite trial states, too-deep chart steps
  long rhs_evals = 0;       ///< right-hand side evaluations, including event location
  long chart_switches = 0;  ///< re-centerings and MRP shadow switches
  long events = 0;          ///< user events located and acted on
};

/// Throws std::invalid_argument naming the first bad option.
inline void validate(const OdeintOptions& o) {
  const auto bad = [](const char* name, double v, const char* rule) {
    throw std::invalid_argument(std::string("tumble::OdeintOptions: ") + name + " = " +
                                std::to_string(v) + ", but it must be " + rule);
  };
  if (!(o.rtol > 0.0) || !std::isfinite(o.rtol)) {
    bad("rtol", o.rtol, "finite and > 0");
  }
  if (!(o.atol >= 0.0) || !std::isfinite(o.atol)) {
    bad("atol", o.atol, "finite and >= 0");
  }
  if (!(o.max_step > 0.0)) {
    bad("max_step", o.max_step, "> 0");
  }
  if (!(o.initial_step >= 0.0) || !std::isfinite(o.initial_step)) {
    bad("initial_step", o.initial_step, "finite and >= 0 (0: estimated)");
  }
  if (o.max_steps < 1) {
    bad("max_steps", static_cast<double>(o.max_steps), ">= 1");
  }
}

}  // namespace tumble
