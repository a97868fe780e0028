#pragma once
// A scene for Python: what tumble.Scene records (bodies, loads, events) and the run-time
// interface of a compiled C++ Scene built from that record.
//
// The C++ Scene's type lists its body and load types at compile time. The module compiles, for
// each parameterization of TUMBLE_PYTHON_SCENE_PARAMETERIZATIONS (python/CMakeLists.txt), two
// scene types whose bodies are RigidBody<P, centroid | offset | fixed_point>:
//   - Loads<UniformGravity, PointForce, BodyMoment, SpringDamper, SpringDamperBetween>, every load
//     differentiable, so BDF gets the exact Jacobian;
//   - the same plus a Python callable (PythonLoad), which only double can evaluate: CVODE's
//     difference quotients, and the GIL taken at every call (slow).
// Python events are tumble::Event (std::function) in either, so they choose no type.
// tumble.Scene builds the C++ scene from its record when it is first needed, the type chosen by
// the bodies' parameterization and whether a Python load was added; adding to the record after
// that builds it again. Everything of a run (states, integrators) lives in the call, so a built
// scene is only read, from any number of threads.

#include <cstddef>
#include <memory>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include <Eigen/Core>
#include <nanobind/nanobind.h>

#include "body.hpp"
#include "tumble/force/coupling.hpp"
#include "tumble/force/gravity.hpp"
#include "tumble/force/point_force.hpp"
#include "tumble/force/spring_damper.hpp"
#include "tumble/scene/state.hpp"

namespace tumble::python {

/// A Python callable as a load: fn(t, position, rotation, velocity, omega) -> (force, moment),
/// force in inertial components at the reference point (N), moment about it in body components
/// (N m); position r_oc (m) and velocity (m/s) inertial, rotation R (body -> inertial), omega
/// (rad/s) body. Called with the GIL held (taken at every call when the GIL was released).
class PythonLoad {
 public:
  explicit PythonLoad(nanobind::object fn);
  template <ReferencePoint Ref>
  Wrench<double> operator()(double t, const BodyKinematics<double, Ref>& k) const {
    return call(t, k);
  }

 private:
  Wrench<double> call(double t, const KinematicsView<double>& k) const;
  // Shared, so that copies of the load need no GIL; the last owner takes the GIL to release it.
  std::shared_ptr<nanobind::object> fn_;
};

class CompiledScene;

/// A Python event (tumble.Scene.add_event): function(t, state) -> float, whose zero crossing in
/// `direction` (+1 rising, -1 falling, 0 both) calls action(t, state) -> new y or None (no
/// action: null). The state is a tumble.EventState (events.cpp). Called with the GIL held (taken
/// at every call); what the function raises is carried as a PythonLoadError (load_error.hpp),
/// which the integrators make the cause of an IntegrationError, and what the action raises as
/// one too, which they pass through unchanged (the Python exception itself reaches the caller).
class PythonEvent {
 public:
  /// function: callable; action: callable or None; direction in {-1, 0, 1} (checked by the
  /// caller). Needs the GIL.
  PythonEvent(nanobind::object function, int direction, nanobind::object action);
  [[nodiscard]] int direction() const { return direction_; }
  [[nodiscard]] bool has_action() const { return static_cast<bool>(action_); }
  /// g(t, state), finite, for the state of `scene`; any thread, without the GIL.
  [[nodiscard]] double value(double t, const SceneStateView& s, const CompiledScene& scene) const;
  /// Calls the action and puts the y it returned, if any, in s.y; any thread, without the GIL.
  /// \throws std::invalid_argument when the action returned no y of size() finite entries.
  void act(double t, SceneState& s, const CompiledScene& scene) const;

 private:
  // Shared, so that copies need no GIL (as PythonLoad's callable).
  std::shared_ptr<nanobind::object> function_, action_;
  int direction_ = 0;
};

/// One load of the record: on body a, or between a and b (SpringDamperBetween).
struct LoadRecord {
  std::variant<UniformGravity, PointForce, BodyMoment, SpringDamper, SpringDamperBetween,
               PythonLoad>
      load;
  int a = -1;
  int b = -1;
};

struct BodyRecord {
  std::shared_ptr<const Body> body;
  InitialState initial;
};

/// The integrator and its options, as Python names them.
struct RunOptions {
  std::string method = "auto";  ///< auto | fehlberg78 | dopri5 | cash_karp54 | bdf | adams
  double rtol = 1e-8;
  double atol = 1e-8;
  long max_steps = 0;
  double initial_step = 0.0;
  double max_step = 0.0;  ///< 0: no limit
};

/// What an integration reports: the shared statistics and, for the front door, its choices.
struct RunStatistics {
  std::string method;  ///< the method that ran last
  long steps = 0;
  long rejected_steps = 0;
  long rhs_evals = 0;
  long chart_switches = 0;
  long projections = 0;
  long events = 0;
  /// (method, from time s, why): the front door's decisions, or the one method asked for.
  std::vector<std::tuple<std::string, double, std::string>> choices;
};

/// The values kept at each output time, per body: position r_oc (3, inertial, m), the unit
/// quaternion of R (4, w >= 0), velocity (3, inertial, m/s), omega (3, body, rad/s).
inline constexpr int kRecordPerBody = 13;

/// A trajectory, flat and row-major: t (T), y (T x n), bases (T x B x 9), per body (T x B x 13),
/// energy (T).
struct RawTrajectory {
  std::vector<double> t, y, bases, bodies, energy;
  RunStatistics statistics;
};

/// An ensemble's results, flat: y (R x T x n), per body (R x T x B x 13), energy (R x T); a failed
/// run's rows are NaN and its message is in errors.
struct RawEnsemble {
  std::vector<double> y, bodies, energy;
  std::vector<std::pair<std::size_t, std::string>> errors;
  int threads = 0;
};

/// A compiled scene, built from a record (see the file comment).
class CompiledScene {
 public:
  virtual ~CompiledScene() = default;
  [[nodiscard]] virtual int size() const = 0;
  [[nodiscard]] virtual int body_count() const = 0;
  [[nodiscard]] virtual const SceneState& initial_state() const = 0;
  /// Where body `id`'s blocks start in y: {offset (r_oc or theta), rates (v or omega)}.
  [[nodiscard]] virtual std::pair<int, int> layout(int id) const = 0;

  // Observables of a state (scene/observables.hpp), SI units.
  [[nodiscard]] virtual double kinetic_energy(const SceneState& s) const = 0;
  [[nodiscard]] virtual double potential_energy(const SceneState& s) const = 0;
  [[nodiscard]] virtual Eigen::Vector3d linear_momentum(const SceneState& s) const = 0;
  [[nodiscard]] virtual Eigen::Vector3d angular_momentum(const SceneState& s) const = 0;
  [[nodiscard]] virtual double constraint_drift(const SceneState& s) const = 0;
  [[nodiscard]] virtual Eigen::Matrix3d rotation(int id, const SceneState& s) const = 0;
  [[nodiscard]] virtual Eigen::Vector3d omega(int id, const SceneState& s) const = 0;
  [[nodiscard]] virtual Eigen::Vector3d position(int id, const SceneState& s) const = 0;
  [[nodiscard]] virtual Eigen::Vector3d velocity(int id, const SceneState& s) const = 0;
  [[nodiscard]] virtual Eigen::Vector3d reaction_force(int id, const SceneState& s,
                                                       double t) const = 0;
  /// Appends, per body, kRecordPerBody values (as RawTrajectory's bodies) of the state.
  virtual void record(const SceneStateView& s, std::vector<double>& out) const = 0;
  /// y' = f(t, y) (scene/rhs.hpp).
  [[nodiscard]] virtual Eigen::VectorXd rhs(double t, const SceneState& s) const = 0;

  /// Integrates from (t0, s0) through `times`. Call without the GIL.
  [[nodiscard]] virtual RawTrajectory integrate(double t0, const SceneState& s0,
                                                const std::vector<double>& times,
                                                const RunOptions& options) const = 0;
  /// Runs `runs` integrations from t0, run i from y0[i * n, (i + 1) * n) with the initial chart
  /// bases, on at most `threads` threads (0: TBB's choice). Call without the GIL.
  [[nodiscard]] virtual RawEnsemble ensemble(double t0, const std::vector<double>& y0,
                                             std::size_t runs, const std::vector<double>& times,
                                             const RunOptions& options, int threads) const = 0;
};

/// The compiled scene for the record: \throws std::invalid_argument when the bodies'
/// parameterization has no compiled scene (the message lists those that have) or the C++ scene
/// rejects a body or a load. The events do not choose the type (they are std::function in any
/// C++ scene).
std::unique_ptr<CompiledScene> build_scene(const std::vector<BodyRecord>& bodies,
                                           const std::vector<LoadRecord>& loads,
                                           const std::vector<PythonEvent>& events);

/// The parameterizations with compiled scenes (scene_registry.cpp, generated).
std::vector<std::string> scene_parameterizations();

}  // namespace tumble::python
