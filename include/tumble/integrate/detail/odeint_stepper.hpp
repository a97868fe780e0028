#pragma once
// Boost.Odeint behind one interface for OdeintIntegrator (explicit_integrator.hpp): the state
// type, and one controlled stepper per OdeintMethod with
//   try_step(sys, x, dxdt, t, x_new, dxdt_new, h)  one trial step from (t, x) with x' = dxdt;
//       true when accepted (t advanced, h the next suggestion), false when rejected (h reduced).
//       For a first-same-as-last pair (dopri5) dxdt_new is x' at x_new; otherwise untouched.
//   state_at(sys, t, out, <the last accepted step>)  the state at t inside that step: Odeint's
//       dense output (dopri5's calc_state, exact to the method's interpolation order) or, for the
//       pairs without one, a step of the same method from the step's start to t (as accurate as
//       the step itself, at one step's cost).
// Only Odeint's steppers and its step-size controller are used; the loop around them (output
// times, charts, projection, events, budgets) is the integrator's.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include <Eigen/Core>
// Odeint's steppers hold their stage buffers (std::array for a fixed size) uninitialized until
// the first step writes them, and copy them when constructed: GCC's -W(maybe-)uninitialized
// reports those copies at the point of inlining, past the system-header exemption.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"
#endif
#include <boost/numeric/odeint/stepper/controlled_runge_kutta.hpp>
#include <boost/numeric/odeint/stepper/runge_kutta_cash_karp54.hpp>
#include <boost/numeric/odeint/stepper/runge_kutta_dopri5.hpp>
#include <boost/numeric/odeint/stepper/runge_kutta_fehlberg78.hpp>
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

#include "tumble/core/cache_line.hpp"
#include "tumble/integrate/explicit_options.hpp"

namespace tumble::detail {

namespace odeint = boost::numeric::odeint;

/// Odeint's state: a std::array when the size is known at compile time (no heap at all), a
/// std::vector otherwise (sized once; Odeint's buffers are resized only when the size changes),
/// on whole cache lines of its own (core/cache_line.hpp): the state, the stage buffers Odeint
/// makes of the same type, written at every step, share no line with another thread's data.
template <int N>
using OdeintState = std::conditional_t<N == Eigen::Dynamic, CacheLineVector<double>,
                                       std::array<double, static_cast<std::size_t>(N < 0 ? 1 : N)>>;

/// Odeint's error test with an absolute tolerance per entry (or one for all): the largest of
/// |err_i| / (atol_i + rtol (|x_i| + |h| |x'_i|)) over i, Odeint's default_error_checker with
/// a_x = a_dxdt = 1 but for atol_i; in one pass, with a NaN error counted as infinite (a
/// rejected step), where the default's maximum would pass it over. A floor > 0 raises rtol and
/// every atol_i to at least the floor (OdeintControlled::raise_tolerances_to).
template <class Value, class Algebra, class Operations> class ToleranceChecker {
 public:
  using value_type = Value;
  using algebra_type = Algebra;
  using operations_type = Operations;

  /// atol_entries: nullptr for the one value atol, else atol_i for each entry (not owned).
  explicit ToleranceChecker(Value atol = 1e-8, Value rtol = 1e-8,
                            const Value* atol_entries = nullptr, Value floor = 0)
      : atol_(atol), rtol_(rtol), entries_(atol_entries), floor_(floor) {}

  template <class State, class Deriv, class Err, class Time>
  Value error(Algebra& /*algebra*/, const State& x_old, const Deriv& dxdt_old, Err& x_err,
              Time dt) const {
    using std::abs;
    const Value adt = abs(static_cast<Value>(dt));
    const std::size_t n = x_err.size();
    Value worst = 0;
    if (floor_ > 0) [[unlikely]] {
      const Value rtol = std::max(rtol_, floor_);
      for (std::size_t i = 0; i < n; ++i) {
        const Value atol = std::max(entries_ == nullptr ? atol_ : entries_[i], floor_);
        const Value e = abs(x_err[i]) / (atol + rtol * (abs(x_old[i]) + adt * abs(dxdt_old[i])));
        worst = e > worst ? e : worst;
        if (e != e) {
          return std::numeric_limits<Value>::infinity();
        }
      }
    } else if (entries_ == nullptr) {
      for (std::size_t i = 0; i < n; ++i) {
        const Value e = abs(x_err[i]) / (atol_ + rtol_ * (abs(x_old[i]) + adt * abs(dxdt_old[i])));
        worst = e > worst ? e : worst;
        if (e != e) {
          return std::numeric_limits<Value>::infinity();
        }
      }
    } else {
      for (std::size_t i = 0; i < n; ++i) {
        const Value e =
            abs(x_err[i]) / (entries_[i] + rtol_ * (abs(x_old[i]) + adt * abs(dxdt_old[i])));
        worst = e > worst ? e : worst;
        if (e != e) {
          return std::numeric_limits<Value>::infinity();
        }
      }
    }
    return worst;
  }

 private:
  Value atol_, rtol_;
  const Value* entries_;
  Value floor_;
};

/// One embedded pair under Odeint's controller (controlled_runge_kutta) with the per-entry
/// error test above.
template <class ErrorStepper> class OdeintControlled {
  using Checker =
      ToleranceChecker<typename ErrorStepper::value_type, typename ErrorStepper::algebra_type,
                       typename ErrorStepper::operations_type>;
  using Controlled = odeint::controlled_runge_kutta<ErrorStepper, Checker>;

 public:
  /// dopri5: first same as last, and Odeint's dense output.
  static constexpr bool fsal = std::is_same_v<typename ErrorStepper::stepper_category,
                                              odeint::explicit_error_stepper_fsal_tag>;
  static constexpr bool dense = fsal;

  /// atol_entries: nullptr for the one value atol, else atol_i per entry (must outlive this).
  OdeintControlled(double atol, double rtol, const double* atol_entries = nullptr)
      : atol_(atol),
        rtol_(rtol),
        entries_(atol_entries),
        controlled_(Checker(atol, rtol, atol_entries)) {}

  /// From the next try_step on, the error test asks for no less than `floor` (rtol and every
  /// atol_i raised to it; 0: the tolerances as given). A new floor rebuilds the controlled
  /// stepper (Odeint's keeps its error checker by value): call it only between a step's dense
  /// outputs and the next try_step, which the stepper's stage buffers (recreated here) serve.
  void raise_tolerances_to(double floor) {
    if (floor != floor_) {
      floor_ = floor;
      controlled_ = Controlled(Checker(atol_, rtol_, entries_, floor));
    }
  }

  /// Sys::inline_stages: the system inlined into every stage of the step (try_step_inlined).
  template <class Sys, class State>
  bool try_step(Sys sys, const State& x, const State& dxdt, double& t, State& x_new,
                State& dxdt_new, double& h) {
    if constexpr (requires { requires Sys::inline_stages; }) {
      return try_step_inlined(sys, x, dxdt, t, x_new, dxdt_new, h);
    } else {
      return try_step_called(sys, x, dxdt, t, x_new, dxdt_new, h);
    }
  }

  /// The state at t in [t_old, t_new], the last accepted step (from x_old with x' = dxdt_old to
  /// x_new with x' = dxdt_new). Dense output is valid only until the next try_step.
  template <class Sys, class State>
  void state_at(Sys sys, double t, State& out, const State& x_old, const State& dxdt_old,
                double t_old, const State& x_new, const State& dxdt_new, double t_new) {
    if constexpr (dense) {
      controlled_.stepper().calc_state(t, out, x_old, dxdt_old, t_old, x_new, dxdt_new, t_new);
    } else {
      (void)x_new, (void)dxdt_new, (void)t_new;
      controlled_.stepper().do_step(sys, x_old, dxdt_old, t_old, out, t - t_old);
    }
  }

  /// Order of the solution that is propagated (for the initial step estimate).
  static constexpr int order = ErrorStepper::order_value;

  /// Right-hand sides that one try_step evaluates, every one of them whether the step is
  /// accepted or not (x' at the step's start is given; Dormand-Prince's x' at its end is its
  /// last stage), and one state_at (the dense output evaluates none; a generic pair steps again
  /// from the start). What the integrator counts when its stages do not count themselves.
  static constexpr long evaluations_per_try = [] {
    if constexpr (fsal) {
      return 6L;  // Dormand-Prince 5(4): stages 2 to 7, the 7th at the step's end
    } else {
      return static_cast<long>(ErrorStepper::stage_count) - 1;  // 12 (Fehlberg), 5 (Cash-Karp)
    }
  }();
  static constexpr long evaluations_per_state_at = dense ? 0 : evaluations_per_try;

 private:
  /// The step with every call in it inlined (flatten), the system's too, into each of the
  /// stepper's stage sums (13 for Fehlberg 7(8)), whatever the translation unit's inlining budget.
  /// For a right-hand side of about a hundred instructions (a scene without loads or joints) the
  /// call, its register saves and the loads it repeats were a tenth of a torque-free body's run:
  /// 438k instructions against 398k for the tumbling body to 1e-6 in a standalone program, the
  /// same results to the bit (docs/benchmarks/floors.md, 2026-12-05). A larger right-hand side
  /// stays one function, called: inlined 13 times it would cost code and compile time for a
  /// smaller share.
  template <class Sys, class State>
  [[gnu::flatten]] bool try_step_inlined(Sys sys, const State& x, const State& dxdt, double& t,
                                         State& x_new, State& dxdt_new, double& h) {
    return try_step_called(sys, x, dxdt, t, x_new, dxdt_new, h);
  }

  template <class Sys, class State>
  bool try_step_called(Sys sys, const State& x, const State& dxdt, double& t, State& x_new,
                       State& dxdt_new, double& h) {
    odeint::controlled_step_result r;
    if constexpr (fsal) {
      r = controlled_.try_step(sys, x, dxdt, t, x_new, dxdt_new, h);
    } else {
      (void)dxdt_new;
      r = controlled_.try_step(sys, x, dxdt, t, x_new, h);
    }
    return r == odeint::success;
  }

  double atol_, rtol_;
  const double* entries_;
  double floor_ = 0.0;
  Controlled controlled_;
};

template <class State> using Fehlberg78 = OdeintControlled<odeint::runge_kutta_fehlberg78<State>>;
template <class State> using Dopri5 = OdeintControlled<odeint::runge_kutta_dopri5<State>>;
template <class State> using CashKarp54 = OdeintControlled<odeint::runge_kutta_cash_karp54<State>>;

/// The options, validated for a scene of size n (explicit_options.hpp), and N, the integrator's
/// fixed size (Eigen::Dynamic: any), checked against it.
template <int N> OdeintOptions checked_odeint_options(const OdeintOptions& o, long n) {
  validate(o, n);
  if constexpr (N != Eigen::Dynamic) {
    if (n != N) {
      throw std::invalid_argument(
          "tumble::OdeintIntegrator<SceneT, N>: N = " + std::to_string(N) +
          ", but the scene has size " + std::to_string(n) +
          " (Scene::size()): give N as tumble::state_size<SceneT, Body...> with one Body for "
          "each body of the scene, or Eigen::Dynamic");
    }
  }
  return o;
}

/// The pair OdeintOptions::method names, with the error test of the options' tolerances (a
/// per-entry atol is read from `options`, which must outlive the stepper).
template <class State>
using OdeintStepper = std::variant<Fehlberg78<State>, Dopri5<State>, CashKarp54<State>>;
template <class State> OdeintStepper<State> make_odeint_stepper(const OdeintOptions& options) {
  const auto* v = std::get_if<Eigen::VectorXd>(&options.atol);
  const double atol = v ? 0.0 : std::get<double>(options.atol);
  const double* entries = v ? v->data() : nullptr;
  switch (options.method) {
    case OdeintMethod::dopri5:
      return Dopri5<State>(atol, options.rtol, entries);
    case OdeintMethod::cash_karp54:
      return CashKarp54<State>(atol, options.rtol, entries);
    case OdeintMethod::fehlberg78:
      break;
  }
  return Fehlberg78<State>(atol, options.rtol, entries);
}

}  // namespace tumble::detail
