// C++ exceptions as Python exceptions, with the same messages.
//  - std::invalid_argument (bad input: mass properties, options, states, times) and
//    tumble::NonFiniteError (std::domain_error: a non-finite value met) -> ValueError
//    (nanobind's own translation of the standard exceptions);
//  - tumble::IntegrationError and its subclasses -> tumble.IntegrationError (a RuntimeError),
//    with the attributes `reason` (IntegrationFailure's name, e.g. 'step_budget') and `time`
//    (the time reached, s).

#include "tumble/integrate/errors.hpp"

#include <nanobind/nanobind.h>

#include "bindings.hpp"

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
          PyErr_SetObject(exc_type, exc.ptr());
        }
      },
      type.ptr());
}

}  // namespace tumble::python
