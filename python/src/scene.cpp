// Python bindings of scenes: tumble.Scene (a record of bodies, loads and events, built into a
// compiled C++ scene when first needed; scene_api.hpp), tumble.State, tumble.Trajectory,
// tumble.EnsembleResult, tumble.Statistics, and the Python load (the Python events: events.cpp).

#include <cmath>
#include <cstddef>
#include <initializer_list>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include <nanobind/eigen/dense.h>
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/pair.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/tuple.h>
#include <nanobind/stl/vector.h>

#include "bindings.hpp"
#include "convert.hpp"
#include "handles.hpp"
#include "load_error.hpp"
#include "scene_api.hpp"

namespace tumble::python {

using namespace nb::literals;
using OutArray = nb::ndarray<nb::numpy, double>;

// --- the Python load -------------------------------------------------------------------------

PythonLoad::PythonLoad(nb::object fn)
    : fn_(new nb::object(std::move(fn)), [](nb::object* o) {
        const nb::gil_scoped_acquire gil;
        delete o;
      }) {}

Wrench<double> PythonLoad::call(double t, const KinematicsView<double>& k) const {
  const nb::gil_scoped_acquire gil;
  try {
    const nb::object r = (*fn_)(t, Eigen::Vector3d(k.position), Eigen::Matrix3d(k.rotation),
                                Eigen::Vector3d(k.velocity), Eigen::Vector3d(k.omega));
    if (!nb::isinstance<nb::sequence>(r) || nb::len(r) != 2) {
      throw std::invalid_argument("tumble: a user load must return (force, moment), two 3-vectors");
    }
    return Wrench<double>{vector3(r[0], "user load force"), vector3(r[1], "user load moment")};
  } catch (const nb::python_error& e) {
    // Carried through C++ as "tumble: the user load raised TypeName: message" (no traceback),
    // with the exception object for the IntegrationError's __cause__ (load_error.hpp).
    const std::string type = nb::cast<std::string>(nb::handle(e.type()).attr("__name__"));
    throw PythonLoadError(
        "tumble: the user load raised " + type + ": " + nb::cast<std::string>(nb::str(e.value())),
        e.value());
  }
}

namespace {

// --- NumPy arrays of results -----------------------------------------------------------------

/// The vector as a NumPy array of `shape`, owning its data (no copy).
OutArray numpy(std::vector<double>&& v, std::initializer_list<std::size_t> shape) {
  auto* data = new std::vector<double>(std::move(v));
  nb::capsule owner(data, [](void* p) noexcept { delete static_cast<std::vector<double>*>(p); });
  return OutArray(data->data(), shape.size(), shape.begin(), owner);
}

// --- results ---------------------------------------------------------------------------------

/// tumble.Trajectory: the arrays; a whole state (state(k)) is assembled from y and bases when
/// asked for, not kept per output time (two heap blocks and copies each: the tumbling body's
/// integration from Python took 148 us without them, 165 us with, docs/benchmarks/python.md).
struct PyTrajectory {
  OutArray t, y, bases, position, quaternion, velocity, omega, energy;
  RunStatistics statistics;
};

struct PyEnsemble {
  OutArray t, y, position, quaternion, velocity, omega, energy;
  std::vector<std::pair<std::size_t, std::string>> errors;
  int threads = 0;
};

/// Splits the per-body records (N x B x 13, flat) into position, quaternion, velocity, omega.
void split_bodies(const std::vector<double>& flat, std::size_t rows, std::size_t bodies,
                  std::vector<std::size_t> lead, OutArray& position, OutArray& quaternion,
                  OutArray& velocity, OutArray& omega) {
  std::vector<double> p, q, v, w;
  p.reserve(rows * bodies * 3);
  q.reserve(rows * bodies * 4);
  v.reserve(rows * bodies * 3);
  w.reserve(rows * bodies * 3);
  for (std::size_t i = 0; i < rows * bodies; ++i) {
    const double* r = flat.data() + i * kRecordPerBody;
    p.insert(p.end(), r, r + 3);
    q.insert(q.end(), r + 3, r + 7);
    v.insert(v.end(), r + 7, r + 10);
    w.insert(w.end(), r + 10, r + 13);
  }
  const auto shape = [&](std::size_t last) {
    std::vector<std::size_t> s = lead;
    s.push_back(bodies);
    s.push_back(last);
    return s;
  };
  const auto make = [](std::vector<double>&& d, const std::vector<std::size_t>& s) {
    auto* data = new std::vector<double>(std::move(d));
    nb::capsule owner(data, [](void* x) noexcept { delete static_cast<std::vector<double>*>(x); });
    return OutArray(data->data(), s.size(), s.data(), owner);
  };
  position = make(std::move(p), shape(3));
  quaternion = make(std::move(q), shape(4));
  velocity = make(std::move(v), shape(3));
  omega = make(std::move(w), shape(3));
}

// --- Scene -----------------------------------------------------------------------------------

class PyScene {
 public:
  /// Marks the scene as integrating while it lives (taken and dropped with the GIL held): the
  /// record cannot change then, since that would free the compiled scene under the run (from
  /// a Python load or event of the run, or from another thread).
  class Running {
   public:
    explicit Running(const PyScene& s) : s_(s) { ++s_.running_; }
    ~Running() { --s_.running_; }
    Running(const Running&) = delete;
    Running& operator=(const Running&) = delete;

   private:
    const PyScene& s_;
  };

  int add(const BodyHandle& body, nb::handle position, nb::handle rotation, nb::handle velocity,
          nb::handle omega) {
    check_not_running("add");
    if (!bodies_.empty() &&
        body.body->parameterization().name() != bodies_.front().body->parameterization().name()) {
      throw std::invalid_argument(
          "tumble.Scene.add: the bodies of one scene share one parameterization (this scene's "
          "is " +
          std::string(bodies_.front().body->parameterization().name()) + ", the body's " +
          std::string(body.body->parameterization().name()) + ")");
    }
    InitialState s;
    s.position =
        body.body->reference() == ReferencePoint::fixed_point && position.is_none()
            ? body.body->fixed_point()
            : (position.is_none() ? Eigen::Vector3d::Zero() : vector3(position, "position"));
    s.rotation = rotation.is_none() ? Eigen::Matrix3d::Identity() : matrix3(rotation, "rotation");
    s.velocity = velocity.is_none() ? Eigen::Vector3d::Zero() : vector3(velocity, "velocity");
    s.omega = omega.is_none() ? Eigen::Vector3d::Zero() : vector3(omega, "omega");
    bodies_.push_back({body.body, s});
    try {
      compiled_.reset();
      (void)compiled();  // the C++ scene checks the initial state now, not at the first run
    } catch (...) {
      bodies_.pop_back();
      compiled_.reset();
      throw;
    }
    return static_cast<int>(bodies_.size()) - 1;
  }

  void add_load(LoadRecord load) {
    check_not_running("add a load");
    check_body(load.a, "body");
    if (load.b >= 0 || std::holds_alternative<SpringDamperBetween>(load.load)) {
      check_body(load.b, "other body");
    }
    loads_.push_back(std::move(load));
    compiled_.reset();
  }

  void add_user_load(int body, nb::handle fn) {
    add_load({PythonLoad(nb::borrow<nb::object>(fn)), body, -1});
    owned_.push_back(fn.ptr());
  }

  void add_event(nb::handle function, int direction, nb::handle action) {
    check_not_running("add_event");
    if (!PyCallable_Check(function.ptr())) {
      throw std::invalid_argument(
          "tumble.Scene.add_event: 'function' must be callable as function(t, state) -> float, "
          "got " +
          std::string(Py_TYPE(function.ptr())->tp_name));
    }
    if (direction < -1 || direction > 1) {
      throw std::invalid_argument("tumble.Scene.add_event: 'direction' must be +1 (rising), -1 "
                                  "(falling) or 0 (both), got " +
                                  std::to_string(direction));
    }
    if (!action.is_none() && !PyCallable_Check(action.ptr())) {
      throw std::invalid_argument(
          "tumble.Scene.add_event: 'action' must be None or callable as action(t, state) -> y "
          "or None, got " +
          std::string(Py_TYPE(action.ptr())->tp_name));
    }
    events_.emplace_back(nb::borrow<nb::object>(function), direction,
                         nb::borrow<nb::object>(action));
    owned_.push_back(function.ptr());
    if (!action.is_none()) {
      owned_.push_back(action.ptr());
    }
    compiled_.reset();
  }

  /// For Python's cycle collector (a load or an event that refers to its scene, as a closure
  /// over it does, makes a cycle through C++ it cannot see otherwise): the Python objects the
  /// record holds, one reference each (the compiled scene's copies share them).
  int traverse(visitproc visit, void* arg) const {
    for (PyObject* o : owned_) {
      Py_VISIT(o);
    }
    return 0;
  }
  /// Drops them (the cycle collector breaking a cycle): the Python loads and the events go.
  void clear() {
    compiled_.reset();
    events_.clear();
    std::erase_if(loads_,
                  [](const LoadRecord& l) { return std::holds_alternative<PythonLoad>(l.load); });
    owned_.clear();
  }

  const CompiledScene& compiled() const {
    if (bodies_.empty()) {
      throw std::invalid_argument("tumble.Scene: the scene has no body yet (Scene.add)");
    }
    if (!compiled_) {
      compiled_ = build_scene(bodies_, loads_, events_);
    }
    return *compiled_;
  }

  void check_not_running(const char* what) const {
    if (running_ > 0) {
      throw std::invalid_argument(std::string("tumble.Scene.") + what +
                                  ": the scene cannot change while it integrates (from one of "
                                  "its callbacks, or another thread)");
    }
  }

  void check_body(int id, const char* what) const {
    if (id < 0 || id >= static_cast<int>(bodies_.size())) {
      throw std::invalid_argument(std::string("tumble.Scene: ") + what + " " + std::to_string(id) +
                                  " is not a body of this scene (it has " +
                                  std::to_string(bodies_.size()) + ")");
    }
  }

  /// The state for y (n) with the initial chart bases, or a State itself.
  SceneState state(nb::handle s) const {
    const CompiledScene& c = compiled();
    if (PyState* st = nullptr; nb::try_cast(s, st) && st != nullptr) {
      if (st->state.y.size() != c.size() ||
          st->state.base.size() != c.initial_state().base.size()) {
        throw std::invalid_argument("tumble.Scene: the state has " +
                                    std::to_string(st->state.y.size()) +
                                    " entries; this scene's have " + std::to_string(c.size()));
      }
      return st->state;
    }
    SceneState r = c.initial_state();
    r.y = vector(s, c.size(), "state");
    return r;
  }

  const std::vector<BodyRecord>& bodies() const { return bodies_; }

 private:
  std::vector<BodyRecord> bodies_;
  std::vector<LoadRecord> loads_;
  std::vector<PythonEvent> events_;
  std::vector<PyObject*> owned_;  // the Python objects of loads_ and events_ (see traverse)
  mutable std::unique_ptr<CompiledScene> compiled_;  // a cache of the record, rebuilt on change
  mutable int running_ = 0;  // integrations under way (Running), changed with the GIL held
};

RunOptions run_options(const std::string& method, double rtol, double atol, long max_steps,
                       double initial_step, double max_step) {
  return RunOptions{method, rtol, atol, max_steps, initial_step, max_step};
}

std::vector<double> output_times(nb::handle times) {
  const InArray a = as_array(times, "times");
  if (a.ndim() != 1 || a.shape(0) == 0) {
    throw std::invalid_argument("tumble: 'times' must be a non-empty 1-d array of output times "
                                "(s), got shape " +
                                shape_of(a));
  }
  check_finite(a.data(), a.size(), "times");
  return {a.data(), a.data() + a.size()};
}

PyTrajectory trajectory(const PyScene& scene, RawTrajectory&& raw, std::size_t n) {
  const std::size_t rows = raw.t.size();
  const std::size_t b = scene.bodies().size();
  PyTrajectory out;
  split_bodies(raw.bodies, rows, b, {rows}, out.position, out.quaternion, out.velocity, out.omega);
  out.t = numpy(std::move(raw.t), {rows});
  out.y = numpy(std::move(raw.y), {rows, n});
  out.bases = numpy(std::move(raw.bases), {rows, b, 3, 3});
  out.energy = numpy(std::move(raw.energy), {rows});
  out.statistics = std::move(raw.statistics);
  return out;
}

constexpr const char* kIntegrateDoc =
    "Integrates the scene from (t0, state) and returns a Trajectory at the output times `times` "
    "(s, non-decreasing, not before t0). state: None (the initial state), a State, or y "
    "(size()). method: 'auto' (tumble::integrate, the front door: it chooses Fehlberg 7(8), "
    "Dormand-Prince 5(4) or BDF and says why in statistics.choices), 'fehlberg78', 'dopri5', "
    "'cash_karp54' (OdeintIntegrator), 'bdf', 'adams' (SceneIntegrator, CVODE). rtol, atol: the "
    "tolerances; max_steps: step attempts per output interval (0: no limit); initial_step (0: "
    "estimated), max_step (0: no limit), s. The GIL is released while C++ integrates. Raises "
    "ValueError for bad input, tumble.IntegrationError when the integration cannot go on.";

constexpr const char* kEnsembleDoc =
    "Runs one integration per row of `initial` (runs x size(): y vectors, with the scene's "
    "initial chart bases) from t0 to the output times `times`, on at most `threads` threads "
    "(0: oneTBB's choice), with the GIL released. Returns an EnsembleResult: arrays "
    "(runs x times x ...), NaN for the rows of a run that failed, whose (run, message) is in "
    "errors; the other runs keep their results (tumble::Ensemble). The same results on any "
    "number of threads, to the bit. Options as for integrate().";

constexpr const char* kAddEventDoc =
    "Adds an event (tumble::Event): function(t, state) -> float, whose zero crossing in "
    "`direction` (+1 rising, -1 falling, 0 both) calls action(t, state), which returns a new y "
    "(size(), finite) or None (no change; action=None: none is called). state is a read-only "
    "EventState (y, bases, and per body position, quaternion, velocity, omega; Scene's "
    "observables take it). Every method locates the crossing between two steps (CVODE's "
    "root finding; Illinois on the explicit step, to 1e-12 of the time scale), applies the "
    "action there, re-centers the charts and evaluates the derivative again (the explicit "
    "methods cut the step at the first crossing and find the others from there); "
    "statistics.events counts the crossings, with or without an action; their times are not "
    "recorded (keep t in the action). A step over two crossings of one function sees no sign "
    "change: bound the steps with max_step where that can happen. With events, method='auto' "
    "stays on Fehlberg 7(8) (no hand-over to Dormand-Prince's dense outputs). SLOW: Python is "
    "called (taking the GIL) at every step and more while a crossing is located; the runs of "
    "an ensemble take turns for it. What "
    "the function raises stops the integration with tumble.IntegrationError (reason "
    "'callback', the exception its __cause__), as a Python load's does; what the action "
    "raises reaches the caller itself, unchanged, as tumble::Event's actions do (an ensemble "
    "records its message as the run's error). ValueError for a function that is not callable, "
    "a direction not in {-1, 0, 1}, an action that is neither None nor callable, or that "
    "returns no y of size() finite entries.";

int scene_traverse(PyObject* self, visitproc visit, void* arg) {
  if (nb::inst_ready(self)) {
    if (const int r = nb::inst_ptr<PyScene>(self)->traverse(visit, arg); r != 0) {
      return r;
    }
  }
  Py_VISIT(Py_TYPE(self));
  return 0;
}

int scene_clear(PyObject* self) {
  if (nb::inst_ready(self)) {
    nb::inst_ptr<PyScene>(self)->clear();
  }
  return 0;
}

PyType_Slot kSceneSlots[] = {{Py_tp_traverse, reinterpret_cast<void*>(scene_traverse)},
                             {Py_tp_clear, reinterpret_cast<void*>(scene_clear)},
                             {0, nullptr}};

/// A getter of an array member: the array itself (it owns its data through a capsule), which
/// def_ro's reference_internal policy does not allow.
template <class C> auto array_of(OutArray C::*member) {
  return [member](const C& c) { return c.*member; };
}

}  // namespace

void bind_scene(nb::module_& m) {
  nb::class_<RunStatistics>(m, "Statistics",
                            "What an integration did: steps, rejected_steps, rhs_evals, "
                            "chart_switches, projections, events, the method that ran last, "
                            "and choices: (method, from time s, why) for each decision.")
      .def_ro("method", &RunStatistics::method)
      .def_ro("steps", &RunStatistics::steps)
      .def_ro("rejected_steps", &RunStatistics::rejected_steps)
      .def_ro("rhs_evals", &RunStatistics::rhs_evals)
      .def_ro("chart_switches", &RunStatistics::chart_switches)
      .def_ro("projections", &RunStatistics::projections)
      .def_ro("events", &RunStatistics::events)
      .def_ro("choices", &RunStatistics::choices)
      .def("__repr__", [](const RunStatistics& s) {
        return "tumble.Statistics(method='" + s.method + "', steps=" + std::to_string(s.steps) +
               ", rhs_evals=" + std::to_string(s.rhs_evals) +
               ", chart_switches=" + std::to_string(s.chart_switches) + ")";
      });

  nb::class_<PyState>(m, "State",
                      "A whole state of a scene: y, the integrated vector (per body [r_oc; "
                      "theta; v; omega], or [theta; omega] for a body held at a fixed point), "
                      "and the chart base of every body (bases, B x 3 x 3: R = base R(theta)), "
                      "so that a saved state always means the same attitude.")
      .def(nb::init<>())
      .def_prop_ro(
          "y", [](const PyState& s) { return Eigen::VectorXd(s.state.y); }, nb::rv_policy::move)
      .def_prop_ro(
          "bases",
          [](const PyState& s) {
            std::vector<double> b;
            for (const Eigen::Matrix3d& m3 : s.state.base) {
              for (int i = 0; i < 3; ++i) {
                for (int j = 0; j < 3; ++j) {
                  b.push_back(m3(i, j));
                }
              }
            }
            const std::size_t count = s.state.base.size();
            return numpy(std::move(b), {count, 3, 3});
          },
          nb::rv_policy::move);

  nb::class_<PyTrajectory>(m, "Trajectory",
                           "The results of Scene.integrate at its output times (T of them), "
                           "for B bodies: t (T, s), y (T x size()), bases (T x B x 3 x 3), "
                           "position (T x B x 3, r_oc inertial, m), quaternion (T x B x 4, of R, "
                           "(w, x, y, z), w >= 0), velocity (T x B x 3, inertial, m/s), omega "
                           "(T x B x 3, body, rad/s), energy (T, J), statistics; state(k) is "
                           "the whole state at output k (to restart from).")
      .def_prop_ro("t", array_of(&PyTrajectory::t), nb::rv_policy::move)
      .def_prop_ro("y", array_of(&PyTrajectory::y), nb::rv_policy::move)
      .def_prop_ro("bases", array_of(&PyTrajectory::bases), nb::rv_policy::move)
      .def_prop_ro("position", array_of(&PyTrajectory::position), nb::rv_policy::move)
      .def_prop_ro("quaternion", array_of(&PyTrajectory::quaternion), nb::rv_policy::move)
      .def_prop_ro("velocity", array_of(&PyTrajectory::velocity), nb::rv_policy::move)
      .def_prop_ro("omega", array_of(&PyTrajectory::omega), nb::rv_policy::move)
      .def_prop_ro("energy", array_of(&PyTrajectory::energy), nb::rv_policy::move)
      .def_ro("statistics", &PyTrajectory::statistics)
      .def(
          "state",
          [](const PyTrajectory& t, long k) {
            const long n = static_cast<long>(t.t.shape(0));
            if (k < -n || k >= n) {
              throw std::invalid_argument("tumble.Trajectory.state: output " + std::to_string(k) +
                                          " of " + std::to_string(n));
            }
            const auto row = static_cast<std::size_t>(k < 0 ? k + n : k);
            const std::size_t size = t.y.shape(1), bodies = t.bases.shape(1);
            PyState s;
            s.state.y = Eigen::Map<const Eigen::VectorXd>(t.y.data() + row * size,
                                                          static_cast<Eigen::Index>(size));
            using RowMajor3 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;
            for (std::size_t i = 0; i < bodies; ++i) {  // bases: row-major, as NumPy prints them
              s.state.base.emplace_back(
                  Eigen::Map<const RowMajor3>(t.bases.data() + (row * bodies + i) * 9));
            }
            return s;
          },
          "k"_a, "The whole state at output k (negative: from the end).")
      .def("__len__", [](const PyTrajectory& t) { return t.t.shape(0); });

  nb::class_<PyEnsemble>(m, "EnsembleResult",
                         "The results of Scene.ensemble for R runs, T output times, B bodies: t "
                         "(T), y (R x T x size()), position, quaternion, velocity, omega "
                         "(R x T x B x 3 or 4, as in Trajectory), energy (R x T); a failed run's "
                         "rows are NaN and errors lists (run, message); threads: the threads "
                         "the runs were spread over.")
      .def_prop_ro("t", array_of(&PyEnsemble::t), nb::rv_policy::move)
      .def_prop_ro("y", array_of(&PyEnsemble::y), nb::rv_policy::move)
      .def_prop_ro("position", array_of(&PyEnsemble::position), nb::rv_policy::move)
      .def_prop_ro("quaternion", array_of(&PyEnsemble::quaternion), nb::rv_policy::move)
      .def_prop_ro("velocity", array_of(&PyEnsemble::velocity), nb::rv_policy::move)
      .def_prop_ro("omega", array_of(&PyEnsemble::omega), nb::rv_policy::move)
      .def_prop_ro("energy", array_of(&PyEnsemble::energy), nb::rv_policy::move)
      .def_ro("errors", &PyEnsemble::errors)
      .def_ro("threads", &PyEnsemble::threads);

  nb::class_<PyScene>(
      m, "Scene",
      "A scene: bodies of one parameterization (each framed at its centroid, at an offset, or "
      "held at a fixed point) and the loads on them; one state, one right-hand side. Bodies are "
      "numbered from 0 in the order of add(). Built into a compiled C++ scene when first "
      "needed (the parameterizations with compiled scenes: tumble.scene_parameterizations()).",
      nb::type_slots(kSceneSlots))
      .def(nb::init<>())
      .def("add", &PyScene::add, "body"_a, "position"_a = nb::none(), "rotation"_a = nb::none(),
           "velocity"_a = nb::none(), "omega"_a = nb::none(),
           "Adds a body with its initial state: position r_oc (inertial, m; a body held at a "
           "fixed point is at its fixed point), rotation R (body -> inertial), velocity "
           "(inertial, m/s), omega (body, rad/s). Returns the body's index.")
      .def(
          "add_gravity",
          [](PyScene& s, int body, nb::handle g) {
            s.add_load({UniformGravity(vector3(g, "g")), body, -1});
          },
          "body"_a, "g"_a = nb::make_tuple(0.0, 0.0, -9.81),
          "Uniform gravity g (inertial, m/s^2) on the body, at its centroid.")
      .def(
          "add_point_force",
          [](PyScene& s, int body, nb::handle point, nb::handle force,
             const std::string& components) {
            if (components != "inertial" && components != "body") {
              throw std::invalid_argument(
                  "tumble.Scene.add_point_force: components must be 'inertial' or 'body'");
            }
            s.add_load({PointForce(vector3(point, "point"), vector3(force, "force"),
                                   components == "body" ? Components::body : Components::inertial),
                        body, -1});
          },
          "body"_a, "point"_a, "force"_a, "components"_a = "inertial",
          "A constant force (N, in `components`: 'inertial' or 'body') at the body point "
          "`point` (m, body components, from the reference point).")
      .def(
          "add_moment",
          [](PyScene& s, int body, nb::handle moment) {
            s.add_load({BodyMoment(vector3(moment, "moment")), body, -1});
          },
          "body"_a, "moment"_a, "A constant moment (N m, body components).")
      .def(
          "add_spring",
          [](PyScene& s, int body, nb::handle point, nb::handle anchor, double stiffness,
             double damping, double rest_length) {
            s.add_load({SpringDamper(vector3(point, "point"), vector3(anchor, "anchor"),
                                     {stiffness, damping, rest_length}),
                        body, -1});
          },
          "body"_a, "point"_a, "anchor"_a, "stiffness"_a, "damping"_a = 0.0, "rest_length"_a = 0.0,
          "A linear spring-damper from the body point `point` (m, body components) to the fixed "
          "`anchor` (m, inertial): stiffness N/m, damping N s/m, rest_length m.")
      .def(
          "add_spring_between",
          [](PyScene& s, int a, int b, nb::handle point_a, nb::handle point_b, double stiffness,
             double damping, double rest_length) {
            s.add_load(
                {SpringDamperBetween(vector3(point_a, "point_a"), vector3(point_b, "point_b"),
                                     {stiffness, damping, rest_length}),
                 a, b});
          },
          "a"_a, "b"_a, "point_a"_a, "point_b"_a, "stiffness"_a, "damping"_a = 0.0,
          "rest_length"_a = 0.0,
          "A linear spring-damper between body points of bodies a and b (m, body components of "
          "each).")
      .def(
          "add_user_load", [](PyScene& s, int body, nb::callable fn) { s.add_user_load(body, fn); },
          "body"_a, "fn"_a,
          "A Python callable as a load: fn(t, position, rotation, velocity, omega) -> (force, "
          "moment), force in inertial components at the reference point (N), moment about it "
          "in body components (N m). SLOW: every right-hand side calls Python (taking the GIL), "
          "and a scene with one has no exact Jacobian (BDF uses difference quotients); an "
          "ensemble with one runs its loads one thread at a time.")
      .def("add_event", &PyScene::add_event, "function"_a, "direction"_a = 0,
           "action"_a = nb::none(),
           nb::sig("def add_event(self, function: collections.abc.Callable[[float, EventState], "
                   "float], direction: int = 0, action: collections.abc.Callable[[float, "
                   "EventState], object] | None = None) -> None"),
           kAddEventDoc)
      .def_prop_ro(
          "size", [](const PyScene& s) { return s.compiled().size(); }, "The length of y.")
      .def_prop_ro("body_count", [](const PyScene& s) { return s.bodies().size(); })
      .def(
          "layout",
          [](const PyScene& s, int body) {
            s.check_body(body, "body");
            const auto [offset, rates] = s.compiled().layout(body);
            const BodyRecord& r = s.bodies()[static_cast<std::size_t>(body)];
            const int nt = r.body->parameterization().size();
            nb::dict d;
            const auto sl = [](int a, int b) { return nb::slice(a, b, 1); };
            if (r.body->reference() == ReferencePoint::fixed_point) {
              d["theta"] = sl(offset, offset + nt);
              d["omega"] = sl(rates, rates + 3);
            } else {
              d["position"] = sl(offset, offset + 3);
              d["theta"] = sl(offset + 3, offset + 3 + nt);
              d["velocity"] = sl(rates, rates + 3);
              d["omega"] = sl(rates + 3, rates + 6);
            }
            return d;
          },
          "body"_a,
          "Where the body's entries sit in y: a dict of slices 'position', 'theta', 'velocity', "
          "'omega' (only 'theta' and 'omega' for a body held at a fixed point).")
      .def(
          "initial_state", [](const PyScene& s) { return PyState{s.compiled().initial_state()}; },
          "The initial state, from the bodies' initial states.")
      .def(
          "state", [](const PyScene& s, nb::handle y) { return PyState{s.state(y)}; }, "y"_a,
          "The State of y (size()) with the initial chart bases.")
      .def(
          "kinetic_energy",
          [](const PyScene& s, nb::handle st) { return s.compiled().kinetic_energy(s.state(st)); },
          "state"_a, "J.")
      .def(
          "potential_energy",
          [](const PyScene& s, nb::handle st) {
            return s.compiled().potential_energy(s.state(st));
          },
          "state"_a, "Of gravity and the springs, J.")
      .def(
          "energy",
          [](const PyScene& s, nb::handle st) {
            const SceneState x = s.state(st);
            return s.compiled().kinetic_energy(x) + s.compiled().potential_energy(x);
          },
          "state"_a, "Kinetic plus potential, J.")
      .def(
          "linear_momentum",
          [](const PyScene& s, nb::handle st) { return s.compiled().linear_momentum(s.state(st)); },
          "state"_a, "kg m/s, inertial.")
      .def(
          "angular_momentum",
          [](const PyScene& s, nb::handle st) {
            return s.compiled().angular_momentum(s.state(st));
          },
          "state"_a, "About the inertial origin, kg m^2/s, inertial.")
      .def(
          "constraint_drift",
          [](const PyScene& s, nb::handle st) {
            return s.compiled().constraint_drift(s.state(st));
          },
          "state"_a, "The largest | |p| - 1 | of the Euler-parameter bodies (0 for others).")
      .def(
          "rotation",
          [](const PyScene& s, int body, nb::handle st) {
            s.check_body(body, "body");
            return s.compiled().rotation(body, s.state(st));
          },
          "body"_a, "state"_a, "R of the body, body -> inertial (chart base included).")
      .def(
          "omega",
          [](const PyScene& s, int body, nb::handle st) {
            s.check_body(body, "body");
            return s.compiled().omega(body, s.state(st));
          },
          "body"_a, "state"_a, "rad/s, body components.")
      .def(
          "position",
          [](const PyScene& s, int body, nb::handle st) {
            s.check_body(body, "body");
            return s.compiled().position(body, s.state(st));
          },
          "body"_a, "state"_a, "r_oc, m, inertial.")
      .def(
          "velocity",
          [](const PyScene& s, int body, nb::handle st) {
            s.check_body(body, "body");
            return s.compiled().velocity(body, s.state(st));
          },
          "body"_a, "state"_a, "rdot_oc, m/s, inertial.")
      .def(
          "reaction_force",
          [](const PyScene& s, int body, nb::handle st, double t) {
            s.check_body(body, "body");
            return s.compiled().reaction_force(body, s.state(st), t);
          },
          "body"_a, "state"_a, "t"_a = 0.0,
          "The force the support exerts on a body held at a fixed point, N, inertial, with the "
          "loads evaluated at time t (s).")
      .def(
          "rhs",
          [](const PyScene& s, nb::handle st, double t) {
            return s.compiled().rhs(t, s.state(st));
          },
          "state"_a, "t"_a = 0.0, "y' = f(t, y), the right-hand side the integrators see.")
      .def(
          "integrate",
          [](const PyScene& s, nb::handle times, double t0, nb::handle state,
             const std::string& method, double rtol, double atol, long max_steps,
             double initial_step, double max_step) {
            const CompiledScene& c = s.compiled();
            const std::vector<double> ts = output_times(times);
            const SceneState s0 = state.is_none() ? c.initial_state() : s.state(state);
            const RunOptions o = run_options(method, rtol, atol, max_steps, initial_step, max_step);
            RawTrajectory raw;
            {
              const PyScene::Running running(s);
              const nb::gil_scoped_release release;
              raw = c.integrate(t0, s0, ts, o);
            }
            return trajectory(s, std::move(raw), static_cast<std::size_t>(c.size()));
          },
          "times"_a, "t0"_a = 0.0, "state"_a = nb::none(), "method"_a = "auto", "rtol"_a = 1e-8,
          "atol"_a = 1e-8, "max_steps"_a = 0, "initial_step"_a = 0.0, "max_step"_a = 0.0,
          kIntegrateDoc)
      .def(
          "ensemble",
          [](const PyScene& s, nb::handle times, nb::handle initial, double t0,
             const std::string& method, double rtol, double atol, long max_steps,
             double initial_step, double max_step, int threads) {
            const CompiledScene& c = s.compiled();
            const std::vector<double> ts = output_times(times);
            const InArray a = as_array(initial, "initial");
            const auto n = static_cast<std::size_t>(c.size());
            if (a.ndim() != 2 || a.shape(1) != n || a.shape(0) == 0) {
              throw std::invalid_argument("tumble.Scene.ensemble: 'initial' must have shape "
                                          "(runs, " +
                                          std::to_string(n) +
                                          "), runs >= 1, got "
                                          "shape " +
                                          shape_of(a));
            }
            check_finite(a.data(), a.size(), "initial");
            if (threads < 0) {
              throw std::invalid_argument("tumble.Scene.ensemble: 'threads' must be >= 0");
            }
            const std::vector<double> y0(a.data(), a.data() + a.size());
            const std::size_t runs = a.shape(0);
            const RunOptions o = run_options(method, rtol, atol, max_steps, initial_step, max_step);
            RawEnsemble raw;
            {
              const PyScene::Running running(s);
              const nb::gil_scoped_release release;
              raw = c.ensemble(t0, y0, runs, ts, o, threads);
            }
            PyEnsemble out;
            const std::size_t b = s.bodies().size(), nt = ts.size();
            split_bodies(raw.bodies, runs * nt, b, {runs, nt}, out.position, out.quaternion,
                         out.velocity, out.omega);
            out.t = numpy(std::vector<double>(ts), {nt});
            out.y = numpy(std::move(raw.y), {runs, nt, n});
            out.energy = numpy(std::move(raw.energy), {runs, nt});
            out.errors = std::move(raw.errors);
            out.threads = raw.threads;
            return out;
          },
          "times"_a, "initial"_a, "t0"_a = 0.0, "method"_a = "auto", "rtol"_a = 1e-8,
          "atol"_a = 1e-8, "max_steps"_a = 0, "initial_step"_a = 0.0, "max_step"_a = 0.0,
          "threads"_a = 0, kEnsembleDoc);

  m.def("scene_parameterizations", &scene_parameterizations,
        "The parameterizations this module has compiled scenes for (a build option: "
        "TUMBLE_PYTHON_SCENE_PARAMETERIZATIONS).");
}

}  // namespace tumble::python
