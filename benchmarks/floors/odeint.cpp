// tumble_bench: integrator floors with Boost.Odeint on the hand-written first-order right-hand
// side (floors/rhs.hpp), the state a fixed-size std::array<double, N> (no heap):
//  - runge_kutta_fehlberg78 under Odeint's controller (make_controlled(atol, rtol)), written two
//    ways, both in the main job, the faster of the two being the floor:
//    - in Odeint's integrate_times: the steps end on the output times;
//    - as a plain loop over the controller's try_step, keeping x' across a rejected attempt (as
//      tumble's integrator does; integrate_times evaluates it again), each output time reached
//      by shortening the step to it and the step size restored after (as integrate_times does).
//  - runge_kutta_dopri5 with dense output (make_dense_output(atol, rtol)): free steps, the output
//    times interpolated.
// rtol = atol = tol, as for the CVODE methods. The first step is estimated (Hairer, Norsett and
// Wanner, Solving ODEs I, Sec. II.4, as tumble's OdeintIntegrator does), not a fixed fraction of
// the first output interval. |p| is normalized at output only. The right-hand side is inlined
// into Odeint's stepper, as tumble's is into its own.
//
// One kind per translation unit (TUMBLE_BENCH_ODEINT_FLOOR, set by main/tumble_bench.cmake in the
// units it generates from this file): with all in one unit, GCC 12 -O3 reached its whole-unit
// limit on inlining and left the 13-state floor's right-hand side out of its stepper. tumble's
// headline configuration, which these floors are compared with, has a unit of its own too
// (work_precision/tumble_d.cpp).

#ifndef TUMBLE_BENCH_ODEINT_FLOOR
#error "compiled through the units main/tumble_bench.cmake generates (TUMBLE_BENCH_ODEINT_FLOOR)"
#endif

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <vector>

// GCC 12 -O3 reports Odeint's copy of a freshly built stepper (std::array members, filled before
// use) as -Wmaybe-uninitialized inside the Boost headers, or as -Wuninitialized where the copy is
// inlined into floors/fehlberg_loop.hpp: a false positive, silenced for this file only (the
// location it reports is in the header, so the pragma precedes the include).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"
#endif
#include <boost/numeric/odeint.hpp>

#include "floors/fehlberg_loop.hpp"
#include "floors/rhs.hpp"

namespace tumble::bench {
namespace {

namespace odeint = boost::numeric::odeint;

enum class OdeintKind { rkf78, rkf78_loop, dopri5 };

/// The first step for a method of order `order` at x with x' = f0 (Hairer, Norsett and Wanner,
/// Sec. II.4: an Euler step of size h0, then the second derivative from it), with one more
/// evaluation of f, written out as tumble's detail::initial_step is.
template <int N, class F>
double initial_step(const F& f, const std::array<double, N>& x, const std::array<double, N>& f0,
                    double tol, double order) {
  std::array<double, N> sc{}, x1{}, f1{};
  double d0 = 0, d1 = 0;
  for (int i = 0; i < N; ++i) {
    sc[i] = tol + tol * std::abs(x[i]);
    d0 += (x[i] / sc[i]) * (x[i] / sc[i]);
    d1 += (f0[i] / sc[i]) * (f0[i] / sc[i]);
  }
  d0 = std::sqrt(d0 / N);
  d1 = std::sqrt(d1 / N);
  const double h0 = (d0 < 1e-5 || d1 < 1e-5) ? 1e-6 : 0.01 * d0 / d1;
  for (int i = 0; i < N; ++i) {
    x1[i] = x[i] + h0 * f0[i];
  }
  f(x1, f1);
  double d2 = 0;
  for (int i = 0; i < N; ++i) {
    d2 += ((f1[i] - f0[i]) / sc[i]) * ((f1[i] - f0[i]) / sc[i]);
  }
  d2 = std::sqrt(d2 / N) / h0;
  const double dm = std::max(d1, d2);
  const double h1 = dm <= 1e-15 ? std::max(1e-6, 1e-3 * h0) : std::pow(0.01 / dm, 1 / (order + 1));
  return std::min(100 * h0, h1);
}

template <int N, OdeintKind Kind>
Run odeint_floor(const Problem& p, const MethodSetting& c, const Timing& timing) {
  using State = std::array<double, N>;
  Run run;
  run.samples.resize(p.times.size());
  const FloorRhs<N> f(p);
  const State x0 = f.initial(p);
  std::vector<double> grid(p.times.size() + 1, 0.0);  // t = 0, then the output times
  std::copy(p.times.begin(), p.times.end(), grid.begin() + 1);
  // Every evaluation is counted, as tumble's integrator counts its own (Odeint reports only the
  // accepted steps).
  const auto counted = [&f](const State& x, State& xd, double /*t*/) { f(x.data(), xd.data()); };
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
      State dxdt{};
      counted(x, dxdt, 0.0);
      const double order = Kind == OdeintKind::dopri5 ? 5 : 7;
      const auto counted_eval = [&f](const State& y, State& yd) { f(y.data(), yd.data()); };
      const double dt0 =
          std::min(initial_step<N>(counted_eval, x, dxdt, c.tol, order), p.times.front());
      std::size_t steps = 0;
      if constexpr (Kind == OdeintKind::rkf78) {
        auto stepper =
            odeint::make_controlled(c.tol, c.tol, odeint::runge_kutta_fehlberg78<State>());
        steps = odeint::integrate_times(stepper, counted, x, grid.begin(), grid.end(), dt0, observe,
                                        odeint::max_step_checker(kFloorMaxSteps));
      } else if constexpr (Kind == OdeintKind::rkf78_loop) {
        observe(x, 0.0);
        steps = fehlberg78_loop(c.tol, counted, x, dxdt, dt0, p.times, observe);
      } else {
        auto stepper = odeint::make_dense_output(c.tol, c.tol, odeint::runge_kutta_dopri5<State>());
        steps = odeint::integrate_times(stepper, counted, x, grid.begin(), grid.end(), dt0, observe,
                                        odeint::max_step_checker(kFloorMaxSteps));
      }
      run.steps = static_cast<long>(steps);
      run.rhs_evals = f.evals;
      record_time(run, times, watch, timing);
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

#if TUMBLE_BENCH_ODEINT_FLOOR == 0
Run run_floor_odeint_rkf78(const Problem& p, const MethodSetting& c, const Timing& timing) {
  return dispatch<OdeintKind::rkf78>(p, c, timing);
}
#elif TUMBLE_BENCH_ODEINT_FLOOR == 1
Run run_floor_odeint_rkf78_loop(const Problem& p, const MethodSetting& c, const Timing& timing) {
  return dispatch<OdeintKind::rkf78_loop>(p, c, timing);
}
#elif TUMBLE_BENCH_ODEINT_FLOOR == 2
Run run_floor_odeint_dopri5(const Problem& p, const MethodSetting& c, const Timing& timing) {
  return dispatch<OdeintKind::dopri5>(p, c, timing);
}
#else
#error "TUMBLE_BENCH_ODEINT_FLOOR: 0 (Fehlberg 7(8)), 1 (the same as a loop) or 2 (Dormand-Prince)"
#endif

}  // namespace tumble::bench
