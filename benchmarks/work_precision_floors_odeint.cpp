// tumble_bench: integrator floors with Boost.Odeint on the hand-written first-order right-hand
// side (work_precision_floor_rhs.hpp), the state a fixed-size std::array<double, N> (no heap):
//  - runge_kutta_fehlberg78 in a controlled stepper (make_controlled(atol, rtol)): steps end on
//    the output times (integrate_times);
//  - runge_kutta_dopri5 with dense output (make_dense_output(atol, rtol)): free steps, the output
//    times interpolated.
// rtol = atol = tol, as for the CVODE methods. |p| is normalized at output only.

#include <array>
#include <exception>
#include <vector>

// GCC 12 -O3 reports Odeint's copy of a freshly built stepper (std::array members, filled before
// use) as -Wmaybe-uninitialized inside the Boost headers: a false positive, silenced for this
// file only (the location it reports is in the header, so the pragma precedes the include).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <boost/numeric/odeint.hpp>

#include "work_precision_floor_rhs.hpp"

namespace tumble::bench {
namespace {

namespace odeint = boost::numeric::odeint;

enum class OdeintKind { rkf78, dopri5 };

template <int N, OdeintKind Kind>
Run odeint_floor(const Problem& p, const MethodSetting& c, const Timing& timing) {
  using State = std::array<double, N>;
  Run run;
  run.samples.resize(p.times.size());
  const FloorRhs<N> f(p);
  const State x0 = f.initial(p);
  std::vector<double> grid(p.times.size() + 1, 0.0);  // t = 0, then the output times
  std::copy(p.times.begin(), p.times.end(), grid.begin() + 1);
  const auto system = [&f](const State& x, State& xd, double /*t*/) { f(x.data(), xd.data()); };
  std::vector<double> times;
  try {
    do {
      f.evals = 0;
      const Stopwatch watch;
      State x = x0;
      std::size_t k = 0;
      const auto observe = [&](const State& y, double /*t*/) {
        if (k > 0) {  // integrate_times observes the initial state too
          run.samples[k - 1] = f.sample(p, y.data());
        }
        ++k;
      };
      const double dt0 = 1e-3 * p.times.front();
      // Odeint stops after 500 steps between two output times by default; the fast spinner at
      // tight tolerances takes more.
      const odeint::max_step_checker checker(100'000'000);
      std::size_t steps = 0;
      if constexpr (Kind == OdeintKind::rkf78) {
        auto stepper =
            odeint::make_controlled(c.tol, c.tol, odeint::runge_kutta_fehlberg78<State>());
        steps = odeint::integrate_times(stepper, system, x, grid.begin(), grid.end(), dt0, observe,
                                        checker);
      } else {
        auto stepper = odeint::make_dense_output(c.tol, c.tol, odeint::runge_kutta_dopri5<State>());
        steps = odeint::integrate_times(stepper, system, x, grid.begin(), grid.end(), dt0, observe,
                                        checker);
      }
      record_time(run, times, watch, timing);
      run.steps = static_cast<long>(steps);
      run.rhs_evals = f.evals;
      run.constraint_drift = FloorRhs<N>::drift(x.data());
    } while (another_rep(timing, times));
  } catch (const std::exception& e) {
    run.ok = false;
    run.error = e.what();
  }
  finish_timing(run, times);
  return run;
}

template <OdeintKind Kind>
Run dispatch(const Problem& p, const MethodSetting& c, const Timing& timing) {
  return FloorRhs<7>::fits(p) ? odeint_floor<7, Kind>(p, c, timing)
                              : odeint_floor<13, Kind>(p, c, timing);
}

}  // namespace

Run run_floor_odeint_rkf78(const Problem& p, const MethodSetting& c, const Timing& timing) {
  return dispatch<OdeintKind::rkf78>(p, c, timing);
}

Run run_floor_odeint_dopri5(const Problem& p, const MethodSetting& c, const Timing& timing) {
  return dispatch<OdeintKind::dopri5>(p, c, timing);
}

}  // namespace tumble::bench
