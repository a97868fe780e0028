#pragma once
// The Fehlberg 7(8) floor's plain loop (floors/odeint.cpp, "floor Odeint RKF78 loop"; and
// floors/explicit_check.cpp): Odeint's controlled runge_kutta_fehlberg78 driven by try_step,
// each step cut to land on the next output time, the controller's proposal kept across an output
// as integrate_times keeps it. The right-hand side is the caller's, so that it is inlined into
// the stepper's stage sums as the caller compiles it. Include <boost/numeric/odeint.hpp> first
// (floors/odeint.cpp says why with a pragma).

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <vector>

namespace tumble::bench {

/// Odeint stops after this many steps between two output times (its default, 500, is too few
/// for the fast spinner at tight tolerances).
inline constexpr long kFloorMaxSteps = 100'000'000;
/// The loop stops after this many rejected attempts in a row (Odeint's failed_step_checker in
/// integrate_times: 500).
inline constexpr long kFloorMaxFailedSteps = 500;

/// Steps x from t = 0, with dxdt = f(x) given, to each of `times` in turn (increasing, > 0),
/// starting with the step dt0, at rtol = atol = tol; observe(x, t) at each output time; f(x, xd,
/// t) also refreshes dxdt after every accepted step. Returns the accepted steps; throws
/// std::runtime_error past kFloorMaxSteps steps to one output or kFloorMaxFailedSteps
/// rejections in a row.
template <class State, class Rhs, class Observe>
std::size_t fehlberg78_loop(double tol, const Rhs& f, State& x, State& dxdt, double dt0,
                            const std::vector<double>& times, Observe&& observe) {
  namespace odeint = boost::numeric::odeint;
  auto stepper = odeint::make_controlled(tol, tol, odeint::runge_kutta_fehlberg78<State>());
  State trial{};
  double t = 0, dt = dt0;
  long failed = 0;
  std::size_t steps = 0;
  for (const double t_out : times) {
    for (long n = 0; t < t_out; ++n) {
      if (n == kFloorMaxSteps) {  // as Odeint's max_step_checker in integrate_times
        throw std::runtime_error("the Fehlberg 7(8) floor: too many steps to an output");
      }
      const bool last = dt >= t_out - t;  // the step ends on the output time
      double t_try = t, h = last ? t_out - t : dt;
      if (stepper.try_step(f, x, dxdt, t_try, trial, h) == odeint::success) {
        ++steps;
        failed = 0;
        x = trial;
        t = last ? t_out : t_try;
        f(x, dxdt, t);
        dt = std::max(dt, h);  // h: the controller's next step (integrate_times' rule)
      } else {
        if (++failed > kFloorMaxFailedSteps) {
          throw std::runtime_error("the Fehlberg 7(8) floor: too many failed steps in a row");
        }
        dt = h;
      }
    }
    observe(x, t);
  }
  return steps;
}

}  // namespace tumble::bench
