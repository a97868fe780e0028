#pragma once
// SceneIntegrator: a Scene (scene/scene.hpp) integrated in time by CVODE (integrate/cvode.hpp).
//
// It adapts the scene to CVODE's system interface and sets up what the scene's coordinates need:
// - Euler parameters: with BDF, CVODE's projection onto |p| = 1, p.pdot = 0 after every step
//   (CVodeSetProjFn; CVODE supports projection only with BDF); with Adams, the scene's
//   Baumgarte-stabilized constraint acceleration instead.
// - Three-parameter sets: one root function per body watches the distance to the chart's
//   singularity; at a root the chart is re-centered (MRP: shadow set) and CVODE restarts.
// - User events: the scene's root functions and actions, with a restart when the state changes.
// - BDF's Newton iteration gets the exact Jacobian df/dy (dense or band) by automatic
//   differentiation (Scene::jacobian) when every load can be differentiated; otherwise, or with
//   CvodeOptions::use_system_jacobian = false, CVODE forms it by difference quotients. With
//   GMRES the same blocks give a block-Jacobi preconditioner, one LU of I - gamma J_kk per body
//   (CvodeOptions::preconditioning: left by default, or right, or none).
// A NonFiniteError met in the right-hand side becomes a recoverable error: CVODE retries with a
// smaller step, and reports an IntegrationError if it cannot recover.

#include <span>
#include <utility>

#include "tumble/core/errors.hpp"
#include "tumble/integrate/cvode.hpp"
#include "tumble/integrate/errors.hpp"
#include "tumble/scene/scene.hpp"

namespace tumble {

/// Options of a SceneIntegrator: CVODE's, plus how Euler parameters keep their norm.
struct SceneIntegratorOptions {
  /// CVODE's options. With CvodeLinearSolver::band and the bandwidths left at -1, the scene's
  /// own half-bandwidth is used (Scene::half_bandwidth).
  CvodeOptions cvode{};
  /// With BDF: project Euler parameters onto their constraint after each step. With Adams the
  /// scene's Baumgarte stabilization is used (CVODE cannot project with Adams).
  bool project_quaternions = true;
};

/// CVODE's counters plus the scene's chart switches.
struct SceneStatistics : CvodeStatistics {
  long chart_switches = 0;  ///< re-centerings and MRP shadow switches since construction
};

namespace detail {

/// The scene as a CVODE system (see CvodeSystem and its optional members).
template <class SceneT> class SceneSystem {
 public:
  explicit SceneSystem(SceneT& scene) : scene_(&scene) {}

  [[nodiscard]] int size() const { return scene_->size(); }

  void rhs(double t, ConstVectorMap y, VectorMap ydot) {
    try {
      scene_->rhs(t, y, ydot);
    } catch (const NonFiniteError& e) {
      throw RecoverableError(e.what());
    }
  }

  [[nodiscard]] int root_count() const { return scene_->root_count(); }
  [[nodiscard]] const std::vector<int>& root_directions() const {
    return scene_->root_directions();
  }
  void roots(double t, ConstVectorMap y, VectorMap g) { scene_->roots(t, y, g); }
  bool on_root(double t, VectorMap y, std::span<const int> which) {
    return scene_->on_root(t, y, which.data());
  }

  /// J = df/dy by automatic differentiation (Scene::jacobian), dense or band; only when every
  /// load of the scene can be differentiated (Scene::differentiable), otherwise CVODE forms J by
  /// difference quotients.
  template <class Jac>
  requires SceneT::differentiable void jacobian(double t, ConstVectorMap y, ConstVectorMap /*fy*/,
                                                Jac jac) {
    try {
      scene_->jacobian(t, y, jac);
    } catch (const NonFiniteError& e) {
      throw RecoverableError(e.what());
    }
  }

  /// Block-Jacobi preconditioner for GMRES (Scene::precondition_setup/solve): one LU of
  /// I - gamma J_kk per body. Only for differentiable scenes (it needs the exact blocks).
  bool precondition_setup(double t, ConstVectorMap y, ConstVectorMap /*fy*/, bool jacobian_ok,
                          double gamma) requires SceneT::differentiable {
    try {
      return scene_->precondition_setup(t, y, jacobian_ok, gamma);
    } catch (const NonFiniteError& e) {
      throw RecoverableError(e.what());
    }
  }
  void precondition_solve(double /*t*/, ConstVectorMap /*y*/, ConstVectorMap /*fy*/,
                          ConstVectorMap r, VectorMap z, double /*gamma*/, double /*delta*/,
                          int /*lr*/) requires SceneT::differentiable {
    try {
      scene_->precondition_solve(r, z);
    } catch (const NonFiniteError& e) {
      throw RecoverableError(e.what());
    }
  }

  void project(double /*t*/, ConstVectorMap y, VectorMap corr, double /*eps*/, VectorMap err) {
    scene_->project(y, corr, err);
  }

 private:
  SceneT* scene_;
};

}  // namespace detail

template <class SceneT> class SceneIntegrator {
 public:
  /// Integrate `scene` from t0 starting at the scene's initial state (Scene::add's InitialState).
  /// The scene must outlive the integrator and must not gain bodies or loads while it is used.
  SceneIntegrator(SceneT& scene, double t0, SceneIntegratorOptions options = {})
      : SceneIntegrator(scene, t0, scene.initial_state(), std::move(options)) {}

  /// Integrate `scene` from (t0, y0).
  SceneIntegrator(SceneT& scene, double t0, const Eigen::Ref<const Eigen::VectorXd>& y0,
                  SceneIntegratorOptions options = {})
      : scene_(&scene),
        cvode_(make(scene, t0, y0, options)),
        switches_at_start_(scene.chart_switches()) {}

  /// Integrate to t_out and return the state there.
  ConstVectorMap advance(double t_out) { return cvode_.advance(t_out); }
  /// One internal step; returns the time reached.
  double step() { return cvode_.step(); }
  /// observer(t, y) at each output time.
  template <class Times, class Observer> void integrate(const Times& times, Observer&& observer) {
    cvode_.integrate(times, std::forward<Observer>(observer));
  }
  template <class Observer>
  void integrate(std::initializer_list<double> times, Observer&& observer) {
    cvode_.integrate(times, std::forward<Observer>(observer));
  }

  [[nodiscard]] ConstVectorMap state() const { return cvode_.state(); }
  [[nodiscard]] double time() const { return cvode_.time(); }

  /// Restart from a state the user changed (charts near their singularity are re-centered
  /// first).
  void reset(double t, const Eigen::Ref<const Eigen::VectorXd>& y) {
    Eigen::VectorXd y1 = y;
    scene_->recenter_charts(y1);
    cvode_.reset(t, y1);
  }

  [[nodiscard]] SceneStatistics statistics() const {
    SceneStatistics s;
    static_cast<CvodeStatistics&>(s) = cvode_.statistics();
    s.chart_switches = scene_->chart_switches() - switches_at_start_;
    return s;
  }

  [[nodiscard]] SceneT& scene() { return *scene_; }
  [[nodiscard]] const SceneT& scene() const { return *scene_; }
  [[nodiscard]] Cvode<detail::SceneSystem<SceneT>>& cvode() { return cvode_; }

 private:
  static Cvode<detail::SceneSystem<SceneT>> make(SceneT& scene, double t0,
                                                 const Eigen::Ref<const Eigen::VectorXd>& y0,
                                                 SceneIntegratorOptions options) {
    scene.prepare();
    if (y0.size() != scene.size()) {
      throw std::invalid_argument("tumble::SceneIntegrator: the state has size " +
                                  std::to_string(y0.size()) + " but the scene has size " +
                                  std::to_string(scene.size()));
    }
    Eigen::VectorXd y = y0;
    scene.recenter_charts(y);
    const bool bdf = options.cvode.method == CvodeMethod::bdf;
    const bool project = bdf && options.project_quaternions && SceneT::has_constraints();
    options.cvode.projection = project;
    if (options.cvode.linear_solver == CvodeLinearSolver::band &&
        options.cvode.upper_bandwidth < 0 && options.cvode.lower_bandwidth < 0) {
      options.cvode.upper_bandwidth = options.cvode.lower_bandwidth = scene.half_bandwidth();
    }
    scene.set_constraint_stabilization(!project);
    if constexpr (SceneT::differentiable) {
      if (options.cvode.method == CvodeMethod::bdf &&
          options.cvode.linear_solver == CvodeLinearSolver::gmres &&
          options.cvode.preconditioning != CvodePreconditioning::none) {
        scene.prepare_preconditioner();
      }
    }
    return Cvode<detail::SceneSystem<SceneT>>(detail::SceneSystem<SceneT>(scene), t0, y,
                                              std::move(options.cvode));
  }

  SceneT* scene_;
  Cvode<detail::SceneSystem<SceneT>> cvode_;
  long switches_at_start_;
};

}  // namespace tumble
