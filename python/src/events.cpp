// Python events (tumble.Scene.add_event): PythonEvent (scene_api.hpp), the glue between the C++
// scene's tumble::Event and the Python callables, and tumble.EventState, the read-only state
// they are given. Kept apart from the compiled scenes (scene_of.cpp.in), which only wrap a
// PythonEvent in a tumble::Event: nothing here is a template of the scene.

#include <cmath>
#include <cstddef>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <nanobind/eigen/dense.h>
#include <nanobind/nanobind.h>

#include "bindings.hpp"
#include "convert.hpp"
#include "handles.hpp"
#include "load_error.hpp"
#include "scene_api.hpp"

namespace tumble::python {

namespace {

/// tumble.EventState: a State (y, bases) and, per body, what Trajectory has per output (the
/// kRecordPerBody values of CompiledScene::record), computed in C++ before the GIL is taken.
struct PyEventState : PyState {
  std::vector<double> bodies;  // B x kRecordPerBody
};

using BodyRows = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// Columns [first, first + count) of the per-body records, B x count.
BodyRows columns(const PyEventState& s, int first, int count) {
  const auto b = static_cast<Eigen::Index>(s.bodies.size() / kRecordPerBody);
  BodyRows out(b, count);
  for (Eigen::Index i = 0; i < b; ++i) {
    for (int j = 0; j < count; ++j) {
      out(i, j) = s.bodies[static_cast<std::size_t>(i * kRecordPerBody + first + j)];
    }
  }
  return out;
}

PyEventState event_state(const SceneStateView& s, const CompiledScene& scene) {
  PyEventState st;
  st.state.y = s.y;
  st.state.base.assign(s.base.begin(), s.base.end());
  st.bodies.reserve(static_cast<std::size_t>(scene.body_count()) * kRecordPerBody);
  scene.record(s, st.bodies);
  return st;
}

/// The Python exception being handled, carried through C++ as "tumble: the event <what> raised
/// TypeName: message" with the exception object (load_error.hpp). Needs the GIL.
PythonLoadError carried(const nb::python_error& e, const char* what) {
  const std::string type = nb::cast<std::string>(nb::handle(e.type()).attr("__name__"));
  return {std::string("tumble: the event ") + what + " raised " + type + ": " +
              nb::cast<std::string>(nb::str(e.value())),
          e.value()};
}

}  // namespace

PythonEvent::PythonEvent(nb::object function, int direction, nb::object action)
    : function_(new nb::object(std::move(function)),
                [](nb::object* o) {
                  const nb::gil_scoped_acquire gil;
                  delete o;
                }),
      direction_(direction) {
  if (!action.is_none()) {
    action_.reset(new nb::object(std::move(action)), [](nb::object* o) {
      const nb::gil_scoped_acquire gil;
      delete o;
    });
  }
}

double PythonEvent::value(double t, const SceneStateView& s, const CompiledScene& scene) const {
  PyEventState st = event_state(s, scene);  // C++ only: before the GIL
  const nb::gil_scoped_acquire gil;
  try {
    const nb::object r = (*function_)(t, nb::cast(std::move(st), nb::rv_policy::move));
    const double g = PyFloat_AsDouble(r.ptr());
    if (g == -1.0 && PyErr_Occurred() != nullptr) {
      PyErr_Clear();
      PyErr_Format(PyExc_TypeError, "an event function must return a float, got %s",
                   Py_TYPE(r.ptr())->tp_name);
      throw nb::python_error();
    }
    if (!std::isfinite(g)) {
      PyErr_Format(PyExc_ValueError, "the event function returned %R at t = %R",
                   nb::float_(g).ptr(), nb::float_(t).ptr());
      throw nb::python_error();
    }
    return g;
  } catch (const nb::python_error& e) {
    throw carried(e, "function");
  }
}

void PythonEvent::act(double t, SceneState& s, const CompiledScene& scene) const {
  PyEventState st = event_state(s, scene);
  const nb::gil_scoped_acquire gil;
  nb::object r;
  try {
    r = (*action_)(t, nb::cast(std::move(st), nb::rv_policy::move));
  } catch (const nb::python_error& e) {
    throw carried(e, "action");
  }
  if (r.is_none()) {
    return;
  }
  const InArray a = as_array(r, "the y an event action returned");
  if (a.ndim() != 1 || static_cast<Eigen::Index>(a.shape(0)) != s.y.size()) {
    throw std::invalid_argument("tumble: an event action must return None or a new y of shape (" +
                                std::to_string(s.y.size()) + ",), got shape " + shape_of(a) +
                                " at t = " + std::to_string(t));
  }
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!std::isfinite(a.data()[i])) {
      throw std::invalid_argument("tumble: the y an event action returned at t = " +
                                  std::to_string(t) + " has a non-finite entry at index " +
                                  std::to_string(i) + " (" + std::to_string(a.data()[i]) + ")");
    }
  }
  s.y = Eigen::Map<const Eigen::VectorXd>(a.data(), s.y.size());
}

void bind_events(nb::module_& m) {
  nb::class_<PyEventState, PyState>(
      m, "EventState",
      "The state an event function or action of Scene.add_event is given: a State (y, bases; "
      "the observables of Scene take it) and, per body as in Trajectory, position (B x 3, r_oc "
      "inertial, m), quaternion (B x 4, of R, (w, x, y, z), w >= 0), velocity (B x 3, "
      "inertial, m/s), omega (B x 3, body, rad/s). A copy: changing it changes nothing; an "
      "action returns the new y instead.")
      .def_prop_ro(
          "position", [](const PyEventState& s) { return columns(s, 0, 3); }, nb::rv_policy::move)
      .def_prop_ro(
          "quaternion", [](const PyEventState& s) { return columns(s, 3, 4); }, nb::rv_policy::move)
      .def_prop_ro(
          "velocity", [](const PyEventState& s) { return columns(s, 7, 3); }, nb::rv_policy::move)
      .def_prop_ro(
          "omega", [](const PyEventState& s) { return columns(s, 10, 3); }, nb::rv_policy::move);
}

}  // namespace tumble::python
