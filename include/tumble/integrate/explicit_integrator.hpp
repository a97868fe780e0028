#pragma once
// OdeintIntegrator: a Scene (scene/scene.hpp) integrated by an explicit embedded Runge-Kutta pair
// of Boost.Odeint (header-only), for small non-stiff scenes where CVODE's per-step overhead and
// its restarts at every chart switch dominate. The same shape of interface as the CVODE
// SceneIntegrator (scene_integrator.hpp): advance, integrate, reset, state, statistics.
//
// The state is Odeint's std::array<double, N> when the scene's size N is a template argument
// (checked against scene.size()), a std::vector otherwise, viewed through Eigen::Map; nothing is
// allocated per step (events' user callables aside), and what a step writes on the heap is whole
// cache lines of its own (core/cache_line.hpp). Odeint supplies the steppers and the step-size
// controller (try_step); the loop is here, and between two accepted steps it does what a
// one-step method can do without a restart (docs/integrators.md, "The explicit integrator"):
// charts re-centered after a step that ends in a switch zone (one that ends deep in it is
// retried shorter), Euler parameters and a mechanism's joints projected after every step, user
// events located on the step (Illinois) and the step cut there (detail/explicit_events.hpp),
// output times stepped to exactly (or, with Dormand-Prince, read off its dense output), and a
// stiffness test every stiffness_window attempts and when a budget is spent
// (detail/explicit_diagnostics.hpp).
// Never a run that does not end, never a NaN state: non-finite trial states are rejected, and a
// step size at the rounding level of t throws. An exception of a load, force or event function
// stops it as CVODE's does (detail/callback_error.hpp): reason() callback, the original as cause().

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include <Eigen/Core>

#include "tumble/core/cache_line.hpp"
#include "tumble/core/errors.hpp"
#include "tumble/core/format.hpp"
#include "tumble/integrate/detail/callback_error.hpp"
#include "tumble/integrate/detail/explicit_diagnostics.hpp"
#include "tumble/integrate/detail/explicit_events.hpp"
#include "tumble/integrate/detail/explicit_numerics.hpp"
#include "tumble/integrate/detail/odeint_stepper.hpp"
#include "tumble/integrate/detail/state_check.hpp"
#include "tumble/integrate/errors.hpp"
#include "tumble/integrate/explicit_options.hpp"
#include "tumble/scene/assembly.hpp"
#include "tumble/scene/chart.hpp"
#include "tumble/scene/charts.hpp"
#include "tumble/scene/projection.hpp"
#include "tumble/scene/rhs.hpp"
#include "tumble/scene/scene.hpp"
#include "tumble/scene/state.hpp"
#include "tumble/scene/workspace.hpp"

namespace tumble {

/// A scene integrated by Boost.Odeint. N: the scene's size (Scene::size()) when known at compile
/// time (no heap allocation at all in a step), or Eigen::Dynamic.
template <class SceneT, int N = Eigen::Dynamic> class OdeintIntegrator {
  using State = detail::OdeintState<N>;
  using Vec = Eigen::Matrix<double, N, 1>;

 public:
  using Options = OdeintOptions;
  using Statistics = OdeintStatistics;

  /// Integrate `scene` from t0 starting at the scene's initial state. The scene must outlive
  /// the integrator; the integrator only reads it.
  OdeintIntegrator(const SceneT& scene, double t0, OdeintOptions options = {})
      : OdeintIntegrator(scene, t0, scene.initial_state(), options) {}

  /// Integrate `scene` from (t0, s0), a state of this scene.
  OdeintIntegrator(const SceneT& scene, double t0, const SceneState& s0, OdeintOptions options = {})
      : scene_(&scene),
        options_(detail::checked_odeint_options<N>(options, scene.size())),
        ws_(scene),
        stepper_(detail::make_odeint_stepper<State>(options_)),
        events_(scene.events(), scene.size(), static_cast<std::size_t>(scene.body_count()), kWho) {
    ws_.stabilize_constraints = options_.stabilize_quaternions;
    const int n = scene.size();
    if constexpr (N == Eigen::Dynamic) {
      for (State* v : {&x_, &dxdt_, &x_old_, &dxdt_old_, &x_new_, &dxdt_new_, &x_tmp_}) {
        v->assign(static_cast<std::size_t>(n), 0.0);
      }
    }
    g_.assign(scene.chart_bodies().size(), 0.0);
    g0_.assign(g_.size(), 0.0);
    scene.for_each_entry([&](const auto& e) {
      using Body = std::remove_cvref_t<decltype(e.body)>;
      if constexpr (Chart<typename Body::Param>::has_singularity) {
        deep_.push_back(-0.5 * e.switch_distance);
      }
    });
    switches_.assign(static_cast<std::size_t>(scene.body_count()), 0);
    // The interpolated outputs and the current state (sync()): sized once, so that neither a step
    // nor an output allocates.
    for (SceneState* s : {&out_state_, &state_}) {
      s->y.setZero(n);
      s->base.assign(static_cast<std::size_t>(scene.body_count()), Matrix3<double>::Identity());
    }
    reset(t0, s0);
  }

  /// A scene must outlive its integrator: a temporary would not.
  OdeintIntegrator(SceneT&&, double, OdeintOptions = {}) = delete;
  OdeintIntegrator(SceneT&&, double, const SceneState&, OdeintOptions = {}) = delete;

  /// Integrates to t_out (>= time()). The state there is state(); save() keeps a copy.
  void advance(double t_out) {
    if (!std::isfinite(t_out) || t_out < t_) {
      throw std::invalid_argument("tumble::OdeintIntegrator::advance: t_out = " + num(t_out) +
                                  " must be finite and not before the current time " + num(t_));
    }
    run_ = detail::StepRun{.t_start = t_};
    std::visit(
        [&](auto& s) {
          while (t_ < t_out) {
            step_with(s, t_out);
          }
        },
        stepper_);
    sync();
  }

  /// observer(t, state) at each output time (non-decreasing, not before time(), validated before
  /// integrating).
  template <class Times, class Observer> void integrate(const Times& times, Observer&& observer) {
    detail::check_output_times("tumble::OdeintIntegrator::integrate", t_, times);
    std::visit(
        [&]<class S>(S& st) {
          if constexpr (S::dense) {  // Dormand-Prince
            if (options_.interpolate_outputs && scene_->events().empty()) {
              integrate_dense(st, times, observer);
              return;
            }
          }
          for (const double t : times) {
            advance(t);
            observer(t, std::as_const(state_));
          }
        },
        stepper_);
  }
  template <class Observer>
  void integrate(std::initializer_list<double> times, Observer&& observer) {
    integrate(std::span<const double>(times.begin(), times.size()),
              std::forward<Observer>(observer));
  }

  /// Restarts from the state s at time t (charts in their switch zone are re-centered first).
  void reset(double t, const SceneState& s) {
    detail::check_scene_state_at(*scene_, s, t, kWho);
    const ChartBases old = base_;
    const State x_old = x_;
    const std::vector<char> rows_old = ws_.joints().dependent;  // the frozen redundant rows
    try {
      Eigen::Map<Vec>(x_.data(), size()) = s.y;
      base_ = s.base;
      if constexpr (SceneT::has_joints) {  // which rows are redundant: decided once per run
        detail::freeze_redundant_rows(*scene_, ws_, map(std::as_const(x_)), bases());
      }
      bool recentered = false;
      after_change(recentered);
      // NonFiniteError: a state the scene cannot evaluate; a load's own exception: as in a step.
      detail::guard_callbacks(kWho, "rhs()", t, t, [&] { evaluate(x_, dxdt_, t); });
      deriv_valid_ = true;
    } catch (...) {  // back to the state before; NonFiniteError is bad input here
      base_ = old;
      x_ = x_old;
      ws_.joints().dependent = rows_old;
      deriv_valid_ = false;  // dxdt_ may be half written
      try {
        throw;
      } catch (const NonFiniteError& e) {
        throw std::invalid_argument(std::string("tumble::OdeintIntegrator::reset: the scene cannot "
                                                "be evaluated at this state: ") +
                                    e.what());
      }
    }
    t_ = t;
    window_ = detail::StepRun{.t_start = t};
    h_ = options_.initial_step > 0.0 ? options_.initial_step : initial_step();
    events_.start(t_, x_.data(), bases());
    sync();
  }

  /// The current state, the continuous vector and the chart bases: a view that every call that
  /// integrates changes. To keep a state, save() it.
  [[nodiscard]] const SceneState& state() const { return state_; }
  /// A copy of the current state, to keep (reset() restarts from it). save(into) copies into a
  /// state of this scene without allocating.
  [[nodiscard]] SceneState save() const {
    SceneState s;
    save(s);
    return s;
  }
  void save(SceneState& into) const {
    into.y = map(x_);
    into.base = base_;
  }
  [[nodiscard]] double time() const { return t_; }
  /// The step size the controller proposes for the next step (kept across output times).
  [[nodiscard]] double step_size() const { return h_; }
  [[nodiscard]] OdeintStatistics statistics() const {
    OdeintStatistics s = stats_;
    for (const long n : switches_) {
      s.chart_switches += n;
    }
    return s;
  }
  /// Chart switches of one body since construction.
  template <class Body> [[nodiscard]] long chart_switches(BodyId<Body> b) const {
    return switches_[static_cast<std::size_t>(scene_->entry(b).id)];
  }
  [[nodiscard]] const SceneT& scene() const { return *scene_; }
  [[nodiscard]] const OdeintOptions& options() const { return options_; }

 private:
  using Stepper = detail::OdeintStepper<State>;

  /// integrate() on the dense output of S: free steps to the last output time; each accepted
  /// step hands the outputs inside it to the observer, interpolated on the step (x_old_, x_
  /// before the projection and the chart switch, base_ the step's chart bases).
  template <class S, class Times, class Observer>
  void integrate_dense(S& stepper, const Times& times, Observer& observer) requires S::dense {
    auto it = std::begin(times);
    const auto end = std::end(times);
    for (; it != end && *it <= t_; ++it) {
      observer(*it, std::as_const(sync()));
    }
    double t_last = t_;
    for (auto j = it; j != end; ++j) {
      t_last = *j;
    }
    const System<S> sys{this};
    const auto outputs = [&](double t_old, double t_new) {
      const auto first = it;
      for (; it != end && *it <= t_new; ++it) {
        stepper.state_at(sys, *it, x_tmp_, x_old_, dxdt_old_, t_old, x_, dxdt_, t_new);
        count_stages(S::evaluations_per_state_at);
        out_state_.y = map(x_tmp_);
        copy_bases(out_state_);
        project_onto_constraints(out_state_.y);
        observer(*it, std::as_const(out_state_));
      }
      if (it != first) {
        run_ = detail::StepRun{.t_start = t_new};  // the step budget counts per output interval
      }
    };
    run_ = detail::StepRun{.t_start = t_};
    while (t_ < t_last) {
      step_with(stepper, t_last, outputs);
    }
    sync();
  }

  /// Whether the scene's right-hand side calls user code (a load's or a joint's callable), which
  /// may throw in a stage. Where it does not, nothing in a stage can throw: every try_step and
  /// state_at evaluates all its stages, and the step counts them (count_stages) instead of each
  /// stage counting itself and noting its time for a message. Those two stores in each stage
  /// were 23k of the 844k instructions of the tumbling body's run to 1e-6 in the main job
  /// (callgrind, docs/benchmarks/floors.md, 2026-12-05).
  static constexpr bool kStagesCallUserCode = SceneT::has_loads || SceneT::has_joints;

  /// What Odeint calls for the stages of a step of the stepper S: x' = f(t, x), unchecked (see
  /// stage()); inlined into them for a scene whose right-hand side calls no user code.
  template <class S> struct System {
    static constexpr bool inline_stages = !kStagesCallUserCode;
    OdeintIntegrator* self;
    [[gnu::always_inline]] void operator()(const State& x, State& dxdt, double t) const {
      self->template stage<S::fsal>(x, dxdt, t);
    }
  };

  [[nodiscard]] Eigen::Index size() const { return scene_->size(); }
  Eigen::Map<Vec> map(State& x) const { return Eigen::Map<Vec>(x.data(), size()); }
  Eigen::Map<const Vec> map(const State& x) const {
    return Eigen::Map<const Vec>(x.data(), size());
  }
  std::span<const Matrix3<double>> bases() const { return base_; }
  static std::string num(double v) { return detail::format_double(v); }
  static constexpr const char* kWho = "tumble::OdeintIntegrator";

  /// x' at x; throws NonFiniteError when it is not finite.
  void evaluate(const State& x, State& dxdt, double t) {
    ++stats_.rhs_evals;
    t_eval_ = t;
    tumble::rhs(*scene_, ws_, t, map(x), bases(), map(dxdt));
  }

  /// x' at a stage of a trial step, not checked one by one: step_with checks x_new once per
  /// step instead. Odeint's generic pairs (Fehlberg 7(8), Cash-Karp) sum every stage into x_new,
  /// zero weights included, and 0 * inf is NaN: a non-finite stage shows in x_new. Dormand-Prince
  /// (CheckInput) leaves its second stage out of x_new, so its stages check their input x, which
  /// sums every stage before it (its last stage is dxdt_new, which step_with checks). A
  /// non-finite entry sets stage_not_finite_, and step_with rejects the step (as if the evaluation
  /// had thrown). Checking each stage's rates just written instead cost 20 % of a run (they are
  /// read back while the stores are in flight); checking each input, 4 %.
  template <bool CheckInput> [[gnu::flatten]] void stage(const State& x, State& dxdt, double t) {
    if constexpr (kStagesCallUserCode) {
      ++stats_.rhs_evals;
      t_eval_ = t;  // for the message, should a load throw
    }
    if constexpr (CheckInput) {
      if (!finite(x)) [[unlikely]] {
        stage_not_finite_ = true;
      }
    }
    tumble::rhs<FiniteCheck::by_caller>(*scene_, ws_, t, map(x), bases(), map(dxdt));
  }

  /// Counts n evaluations by stages that do not count themselves (kStagesCallUserCode).
  void count_stages(long n) {
    if constexpr (!kStagesCallUserCode) {
      stats_.rhs_evals += n;
    }
  }

  /// finite * 0 = 0, inf * 0 and NaN * 0 are NaN: the sum is 0 exactly when all are finite.
  [[gnu::always_inline]] bool finite(const State& v) const {
    return (map(v).array() * 0.0).sum() == 0.0;
  }

  /// Projects y (with the bases of x_) onto the unit quaternions (scene/projection.hpp), then a
  /// mechanism's joints (scene/assembly.hpp); false when the scene has neither (y unchanged).
  template <class Y> bool project_onto_constraints(Y& y) {
    if constexpr (SceneT::has_constraints) {
      tumble::project_in_place(*scene_, y);
    }
    if constexpr (SceneT::has_joints) {
      // Where the rows frozen as redundant no longer leave the others independent, they are
      // decided again here, between two steps (scene/assembly.hpp).
      const ConstraintResidual r = detail::project_mechanism(*scene_, ws_, y, bases());
      if (!(r.position <= detail::kJointProjectionFailure)) [[unlikely]] {
        throw ExplicitIntegrationError("tumble::OdeintIntegrator: the projection onto the joints' "
                                       "constraints did not converge (max |C| = " +
                                           num(r.position) + " at t = " + num(t_) + ")",
                                       IntegrationFailure::solver, t_);
      }
    }
    return SceneT::has_constraints || SceneT::has_joints;
  }

  /// Projects the quaternions and re-centers the charts of x_ (in their switch zone); true if
  /// y changed. `recentered`: whether a chart was.
  bool after_change(bool& recentered) {
    Eigen::Map<Vec> y = map(x_);
    const bool changed = project_onto_constraints(y);
    if constexpr (SceneT::has_joints) {  // the accuracy the next step's evaluations allow
      const double floor = detail::attainable_tolerance(ws_.joints());
      tolerance_floor_ = floor > options_.rtol ? floor : 0.0;
    }
    stats_.projections += changed ? 1 : 0;
    recentered = recenter_charts(*scene_, y, std::span<Matrix3<double>>(base_),
                                 [this](int id) { ++switches_[static_cast<std::size_t>(id)]; }) > 0;
    return changed || recentered;
  }

  /// The initial step (detail::initial_step) for the stepper's order.
  double initial_step() {
    const double p = std::visit([](const auto& s) { return double(s.order); }, stepper_);
    auto y1 = map(x_tmp_);
    auto f1 = map(x_new_);
    return std::visit(
        [&](const auto& atol) {
          return detail::initial_step(evaluator(), map(std::as_const(x_)),
                                      map(std::as_const(dxdt_)), y1, f1, atol, options_.rtol, p,
                                      options_.max_step);
        },
        options_.atol);
  }

  /// f(y, f) for the numerics of detail/explicit_numerics.hpp: false when y cannot be evaluated.
  auto evaluator() {
    return [this](const auto& y, auto& f) {
      try {
        ++stats_.rhs_evals;
        tumble::rhs(*scene_, ws_, t_, y, bases(), f);
        return true;
      } catch (const NonFiniteError&) {
        return false;
      } catch (const RecoverableError&) {
        return false;
      } catch (...) {
        detail::throw_callback_error(kWho, "rhs()", t_, t_);
      }
    };
  }

  /// One accepted step towards t_out (cut at an event); throws when the budget is spent.
  /// on_step(t_old, t_new) sees the accepted step before events, projection and chart switches.
  template <class S, class OnStep = void (*)(double, double)>
  void step_with(
      S& stepper, double t_out, OnStep&& on_step = [](double, double) {}) {
    const System<S> sys{this};
    for (;;) {
      if (options_.max_steps > 0 && run_.attempts >= options_.max_steps) {
        stiffness_test(t_out, true);
      }
      if (options_.stiffness_window > 0 && window_.attempts >= options_.stiffness_window) {
        stiffness_test(t_out);
      }
      ++run_.attempts;
      ++window_.attempts;
      // Step to t_out exactly when it is within reach.
      const bool to_end = t_out - t_ <= std::min(h_, options_.max_step);
      const double h_try = to_end ? t_out - t_ : std::min(h_, options_.max_step);
      double h = h_try, t = t_;
      bool ok = false;
      try {
        if (!deriv_valid_) {
          stage<false>(x_, dxdt_, t_);
          count_stages(1);
          if (!finite(dxdt_)) {
            evaluate(x_, dxdt_, t_);  // throws NonFiniteError, naming the body and the cause
          }
          deriv_valid_ = true;
        }
        stage_not_finite_ = false;
        if constexpr (SceneT::has_joints) {
          stepper.raise_tolerances_to(tolerance_floor_);
        }
        ok = stepper.try_step(sys, x_, dxdt_, t, x_new_, dxdt_new_, h);
        count_stages(S::evaluations_per_try);
        if (!finite(x_new_) || (S::fsal && !finite(dxdt_new_))) {  // see stage()
          stage_not_finite_ = true;
        }
        if (stage_not_finite_) {  // as when an evaluation throws NonFiniteError, below
          ok = false;
          h = 0.25 * h_try;
        } else if (!ok) {
          ++run_.rejected;
          ++window_.rejected;
        } else if (const double f =  // < 1: a chart ends deep in its switch zone (charts.hpp)
                   chart_step_fraction(*scene_, map(x_), map(x_new_), deep_, g0_, g_);
                   f < 1.0) {
          ok = false;
          h = f * h_try;
        }
      } catch (const NonFiniteError&) {
        if (!deriv_valid_) {  // the state itself cannot be evaluated: nothing to retry
          throw ExplicitIntegrationError(
              "tumble::OdeintIntegrator: the right-hand side is not finite at t = " + num(t_),
              IntegrationFailure::callback, t_);
        }
        ok = false;
        h = 0.25 * h_try;
      } catch (const RecoverableError&) {  // a load asks for a shorter step, as CVODE retries
        if (!deriv_valid_) {
          detail::throw_callback_error(kWho, "rhs()", t_, t_);
        }
        ok = false;
        h = 0.25 * h_try;
      } catch (...) {  // a load's or a force's own exception: the step's one handler
        detail::throw_callback_error(kWho, "rhs()", t_eval_, t_);
      }
      if (!ok) {
        ++stats_.rejected_steps;
        if (!(h > 0.0) || t_ + h == t_) {
          throw ExplicitIntegrationError(
              "tumble::OdeintIntegrator: the step size fell to " + num(h) +
                  ", below the rounding level of t = " + num(t_) +
                  " (a state the scene cannot be evaluated at, or a singularity, ahead)",
              IntegrationFailure::step_size, t_);
        }
        h_ = h;
        continue;
      }
      ++stats_.steps;
      ++run_.accepted;
      ++window_.accepted;
      if constexpr (SceneT::has_joints) {
        if (tolerance_floor_ > 0.0) [[unlikely]] {
          ++stats_.relaxed_steps;
          ++window_.relaxed;
          stats_.loosest_tolerance = std::max(stats_.loosest_tolerance, tolerance_floor_);
        }
      }
      // Stepped to t_out exactly: keep the controller's longer suggestion for the next step.
      const double t_new = to_end ? t_out : t;
      h_ = to_end ? std::max(h, h_) : h;
      finish_step(stepper, sys, t_new, on_step);
      return;
    }
  }

  /// After an accepted step from (t_, x_) to (t_new, x_new_): events, then projection and charts.
  /// The step's start is kept (x_old_) only for Dormand-Prince's dense output and the events.
  template <class S, class OnStep>
  void finish_step(S& stepper, const System<S>& sys, double t_new, OnStep& on_step) {
    if (S::dense || !events_.empty()) {
      std::swap(x_old_, x_);
      std::swap(dxdt_old_, dxdt_);
    }
    std::swap(x_, x_new_);
    if constexpr (S::fsal) {
      std::swap(dxdt_, dxdt_new_);
    }
    const double t_old = t_;
    t_ = t_new;
    on_step(t_old, t_new);
    bool event = false, recentered = false;
    if (!events_.empty()) {  // on the step's interpolant (Odeint's, or a step of the same method)
      event = events_.on_step(t_old, t_, x_, x_tmp_, base_, [&](double t, State& out) {
        detail::guard_callbacks(kWho, "rhs()", t, t_, [&] {
          stepper.state_at(sys, t, out, x_old_, dxdt_old_, t_old, x_, dxdt_, t_new);
        });
        count_stages(S::evaluations_per_state_at);
      });
      stats_.events += event ? 1 : 0;
    }
    const bool changed = after_change(recentered) || event;
    deriv_valid_ = S::fsal && !changed;
    events_.next_step(changed, t_, x_.data(), bases());
  }

  /// detail::spectral_radius at the current state (only when a budget is spent, so the scratch
  /// states are free); 0 when the right-hand side cannot be evaluated.
  double spectral_radius() {
    const auto f = evaluator();
    auto f0 = map(dxdt_);
    if (!deriv_valid_ && !f(map(std::as_const(x_)), f0)) {
      return 0.0;
    }
    deriv_valid_ = true;
    auto v = map(x_new_);
    auto y1 = map(x_tmp_);
    auto f1 = map(dxdt_new_);
    return detail::spectral_radius(f, map(std::as_const(x_)), map(std::as_const(dxdt_)), v, y1, f1);
  }

  /// detail::stiffness_test on this advance's attempts (`spent`: its budget is spent) or on the
  /// window's.
  void stiffness_test(double t_out, bool spent = false) {
    detail::stiffness_test(window_, run_, t_, t_out, options_.max_steps, spent, SceneT::has_joints,
                           [this] { return spectral_radius(); });
  }

  /// Copies the current state into state_; no allocation.
  const SceneState& sync() {
    state_.y = map(x_);
    copy_bases(state_);
    return state_;
  }

  /// base_ into s.base, one of the integrator's own states (sized as base_ on construction): the
  /// entries copied, not the vector assigned, at every output.
  void copy_bases(SceneState& s) const { std::copy(base_.begin(), base_.end(), s.base.begin()); }

  const SceneT* scene_;
  OdeintOptions options_;
  SceneWorkspace<SceneT> ws_;
  Stepper stepper_;
  State x_{}, dxdt_{}, x_old_{}, dxdt_old_{}, x_new_{}, dxdt_new_{}, x_tmp_{};
  bool deriv_valid_ = false;        ///< dxdt_ is x' at x_
  bool stage_not_finite_ = false;   ///< some stage of the current trial step was not finite
  detail::StepRun run_;             ///< this advance (or output interval): the step budget
  detail::StepRun window_;          ///< the attempts since the last stiffness test
  double t_ = 0.0, h_ = 0.0;        ///< time, next step size
  double t_eval_ = 0.0;             ///< the time of the last evaluation of the scene
  double tolerance_floor_ = 0.0;    ///< > 0: the next step's error test asks no less (joints)
  CacheLineVector<double> g_, g0_;  ///< chart roots at a step's end and start
  std::vector<double> deep_;        ///< per chart body: roots below this reject a step
  detail::StepEvents events_;       ///< the scene's events: their functions at the step's ends
  ChartBases base_;
  CacheLineVector<long> switches_;
  SceneState state_, out_state_;
  OdeintStatistics stats_;
};

}  // namespace tumble
