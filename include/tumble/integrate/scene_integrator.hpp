#pragma once
// SceneIntegrator: a Scene (scene/scene.hpp) integrated in time by CVODE (integrate/cvode.hpp).
//
// The scene is the model and is only read; everything that changes during the run belongs to the
// integrator: the state (the continuous vector in CVODE's memory and the chart bases beside it),
// the evaluation workspace, the block preconditioner and the counters. It sets up what the
// scene's coordinates need:
// - Euler parameters: with BDF, CVODE's projection onto |p| = 1, p.pdot = 0 after every step
//   (CVodeSetProjFn; CVODE supports projection only with BDF); with Adams, the Baumgarte-
//   stabilized constraint acceleration instead (scene/rhs.hpp). In the quasi-velocity state form
//   (scene/state.hpp) the projection normalizes p alone and Adams gets a first-order drift
//   correction of p (scene/detail/body_terms.hpp); nothing here depends on the form.
// - Three-parameter sets: one root function per body watches the distance to the chart's
//   singularity; at a root the chart is re-centered (MRP: shadow set) and CVODE restarts.
// - User events: the scene's root functions and actions, with a restart when the state changes.
// - BDF's Newton iteration gets the exact Jacobian df/dy (dense or band) by automatic
//   differentiation (scene/jacobian.hpp) when every load can be differentiated; otherwise, or
//   with CvodeOptions::use_system_jacobian = false, CVODE forms it by difference quotients. With
//   GMRES the same blocks give a block-Jacobi preconditioner (scene/preconditioner.hpp). A
//   mechanism (quasi-velocity form) gets its exact Jacobian in dense storage only: the
//   multipliers couple every body of a loop or chain, so its Jacobian is dense there (band
//   storage and GMRES keep CVODE's difference quotients and no preconditioner).
// A NonFiniteError met in the right-hand side becomes a recoverable error: CVODE retries with a
// smaller step, and reports an IntegrationError if it cannot recover.

#include <limits>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "tumble/core/band_matrix.hpp"
#include "tumble/core/cache_line.hpp"
#include "tumble/core/errors.hpp"
#include "tumble/integrate/common.hpp"
#include "tumble/integrate/cvode.hpp"
#include "tumble/integrate/detail/event_action.hpp"
#include "tumble/integrate/detail/state_check.hpp"
#include "tumble/integrate/errors.hpp"
#include "tumble/scene/assembly.hpp"
#include "tumble/scene/charts.hpp"
#include "tumble/scene/jacobian.hpp"
#include "tumble/scene/preconditioner.hpp"
#include "tumble/scene/projection.hpp"
#include "tumble/scene/rhs.hpp"
#include "tumble/scene/scene.hpp"
#include "tumble/scene/state.hpp"
#include "tumble/scene/workspace.hpp"

namespace tumble {

/// Options of a SceneIntegrator: the vocabulary both integrators share (integrate/common.hpp),
/// CVODE's method and own options, and how Euler parameters keep their norm.
struct SceneIntegratorOptions {
  // --- shared with OdeintOptions (integrate/common.hpp) ---
  double rtol = SharedDefaults::rtol;             ///< relative tolerance, > 0
  AbsoluteTolerance atol = SharedDefaults::atol;  ///< one value > 0, or one per entry of y
  /// Internal steps allowed in one advance(), or between two output times of integrate()
  /// (CvodeOptions::max_steps); 0: no limit.
  long max_steps = SharedDefaults::max_steps;
  double initial_step = 0.0;  ///< 0: estimated by CVODE
  double max_step = std::numeric_limits<double>::infinity();
  // --- CVODE only ---
  CvodeMethod method = CvodeMethod::bdf;
  /// CVODE's own options. With CvodeLinearSolver::band and the bandwidths left at -1, the scene's
  /// own half-bandwidth is used (Scene::half_bandwidth).
  CvodeSolverOptions cvode{};
  /// With BDF: project Euler parameters onto their constraint after each step. With Adams the
  /// Baumgarte stabilization is used (CVODE cannot project with Adams).
  bool project_quaternions = true;
  /// Where Euler parameters are not projected (Adams, or BDF with project_quaternions = false):
  /// stabilize |p| = 1 with Baumgarte terms in the constraint acceleration (scene/rhs.hpp). Off,
  /// the constraint drifts freely (for studies of the drift itself).
  bool stabilize_quaternions = true;

  /// The options of the Cvode<System> underneath (without the projection, which the integrator
  /// sets from the scene).
  [[nodiscard]] CvodeOptions cvode_options() const {
    CvodeOptions o;
    o.solver() = cvode;
    o.method = method;
    o.rtol = rtol;
    o.atol = atol;
    o.max_steps = max_steps;
    o.initial_step = initial_step;
    o.max_step = max_step;
    return o;
  }
};

/// The shared counters (integrate/common.hpp) and CVODE's own (the base) with the scene's chart
/// switches. steps, rhs_evals and projections are CVODE's; rejected_steps counts its failed
/// error tests and failed nonlinear solves, each followed by a retry with a smaller step.
struct SceneStatistics : CvodeStatistics {
  long rejected_steps = 0;
  long chart_switches = 0;  ///< re-centerings and MRP shadow switches since construction
  long events = 0;          ///< user events acted on (their actions called)
};
static_assert(IntegratorStatisticsLike<SceneStatistics>);
static_assert(IntegratorOptionsLike<SceneIntegratorOptions>);

namespace detail {

/// A scene and the data of one run of it, as a CVODE system (see CvodeSystem and its optional
/// members). Lives in CVODE's core on the heap, so its address is stable.
template <class SceneT> class SceneSystem {
  struct NoPreconditioner {};
  /// The block-Jacobi preconditioner: the bodies' own blocks, which a mechanism's multipliers
  /// couple (none for a mechanism).
  static constexpr bool preconditionable = SceneT::differentiable && !SceneT::has_joints;
  using Preconditioner =
      std::conditional_t<preconditionable, BlockPreconditioner<SceneT>, NoPreconditioner>;

 public:
  SceneSystem(const SceneT& scene, ChartBases base, bool stabilize, bool with_preconditioner)
      : scene_(&scene),
        ws_(scene),
        base_(std::move(base)),
        switches_(static_cast<std::size_t>(scene.body_count()), 0) {
    ws_.stabilize_constraints = stabilize;
    if constexpr (preconditionable) {
      if (with_preconditioner) {
        preconditioner_.emplace(scene);
      }
    }
    if (!scene.events().empty()) {  // scratch for event actions, sized once
      event_state_.y.resize(scene.size());
      event_state_.base = base_;
    }
  }

  [[nodiscard]] int size() const { return scene_->size(); }

  void rhs(double t, ConstVectorMap y, VectorMap ydot) {
    try {
      tumble::rhs(*scene_, ws_, t, y, bases(), ydot);
    } catch (const NonFiniteError& e) {
      throw RecoverableError(e.what());
    }
  }

  [[nodiscard]] int root_count() const { return scene_->root_count(); }
  [[nodiscard]] std::vector<int> root_directions() const { return scene_->root_directions(); }
  void roots(double t, ConstVectorMap y, VectorMap g) {
    chart_roots(*scene_, y, g);
    const auto& events = scene_->events();
    if (!events.empty()) {
      const SceneStateView s(y.data(), y.size(), bases());
      int i = static_cast<int>(scene_->chart_bodies().size());
      for (const Event& ev : events) {
        g[i++] = ev.function(t, s);
      }
    }
  }
  bool on_root(double t, VectorMap y, std::span<const int> which) {
    bool changed = leave_charts(*scene_, y, std::span<Matrix3<double>>(base_), which.data(),
                                [this](int id) { ++switches_[id]; }) > 0;
    const auto& events = scene_->events();
    const std::size_t first = scene_->chart_bodies().size();
    for (std::size_t i = 0; i < events.size(); ++i) {
      if (which[first + i] != 0) {
        ++events_;
      }
      if (which[first + i] != 0 && events[i].action) {
        detail::apply_event_action(events[i], t, event_state_, y, base_);
        changed = true;
      }
    }
    if (changed) {
      recenter(y);
    }
    return changed;
  }

  /// J = df/dy by automatic differentiation, dense or band (a mechanism's: dense); only when
  /// every load of the scene can be differentiated, otherwise CVODE forms J by difference
  /// quotients.
  template <class Jac>
  requires(SceneT::differentiable &&
           (!SceneT::has_joints ||
            !std::is_same_v<Jac, BandMatrixMap>)) void jacobian(double t, ConstVectorMap y,
                                                                ConstVectorMap /*fy*/, Jac jac) {
    try {
      tumble::jacobian(*scene_, ws_, t, y, bases(), jac);
    } catch (const NonFiniteError& e) {
      throw RecoverableError(e.what());
    }
  }

  /// The block-Jacobi preconditioner for GMRES: one LU of I - gamma J_kk per body.
  bool precondition_setup(double t, ConstVectorMap y, ConstVectorMap /*fy*/, bool jacobian_ok,
                          double gamma) requires preconditionable {
    try {
      if (!preconditioner_) [[unlikely]] {
        preconditioner_.emplace(*scene_);
      }
      return preconditioner_->setup(*scene_, ws_, t, y, bases(), jacobian_ok, gamma);
    } catch (const NonFiniteError& e) {
      throw RecoverableError(e.what());
    }
  }
  void precondition_solve(double /*t*/, ConstVectorMap /*y*/, ConstVectorMap /*fy*/,
                          ConstVectorMap r, VectorMap z, double /*gamma*/, double /*delta*/,
                          int /*lr*/) requires preconditionable {
    try {
      preconditioner_->solve(r, z);
    } catch (const NonFiniteError& e) {
      throw RecoverableError(e.what());
    }
  }

  /// A mechanism's output state (CVODE's interpolation between steps) onto its constraints, as
  /// the steps are: what observers and state() see of a mechanism is on the joints.
  void project_output(Eigen::VectorXd& y) {
    if constexpr (SceneT::has_joints) {
      int iterations = 0;
      detail::project_constraints(
          *scene_, ws_, y, bases(), kJointProjectionTolerance, kJointProjectionIterations,
          [](int) { return true; }, iterations);
    }
  }

  /// The Euler parameters' projection, then a mechanism's (scene/assembly.hpp: Newton on the
  /// positions, the velocities exactly). The error estimate is projected too: for the
  /// quaternions of the generalized form (scene/projection.hpp) and onto the joints' tangent
  /// space (scene/assembly.hpp, project_error_estimate), without which BDF's step size collapsed
  /// on Andrews' mechanism below 1e-10.
  void project(double /*t*/, ConstVectorMap y, VectorMap corr, double /*eps*/, VectorMap err) {
    tumble::project(*scene_, y, corr, err);
    if constexpr (SceneT::has_joints) {
      Eigen::VectorXd& z = ws_.joints().y;
      z = y + corr;
      // Where the rows frozen as redundant no longer leave the others independent, they are
      // decided again at this trial state (scene/assembly.hpp); they stay so for the steps after
      // it, accepted or not: which rows are retained does not change the motion on the
      // constraints, only how well its reactions are conditioned.
      const ConstraintResidual r = project_mechanism(*scene_, ws_, z, bases());
      if (!(r.position <= kJointProjectionFailure)) {
        throw RecoverableError("the projection onto the joints' constraints did not converge "
                               "(max |C| = " +
                               format_double(r.position) + ")");
      }
      corr = z - y;
      if (err.size() > 0) {  // CvodeOptions::project_error: err's normal components removed
        project_error_estimate(*scene_, ws_, z, err);
      }
    }
  }

  /// A mechanism's redundant rows, frozen at the state y for the run (scene/assembly.hpp).
  template <class Y> void freeze_redundancy(const Y& y) {
    if constexpr (SceneT::has_joints) {
      detail::freeze_redundant_rows(*scene_, ws_, y, bases());
    }
  }
  /// The frozen rows (JointScratch::dependent), to restore after a restart that failed.
  [[nodiscard]] std::vector<char>& redundant_rows() { return ws_.joints().dependent; }

  /// Re-centers the charts of y (and base_) that are in their switch zone; true if any changed.
  template <class Y> bool recenter(Y&& y) {
    return recenter_charts(*scene_, y, std::span<Matrix3<double>>(base_),
                           [this](int id) { ++switches_[id]; }) > 0;
  }

  [[nodiscard]] const SceneT& scene() const { return *scene_; }
  [[nodiscard]] std::span<const Matrix3<double>> bases() const { return base_; }
  void set_bases(const ChartBases& base) { base_ = base; }
  [[nodiscard]] long switches(int id) const { return switches_[static_cast<std::size_t>(id)]; }
  [[nodiscard]] long events() const { return events_; }
  [[nodiscard]] long switches() const {
    long n = 0;
    for (const long s : switches_) {
      n += s;
    }
    return n;
  }

 private:
  const SceneT* scene_;
  SceneWorkspace<SceneT> ws_;
  std::optional<Preconditioner> preconditioner_;
  ChartBases base_;                 ///< the discrete part of the state
  CacheLineVector<long> switches_;  ///< per body; on lines of its own (written at switches)
  SceneState event_state_;          ///< what event actions see and change
  long events_ = 0;                 ///< user events located
};

}  // namespace detail

template <class SceneT> class SceneIntegrator {
 public:
  using Options = SceneIntegratorOptions;
  using Statistics = SceneStatistics;

  /// Integrate `scene` from t0 starting at the scene's initial state (Scene::add's InitialState).
  /// The scene must outlive the integrator; the integrator only reads it.
  SceneIntegrator(const SceneT& scene, double t0, SceneIntegratorOptions options = {})
      : SceneIntegrator(scene, t0, scene.initial_state(), std::move(options)) {}

  /// Integrate `scene` from (t0, s0): a state of this scene (its initial state, or one saved
  /// from an integrator of it or of a copy of it).
  SceneIntegrator(const SceneT& scene, double t0, const SceneState& s0,
                  SceneIntegratorOptions options = {})
      : options_(std::move(options)), cvode_(make(scene, t0, s0, options_)) {
    sync();
  }

  /// A scene must outlive its integrator: a temporary would not.
  SceneIntegrator(SceneT&&, double, SceneIntegratorOptions = {}) = delete;
  SceneIntegrator(SceneT&&, double, const SceneState&, SceneIntegratorOptions = {}) = delete;

  /// Integrates to t_out (>= time()). The state there is state(); save() keeps a copy.
  void advance(double t_out) {
    cvode_.advance(t_out);
    sync();
  }
  /// One internal step; returns the time reached.
  double step() {
    const double t = cvode_.step();
    sync();
    return t;
  }
  /// observer(t, state) at each output time (increasing, validated before integrating).
  template <class Times, class Observer> void integrate(const Times& times, Observer&& observer) {
    cvode_.integrate(times, [&](double t, ConstVectorMap) { observer(t, std::as_const(sync())); });
  }
  template <class Observer>
  void integrate(std::initializer_list<double> times, Observer&& observer) {
    cvode_.integrate(times, [&](double t, ConstVectorMap) { observer(t, std::as_const(sync())); });
  }

  /// The current state, the continuous vector and the chart bases: a view that every call that
  /// integrates changes. To keep a state, save() it.
  [[nodiscard]] const SceneState& state() const { return state_; }
  /// A copy of the current state, to keep (reset() restarts from it). save(into) copies into a
  /// state of this scene without allocating.
  [[nodiscard]] SceneState save() const { return state_; }
  void save(SceneState& into) const {
    into.y = state_.y;
    into.base = state_.base;
  }
  [[nodiscard]] double time() const { return cvode_.time(); }

  /// Restarts from the state s at time t: a saved state of this scene (it restarts at the
  /// attitude it was saved at, whatever charts were switched since), or one the user changed
  /// (charts in their switch zone are re-centered first).
  void reset(double t, const SceneState& s) {
    check_state(scene(), s, "reset");
    SceneSystem& sys = cvode_.system();
    const ChartBases old = state_.base;  // the bases in force, if the restart fails
    const std::vector<char> rows_old = sys.redundant_rows();  // and the frozen redundant rows
    try {
      Eigen::VectorXd y = s.y;
      sys.set_bases(s.base);
      sys.recenter(y);
      sys.freeze_redundancy(y);
      cvode_.reset(t, y);
    } catch (...) {
      sys.set_bases(old);
      sys.redundant_rows() = rows_old;
      throw;
    }
    sync();
  }

  [[nodiscard]] SceneStatistics statistics() const {
    SceneStatistics s;
    static_cast<CvodeStatistics&>(s) = cvode_.statistics();
    s.rejected_steps = s.error_test_failures + s.nonlinear_convergence_failures;
    s.chart_switches = cvode_.system().switches();
    s.events = cvode_.system().events();
    return s;
  }
  /// Chart switches of one body since construction.
  template <class Body> [[nodiscard]] long chart_switches(BodyId<Body> b) const {
    return cvode_.system().switches(scene().entry(b).id);
  }

  [[nodiscard]] const SceneT& scene() const { return cvode_.system().scene(); }
  [[nodiscard]] const SceneIntegratorOptions& options() const { return options_; }
  [[nodiscard]] Cvode<detail::SceneSystem<SceneT>>& cvode() { return cvode_; }

 private:
  using SceneSystem = detail::SceneSystem<SceneT>;

  static void check_state(const SceneT& scene, const SceneState& s, const char* who) {
    detail::check_scene_state(scene, s, std::string("tumble::SceneIntegrator::") + who);
  }

  static Cvode<SceneSystem> make(const SceneT& scene, double t0, const SceneState& s0,
                                 const SceneIntegratorOptions& options) {
    check_state(scene, s0, "SceneIntegrator");
    CvodeOptions cvode = options.cvode_options();
    const bool bdf = cvode.method == CvodeMethod::bdf;
    if constexpr (SceneT::has_joints) {
      if (!bdf) {
        throw std::invalid_argument(
            "tumble::SceneIntegrator: a mechanism (a scene with joints) needs method = "
            "CvodeMethod::bdf: its state is projected onto the constraints after every step, and "
            "CVODE projects only with BDF (or use the explicit OdeintIntegrator)");
      }
    }
    const bool project =
        bdf && ((options.project_quaternions && SceneT::has_constraints) || SceneT::has_joints);
    cvode.projection = project;
    if (cvode.linear_solver == CvodeLinearSolver::band && cvode.upper_bandwidth < 0 &&
        cvode.lower_bandwidth < 0) {
      cvode.upper_bandwidth = cvode.lower_bandwidth = scene.half_bandwidth();
    }
    const bool preconditioned = bdf && cvode.linear_solver == CvodeLinearSolver::gmres &&
                                cvode.preconditioning != CvodePreconditioning::none;
    SceneSystem system(scene, s0.base, !project && options.stabilize_quaternions, preconditioned);
    Eigen::VectorXd y = s0.y;
    system.recenter(y);
    system.freeze_redundancy(y);
    return Cvode<SceneSystem>(std::move(system), t0, y, std::move(cvode));
  }

  /// Copies the current state (CVODE's vector and the bases) into state_; no allocation.
  const SceneState& sync() {
    state_.y = cvode_.state();
    if constexpr (SceneT::has_joints) {
      cvode_.system().project_output(state_.y);
    }
    const auto b = cvode_.system().bases();
    state_.base.assign(b.begin(), b.end());
    return state_;
  }

  SceneIntegratorOptions options_;
  Cvode<SceneSystem> cvode_;
  SceneState state_;
};

}  // namespace tumble
