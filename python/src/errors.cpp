// C++ exceptions as Python exceptions, with the same messages.
//  - std::invalid_argument (bad input: mass properties, options, states, times) and
//    tumble::NonFiniteError (std::domain_error: a non-finite value met) -> ValueError
//    (nanobind's own translation of the standard exceptions);
//  - tumble::IntegrationError and its subclasses -> tumble.IntegrationError (a RuntimeError),
//    with the attributes `reason` (IntegrationFailure's name, e.g. 'step_budget') and `time`
//    (the time reached, s). When a callback stopped the integration (reason 'callback', under
//    every method), what it threw is the __cause__: the Python exception a Python load or event
//    function raised (load_error.hpp), or a RuntimeError with the message of a C++ one;
//  - a PythonLoadError no integrator wrapped (an event action's exception, which the integrators
//    pass through unchanged) -> the Python exception itself.

#include "tumble/integrate/errors.hpp"

#include <nanobind/nanobind.h>

#include "bindings.hpp"
#include "load_error.hpp"

namespace tumble::python {

namespace {
const char* reason_name(IntegrationFailure r) {
  switch (r) {
    case IntegrationFailure::step_budget:
      return "step_budget";
    case IntegrationFailure::step_size:
      return "step_size";
    case IntegrationFailure::stiff:
      return "stiff";
    case IntegrationFailure::error_test:
      return "error_test";
    case IntegrationFailure::convergence:
      return "convergence";
    case IntegrationFailure::callback:
      return "callback";
    case IntegrationFailure::solver:
      return "solver";
  }
  return "unknown";
}

/// The Python exception for the cause of an IntegrationError: the one a Python load raised, or
/// a RuntimeError with the message of a C++ exception (a new reference; null if that failed).
PyObject* python_cause(const std::exception_ptr& cause) {
  try {
    std::rethrow_exception(cause);
  } catch (const PythonLoadError& e) {
    return nanobind::handle(e.exception()).inc_ref().ptr();
  } catch (const nanobind::python_error& e) {
    return e.value().inc_ref().ptr();
  } catch (const std::exception& e) {
    return PyObject_CallFunction(PyExc_RuntimeError, "s", e.what());
  } catch (...) {
    return PyObject_CallFunction(PyExc_RuntimeError, "s",
                                 "an exception not derived from std::exception");
  }
}
}  // namespace

void bind_errors(nanobind::module_& m) {
  namespace nb = nanobind;
  // The exception type is kept by the module, which outlives every call that may raise it: the
  // translator gets it as its payload (no global of ours).
  nb::object type = nb::steal(PyErr_NewExceptionWithDoc(
      "tumble.IntegrationError",
      "An integration could not go on (tumble::IntegrationError): str(e) says where and why; "
      "e.reason is one of 'step_budget', 'step_size', 'stiff', 'error_test', 'convergence', "
      "'callback', 'solver'; e.time is the time reached, s.",
      PyExc_RuntimeError, nullptr));
  if (!type.is_valid()) {
    throw nb::python_error();
  }
  m.attr("IntegrationError") = type;
  nb::register_exception_translator(
      [](const std::exception_ptr& p, void* payload) {
        try {
          std::rethrow_exception(p);
        } catch (const IntegrationError& e) {
          auto* exc_type = static_cast<PyObject*>(payload);
          nb::object exc = nb::steal(PyObject_CallFunction(exc_type, "s", e.what()));
          if (!exc.is_valid()) {
            return;  // the call's own error is set
          }
          nb::setattr(exc, "reason", nb::str(reason_name(e.reason())));
          nb::setattr(exc, "time", nb::float_(e.time()));
          if (e.cause()) {
            PyObject* cause = python_cause(e.cause());
            if (cause == nullptr) {
              return;  // the call's own error is set
            }
            PyException_SetCause(exc.ptr(), cause);  // steals the reference
          }
          PyErr_SetObject(exc_type, exc.ptr());
        } catch (const PythonLoadError& e) {
          // A Python callback's exception that no integrator wrapped (an event action's: they
          // pass those through unchanged): the Python exception itself, raised again.
          const nb::handle exc = e.exception();
          PyErr_SetObject(reinterpret_cast<PyObject*>(Py_TYPE(exc.ptr())), exc.ptr());
        }
      },
      type.ptr());
}

}  // namespace tumble::python
