#pragma once
// The options and statistics of tumble::OdeintIntegrator (explicit_integrator.hpp), without
// Boost: the method (OdeintMethod), the shared tolerances and step budget (integrate/common.hpp)
// and Odeint's own options (OdeintOptions), the counters (OdeintStatistics), and validate(),
// which names a bad option in a std::invalid_argument before anything is integrated.

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "tumble/integrate/common.hpp"

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

/// What OdeintIntegrator does: the vocabulary both integrators share (integrate/common.hpp),
/// then Odeint's own options. Every option is validated when the integrator is constructed.
struct OdeintOptions {
  // --- shared with SceneIntegratorOptions (integrate/common.hpp) ---
  /// Odeint's error test per entry i: |err_i| <= atol_i + rtol (|y_i| + h |y'_i|), in the
  /// maximum norm over i.
  double rtol = SharedDefaults::rtol;             ///< > 0
  AbsoluteTolerance atol = SharedDefaults::atol;  ///< >= 0: one value, or one per entry of y
  /// Step attempts (accepted and rejected) allowed in one advance(), or between two output times
  /// of integrate(); 0: no limit (the default). Past it the integrator throws: StiffSceneError
  /// when the steps looked like those of an explicit method on a stiff scene,
  /// ExplicitIntegrationError (IntegrationFailure::step_budget) otherwise.
  long max_steps = SharedDefaults::max_steps;
  double initial_step = 0.0;  ///< 0: estimated (Hairer, Norsett and Wanner, Sec. II.4)
  double max_step = std::numeric_limits<double>::infinity();  ///< > 0
  // --- Odeint only ---
  OdeintMethod method = OdeintMethod::fehlberg78;
  /// The stiffness test, every this many step attempts (over advance() calls; 0: never). When
  /// at least 10 % of the attempts of the window failed the error test, the largest eigenvalue
  /// modulus rho of the Jacobian is estimated (about 30 right-hand sides), and with h rho > 1
  /// for the window's mean step h the integrator throws StiffSceneError: the steps are held at
  /// the method's stability bound, not set by the accuracy asked for. Without rejections the
  /// test costs nothing. The front door (integrate/auto.hpp) switches to BDF on it.
  long stiffness_window = 1000;
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
  /// body, quasi-velocities, tol 1e-10; docs/benchmarks/floors.md).
  bool stabilize_quaternions = false;
};

/// The shared counters (integrate/common.hpp), since construction.
struct OdeintStatistics {
  long steps = 0;           ///< accepted steps
  long rejected_steps = 0;  ///< failed error tests, non-finite trial states, too-deep chart steps
  long rhs_evals = 0;       ///< right-hand side evaluations, including event location
  long chart_switches = 0;  ///< re-centerings and MRP shadow switches
  long projections = 0;     ///< projections of Euler parameters onto |p| = 1 (one per step)
  long events = 0;          ///< user events located and acted on
  /// Accepted steps of a mechanism whose error test asked less than rtol and atol, because the
  /// constraint solve at the step's start was too ill-conditioned (near a singular position) to
  /// give the right-hand side to that accuracy, and the largest tolerance they were tested at
  /// (0 when none was; docs/mechanisms.md, "Singular positions").
  long relaxed_steps = 0;
  double loosest_tolerance = 0.0;
};
static_assert(IntegratorStatisticsLike<OdeintStatistics>);
static_assert(IntegratorOptionsLike<OdeintOptions>);

/// Throws std::invalid_argument naming the first bad option.
inline void validate(const OdeintOptions& o, long n = -1) {
  detail::validate_shared("tumble::OdeintOptions", o.rtol, o.atol, o.max_steps, o.initial_step,
                          o.max_step, n, /*atol_may_be_zero=*/true);
  if (o.method != OdeintMethod::fehlberg78 && o.method != OdeintMethod::dopri5 &&
      o.method != OdeintMethod::cash_karp54) {
    throw std::invalid_argument("tumble::OdeintOptions: 'method' is not an OdeintMethod");
  }
  if (o.stiffness_window < 0) {
    throw std::invalid_argument("tumble::OdeintOptions: 'stiffness_window' must be >= 0, 0 for "
                                "no stiffness test (got " +
                                std::to_string(o.stiffness_window) + ")");
  }
}

}  // namespace tumble
