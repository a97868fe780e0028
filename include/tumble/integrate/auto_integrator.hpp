#pragma once
// The front door: a scene integrated to given times at a given accuracy, the method chosen by the
// library (in the spirit of DifferentialEquations.jl's default algorithm), and a report of what
// ran and why. One call,
//
//   tumble::AutoStatistics st = tumble::integrate(scene, t0, times, observer, {.rtol = 1e-9});
//
// or, to step and restart it, the class AutoIntegrator, which has the interface of the two
// integrators it drives (advance, integrate, reset, state, save, statistics; the options,
// statistics and errors of integrate/common.hpp and integrate/errors.hpp).
//
// The choice (docs/choosing.md gives the measurements behind it):
// 1. Stiff from the start: at the initial state the front door estimates the largest eigenvalue
//    modulus rho of the Jacobian (power iteration, about 30 right-hand sides) and the step h an
//    explicit method of order 8 would take for the accuracy asked for (Hairer, Norsett and
//    Wanner's starting-step estimate, Sec. II.4, which errs short). With h rho above
//    kStiffAtStart the explicit steps would be held at their stability bound: CVODE BDF with
//    the exact Jacobian (SceneIntegrator, dense LU up to kDenseLimit states, band LU beyond).
// 2. Otherwise the explicit path: OdeintIntegrator with Fehlberg 7(8), the most accurate per
//    right-hand side on the torque-free problems down to 1e-12. In integrate() on a scene
//    without events, after the outputs of its first kDenseDecisionSteps steps, when the
//    controller asks for steps more than kDenseOutputs times longer than the spacing of the
//    outputs (the outputs, not the accuracy, cut the steps), it hands over to Dormand-Prince
//    5(4), which reads the outputs off its dense output. Dormand-Prince then runs the outputs
//    in chunks (kDenseCheckOutputs, then twice as many each time), and hands the rest back to
//    Fehlberg 7(8) when, after a chunk, it has cost more right-hand sides per unit time since
//    it took over than Fehlberg's cheapest: one step (kFehlbergStages) per output. The first steps
//    say little of a motion that speeds up: Bricard's mechanism (A04), released at rest, lets
//    Fehlberg take 0.2 s steps at first (4 outputs), but its steps over the 10 s average 0.038 s
//    at 1e-8, where Dormand-Prince needs 2.6 times its steps.
// 3. Stiffness met on the way: the explicit integrator tests every `stiffness_window` attempts
//    whether its steps are held at the stability bound (OdeintOptions::stiffness_window); when
//    they are, the front door restarts from the last accepted step with BDF and goes on.
// Every decision is recorded with the time it took effect and the reason in words
// (AutoStatistics::choices). The hand-overs are one way: a scene that was stiff stays with BDF,
// and Fehlberg 7(8) back from Dormand-Prince keeps the outputs.

#include <cmath>
#include <cstddef>
#include <cstdio>
#include <initializer_list>
#include <iterator>
#include <limits>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "tumble/core/errors.hpp"
#include "tumble/core/format.hpp"
#include "tumble/integrate/common.hpp"
#include "tumble/integrate/detail/explicit_numerics.hpp"
#include "tumble/integrate/errors.hpp"
#include "tumble/integrate/explicit_integrator.hpp"
#include "tumble/integrate/scene_integrator.hpp"
#include "tumble/scene/rhs.hpp"
#include "tumble/scene/scene.hpp"
#include "tumble/scene/state.hpp"
#include "tumble/scene/workspace.hpp"

namespace tumble {

/// The methods the front door chooses from.
enum class AutoMethod {
  fehlberg78,  ///< OdeintIntegrator, OdeintMethod::fehlberg78
  dopri5,      ///< OdeintIntegrator, OdeintMethod::dopri5 with interpolated outputs
  bdf,         ///< SceneIntegrator, CvodeMethod::bdf, exact Jacobian where the loads allow
};

[[nodiscard]] inline const char* name(AutoMethod m) noexcept {
  switch (m) {
    case AutoMethod::fehlberg78:
      return "Fehlberg 7(8) (OdeintIntegrator)";
    case AutoMethod::dopri5:
      return "Dormand-Prince 5(4) (OdeintIntegrator)";
    case AutoMethod::bdf:
      return "BDF (SceneIntegrator, CVODE)";
  }
  return "?";
}

/// One decision of the front door: the method, from when, and why.
struct MethodChoice {
  AutoMethod method;
  double from;      ///< the time it took over
  std::string why;  ///< the measurement it rests on, in words
};

/// Options of the front door: the shared vocabulary (integrate/common.hpp), then its own.
struct AutoOptions {
  // --- shared with OdeintOptions and SceneIntegratorOptions ---
  double rtol = SharedDefaults::rtol;             ///< > 0
  AbsoluteTolerance atol = SharedDefaults::atol;  ///< > 0: one value, or one per entry of y
  long max_steps = SharedDefaults::max_steps;     ///< per advance(), 0: no limit
  double initial_step = 0.0;                      ///< 0: estimated
  double max_step = std::numeric_limits<double>::infinity();
  // --- the front door's own ---
  /// On the explicit path: test for stiffness every this many step attempts (see
  /// OdeintOptions::stiffness_window) and hand over to BDF when the test says so. 0: never test
  /// and never hand over (a stiff scene then runs at the explicit method's stability bound).
  long stiffness_window = 500;
  /// Hand the outputs of integrate() to Dormand-Prince's dense output when they cut the steps of
  /// Fehlberg 7(8) (point 2 above).
  bool dense_outputs = true;
};

/// The shared counters (integrate/common.hpp), summed over every method that ran, and the
/// decisions: choices.front() is the first, each further one a hand-over.
struct AutoStatistics {
  long steps = 0;
  long rejected_steps = 0;
  long rhs_evals = 0;  ///< including those of the front door's own tests
  long chart_switches = 0;
  long projections = 0;
  long events = 0;
  /// The explicit path's steps of a mechanism tested at a tolerance looser than asked, near a
  /// singular position, and the loosest (OdeintStatistics).
  long relaxed_steps = 0;
  double loosest_tolerance = 0.0;
  std::vector<MethodChoice> choices;

  /// The method running now.
  [[nodiscard]] AutoMethod method() const { return choices.back().method; }
};
static_assert(IntegratorStatisticsLike<AutoStatistics>);
static_assert(IntegratorOptionsLike<AutoOptions>);

/// A scene integrated by the method the library chooses (see the top of this header). N: the
/// scene's size for the explicit path's fixed-size state (OdeintIntegrator), or Eigen::Dynamic.
template <class SceneT, int N = Eigen::Dynamic> class AutoIntegrator {
 public:
  using Options = AutoOptions;
  using Statistics = AutoStatistics;

  /// h rho at the initial state above which the scene counts as stiff from the start. The
  /// explicit pairs are stable up to h rho of about 3 to 5 on the negative real axis; the
  /// starting-step estimate errs short, so only a scene far past that bound is sent to BDF
  /// here, and the explicit path's own test catches the rest.
  static constexpr double kStiffAtStart = 10.0;
  /// Fehlberg 7(8) hands over to Dormand-Prince when its controller asks for steps this many
  /// times longer than the spacing of the outputs.
  static constexpr double kDenseOutputs = 2.0;
  /// The steps Fehlberg 7(8) takes before the outputs are judged (its controller grows a step at
  /// most fivefold, so its first steps say little of the steps the accuracy allows).
  static constexpr long kDenseDecisionSteps = 3;
  /// Dormand-Prince's first chunk of outputs, judged before it goes on (point 2).
  static constexpr std::size_t kDenseCheckOutputs = 8;
  /// Right-hand sides per step of Fehlberg 7(8): its stages, 13 (Odeint's runge_kutta_fehlberg78,
  /// not first same as last).
  static constexpr double kFehlbergStages = static_cast<double>(
      detail::odeint::runge_kutta_fehlberg78<detail::OdeintState<N>>::stage_count);
  /// Tolerances below this keep Fehlberg 7(8) whatever the outputs: Dormand-Prince's order 5
  /// then needs several times its steps.
  static constexpr double kDenseOutputsTightest = 1e-9;
  /// BDF's Newton iteration solves with dense LU up to this many states, band LU beyond.
  static constexpr int kDenseLimit = 100;

  /// Integrate `scene` from t0 at its initial state. The scene must outlive the integrator.
  AutoIntegrator(const SceneT& scene, double t0, AutoOptions options = {})
      : AutoIntegrator(scene, t0, scene.initial_state(), std::move(options)) {}

  /// Integrate `scene` from (t0, s0), a state of this scene.
  AutoIntegrator(const SceneT& scene, double t0, const SceneState& s0, AutoOptions options = {})
      : scene_(&scene), options_(std::move(options)) {
    detail::validate_shared("tumble::AutoOptions", options_.rtol, options_.atol, options_.max_steps,
                            options_.initial_step, options_.max_step, scene.size(),
                            /*atol_may_be_zero=*/false);
    if (options_.stiffness_window < 0) {
      throw std::invalid_argument(
          "tumble::AutoOptions: 'stiffness_window' must be >= 0, 0 for no stiffness test (got " +
          std::to_string(options_.stiffness_window) + ")");
    }
    start(t0, s0);
  }

  AutoIntegrator(SceneT&&, double, AutoOptions = {}) = delete;
  AutoIntegrator(SceneT&&, double, const SceneState&, AutoOptions = {}) = delete;

  /// Integrates to t_out (>= time()). The state there is state(); save() keeps a copy.
  void advance(double t_out) {
    if (explicit_) {
      try {
        explicit_->advance(t_out);
        return;
      } catch (const StiffSceneError& e) {
        to_bdf(e);
      }
    }
    implicit_->advance(t_out);
  }

  /// observer(t, state) at each output time (non-decreasing, not before time(), validated before
  /// integrating).
  template <class Times, class Observer> void integrate(const Times& times, Observer&& observer) {
    detail::check_output_times("tumble::AutoIntegrator::integrate", time(), times);
    std::vector<double> ts;  // the times; the tail is what is left after a hand-over
    for (const auto& value : times) {
      ts.push_back(static_cast<double>(value));
    }
    std::size_t done = 0;  // outputs handed to the observer
    const auto observe = [&](double t, const SceneState& s) {
      ++done;
      observer(t, s);
    };
    const auto rest = [&] { return std::span<const double>(ts).subspan(done); };
    if (explicit_) {
      try {
        if (method_ == AutoMethod::fehlberg78 && options_.dense_outputs && ts.size() > 2 &&
            options_.rtol >= kDenseOutputsTightest && scene_->events().empty()) {
          // The outputs one at a time on Fehlberg 7(8) until its controller has taken
          // kDenseDecisionSteps steps past the start; then the outputs decide (point 2).
          const double t0 = time();
          const long steps0 = explicit_->statistics().steps;
          while (done < ts.size() &&
                 (ts[done] <= t0 || explicit_->statistics().steps - steps0 < kDenseDecisionSteps)) {
            explicit_->integrate(rest().first(1), observe);
          }
          const double spacing = (ts.back() - ts.front()) / static_cast<double>(ts.size() - 1);
          if (done < ts.size() && spacing > 0.0 &&
              explicit_->step_size() > kDenseOutputs * spacing) {
            to_dopri5(spacing);
            dense_chunks(ts, done, spacing, observe);
          }
        }
        explicit_->integrate(rest(), observe);
        return;
      } catch (const StiffSceneError& e) {
        to_bdf(e);
      }
    }
    // CVODE asks for increasing times: repeated ones get the state again.
    std::vector<double> increasing;
    for (const double t : rest()) {
      if (increasing.empty() || t > increasing.back()) {
        increasing.push_back(t);
      }
    }
    std::size_t k = done;
    implicit_->integrate(increasing, [&](double t, const SceneState& s) {
      while (k < ts.size() && ts[k] == t) {
        observer(t, s);
        ++k;
      }
    });
  }
  template <class Observer>
  void integrate(std::initializer_list<double> times, Observer&& observer) {
    integrate(std::span<const double>(times.begin(), times.size()),
              std::forward<Observer>(observer));
  }

  /// Restarts from the state s at time t, choosing the method anew (as a new integrator would:
  /// a run after reset() is the same to the bit as one of a new integrator). The integrators of
  /// the chosen method are reused when it is the one running, so a reset costs no construction.
  void reset(double t, const SceneState& s) { start(t, s); }

  /// The current state: a view that every call that integrates changes. To keep it, save() it.
  [[nodiscard]] const SceneState& state() const {
    return explicit_ ? explicit_->state() : implicit_->state();
  }
  [[nodiscard]] SceneState save() const {
    return explicit_ ? explicit_->save() : implicit_->save();
  }
  void save(SceneState& into) const {
    if (explicit_) {
      explicit_->save(into);
    } else {
      implicit_->save(into);
    }
  }
  [[nodiscard]] double time() const { return explicit_ ? explicit_->time() : implicit_->time(); }
  /// The method running now.
  [[nodiscard]] AutoMethod method() const { return method_; }

  /// The shared counters of every method that ran since the last (re)start, and the decisions.
  [[nodiscard]] AutoStatistics statistics() const {
    AutoStatistics s = finished_;
    if (explicit_) {
      add(s, explicit_->statistics(), explicit_base_);
    } else {
      add(s, implicit_->statistics(), implicit_base_);
    }
    s.choices = choices_;
    return s;
  }

  [[nodiscard]] const SceneT& scene() const { return *scene_; }
  [[nodiscard]] const AutoOptions& options() const { return options_; }

 private:
  using Explicit = OdeintIntegrator<SceneT, N>;
  using Implicit = SceneIntegrator<SceneT>;

  template <class From> static void add(AutoStatistics& to, const From& s, const From& base) {
    to.steps += s.steps - base.steps;
    to.rejected_steps += s.rejected_steps - base.rejected_steps;
    to.rhs_evals += s.rhs_evals - base.rhs_evals;
    to.chart_switches += s.chart_switches - base.chart_switches;
    to.projections += s.projections - base.projections;
    to.events += s.events - base.events;
    if constexpr (requires { s.relaxed_steps; }) {
      to.relaxed_steps += s.relaxed_steps - base.relaxed_steps;
      to.loosest_tolerance = std::max(to.loosest_tolerance, s.loosest_tolerance);
    }
  }

  /// The integrator's options with the shared ones (integrate/common.hpp) of options_.
  template <class O> [[nodiscard]] O shared_options() const {
    O o;
    o.rtol = options_.rtol;
    o.atol = options_.atol;
    o.max_steps = options_.max_steps;
    o.initial_step = options_.initial_step;
    o.max_step = options_.max_step;
    return o;
  }

  [[nodiscard]] OdeintOptions odeint_options(AutoMethod m) const {
    auto o = shared_options<OdeintOptions>();
    o.method = m == AutoMethod::dopri5 ? OdeintMethod::dopri5 : OdeintMethod::fehlberg78;
    o.stiffness_window = options_.stiffness_window;
    o.interpolate_outputs = true;
    return o;
  }

  [[nodiscard]] SceneIntegratorOptions bdf_options() const {
    auto o = shared_options<SceneIntegratorOptions>();
    o.method = CvodeMethod::bdf;
    if (scene_->size() > kDenseLimit) {
      o.cvode.linear_solver = CvodeLinearSolver::band;  // the scene's own half-bandwidth
    }
    return o;
  }

  /// The first decision at (t, s) (point 1), and the integrator of the chosen method there.
  void start(double t, const SceneState& s) {
    detail::check_scene_state(*scene_, s, "tumble::AutoIntegrator");
    if (!std::isfinite(t)) {
      throw std::invalid_argument("tumble::AutoIntegrator: the time " + detail::format_double(t) +
                                  " is not finite");
    }
    finished_ = AutoStatistics{};
    choices_.clear();
    double h_rho = 0.0;
    const bool stiff = stiff_at(t, s, h_rho);
    char buf[200];
    if (stiff) {
      std::snprintf(buf, sizeof buf,
                    "stiff at the start: h rho = %.3g > %.3g for the step h an explicit method "
                    "would take and the Jacobian's largest eigenvalue modulus rho",
                    h_rho, kStiffAtStart);
      begin(AutoMethod::bdf, t, s, buf);
    } else {
      std::snprintf(buf, sizeof buf,
                    "not stiff at the start (h rho = %.3g <= %.3g): the explicit path, the most "
                    "accurate pair per right-hand side",
                    h_rho, kStiffAtStart);
      begin(AutoMethod::fehlberg78, t, s, buf);
    }
  }

  /// Makes (or resets) the integrator of method m at (t, s) and records the choice.
  void begin(AutoMethod m, double t, const SceneState& s, std::string why) {
    if (m == AutoMethod::bdf) {
      if (implicit_) {  // a reset CVODE runs as a new one, to the bit
        implicit_->reset(t, s);
      } else {
        implicit_.emplace(*scene_, t, s, bdf_options());
      }
      implicit_base_ = implicit_->statistics();
      explicit_.reset();
    } else {
      if (explicit_ && method_ == m) {
        explicit_->reset(t, s);
      } else {
        explicit_.emplace(*scene_, t, s, odeint_options(m));
      }
      explicit_base_ = explicit_->statistics();
    }
    method_ = m;
    choices_.push_back({m, t, std::move(why)});
  }

  /// The explicit path found the scene stiff: BDF from its last accepted step. Without a
  /// stiffness window the user asked for no hand-over: the error (from a spent step budget) goes
  /// on to the caller.
  void to_bdf(const StiffSceneError& e) {
    if (options_.stiffness_window == 0) {
      throw;  // called from the handler of e
    }
    hand_over(AutoMethod::bdf, std::string("stiff on the way: ") + e.what());
  }

  /// Fehlberg 7(8)'s steps are cut by the outputs: Dormand-Prince from here (point 2).
  void to_dopri5(double spacing) {
    char buf[240];
    std::snprintf(buf, sizeof buf,
                  "the outputs (every %.3g) cut the steps of Fehlberg 7(8), whose controller "
                  "asks for %.3g: Dormand-Prince reads them off its dense output",
                  spacing, explicit_->step_size());
    hand_over(AutoMethod::dopri5, buf);
  }

  /// Point 2's check: Dormand-Prince on the outputs ts[done..] in chunks that double; after
  /// each, its right-hand sides per unit time since it took over (rejected steps and its start
  /// included) against Fehlberg 7(8)'s cheapest on outputs `spacing` apart, one step per
  /// output; when it costs more, Fehlberg takes the rest back. (Where Fehlberg's own steps are
  /// shorter than the spacing it costs more than that; but where Dormand-Prince's steps are
  /// that short, Fehlberg's order 8 takes fewer right-hand sides for the accuracy: A04 at 1e-8,
  /// 3566 against 5223.) Returns with the outputs left for the method running then.
  /// `done` counts the outputs handed to the observer; `observe` advances it.
  template <class Observe>
  void dense_chunks(const std::vector<double>& ts, const std::size_t& done, double spacing,
                    Observe& observe) {
    const double fehlberg = kFehlbergStages / spacing;
    const double t0 = time();
    const long rhs0 = explicit_->statistics().rhs_evals;
    for (std::size_t chunk = kDenseCheckOutputs; ts.size() - done > chunk; chunk *= 2) {
      explicit_->integrate(std::span<const double>(ts).subspan(done, chunk), observe);
      const double elapsed = time() - t0;
      const auto rhs = static_cast<double>(explicit_->statistics().rhs_evals - rhs0);
      if (elapsed > 0.0 && rhs > fehlberg * elapsed) {
        char buf[240];
        std::snprintf(buf, sizeof buf,
                      "Dormand-Prince took %.3g right-hand sides per unit time since it took "
                      "over, Fehlberg 7(8) at most %.3g (one step per output): Fehlberg 7(8) "
                      "from here",
                      rhs / elapsed, fehlberg);
        hand_over(AutoMethod::fehlberg78, buf);
        return;
      }
    }
  }

  /// The explicit integrator's counters kept, then method m from its current state.
  void hand_over(AutoMethod m, std::string why) {
    add(finished_, explicit_->statistics(), explicit_base_);
    const double t = explicit_->time();
    const SceneState s = explicit_->save();
    explicit_.reset();
    begin(m, t, s, std::move(why));
  }

  /// Point 1: h rho at (t, s) against kStiffAtStart; false (and h_rho = 0) when the scene cannot
  /// be evaluated there, a non-finite value or a load's own exception (the explicit integrator
  /// then reports it, as in a step: an IntegrationError of reason callback), or when the window
  /// test is off.
  bool stiff_at(double t, const SceneState& s, double& h_rho) {
    h_rho = 0.0;
    if (options_.stiffness_window == 0) {
      return false;
    }
    SceneWorkspace<SceneT> ws(*scene_);
    const Eigen::Index n = s.y.size();
    Eigen::VectorXd f0(n), v(n), y1(n), f1(n);
    const std::span<const Matrix3<double>> bases(s.base);
    const auto f = [&](const auto& y, auto& out) {
      try {
        ++finished_.rhs_evals;
        tumble::rhs(*scene_, ws, t, y, bases, out);
        return out.allFinite();
      } catch (const NonFiniteError&) {
        return false;
      }
    };
    try {
      if constexpr (SceneT::has_joints) {
        // The redundant rows decided once, as the integrators do: left to each evaluation, the
        // pivots of a mechanism with redundant rows (the N-four-bar: 35 rows of rank 29) can
        // fall differently at the perturbed states than at s, and the difference quotients then
        // measure that jump, not the Jacobian (h rho = 556 at tol 1e-4, where the smooth field
        // gives 0.35).
        detail::freeze_redundant_rows(*scene_, ws, s.y, bases);
      }
      if (!f(s.y, f0)) {
        return false;
      }
      const double rho = detail::spectral_radius(f, s.y, f0, v, y1, f1);
      const double h = std::visit(
          [&](const auto& atol) {
            return detail::initial_step(f, s.y, f0, y1, f1, atol, options_.rtol, 8.0,
                                        options_.max_step);
          },
          options_.atol);
      h_rho = h * rho;
    } catch (...) {  // a load's own exception: see above
      return false;
    }
    return h_rho > kStiffAtStart;
  }

  const SceneT* scene_;
  AutoOptions options_;
  AutoMethod method_ = AutoMethod::fehlberg78;
  std::optional<Explicit> explicit_;
  std::optional<Implicit> implicit_;
  OdeintStatistics explicit_base_{};  ///< the running integrator's counters when it took over
  SceneStatistics implicit_base_{};
  AutoStatistics finished_;  ///< the methods that have handed over, and the front door's tests
  std::vector<MethodChoice> choices_;
};

/// Integrates `scene` from (t0, its initial state) to each of `times`, calling
/// observer(t, const SceneState&) there, by the method the library chooses; returns what ran
/// and why (AutoStatistics::choices) with the counters.
template <class SceneT, class Times, class Observer>
AutoStatistics integrate(const SceneT& scene, double t0, const Times& times, Observer&& observer,
                         AutoOptions options = {}) {
  AutoIntegrator<SceneT> integrator(scene, t0, std::move(options));
  integrator.integrate(times, std::forward<Observer>(observer));
  return integrator.statistics();
}

/// The same from the state s0 of the scene.
template <class SceneT, class Times, class Observer>
AutoStatistics integrate(const SceneT& scene, double t0, const SceneState& s0, const Times& times,
                         Observer&& observer, AutoOptions options = {}) {
  AutoIntegrator<SceneT> integrator(scene, t0, s0, std::move(options));
  integrator.integrate(times, std::forward<Observer>(observer));
  return integrator.statistics();
}

template <class SceneT, class Observer>
AutoStatistics integrate(const SceneT& scene, double t0, std::initializer_list<double> times,
                         Observer&& observer, AutoOptions options = {}) {
  return integrate(scene, t0, std::span<const double>(times.begin(), times.size()),
                   std::forward<Observer>(observer), std::move(options));
}

}  // namespace tumble
