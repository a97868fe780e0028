#pragma once
// What a Python user load or event raised, carried through the C++ integrators as a C++
// exception: what() in words ("tumble: the user load raised TypeName: message", "the event
// function raised ...", no traceback), and the Python exception object itself, which errors.cpp
// makes the __cause__ of the tumble.IntegrationError the integrator stops with (reason
// 'callback'), as `raise IntegrationError from original` would; or, for an event action's (which
// the integrators pass through unchanged), raises again.

#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

#include <nanobind/nanobind.h>

namespace tumble::python {

class PythonLoadError : public std::runtime_error {
 public:
  /// exception: the Python exception object (a new reference is kept); needs the GIL.
  PythonLoadError(const std::string& what, nanobind::handle exception)
      : std::runtime_error(what),
        exception_(new nanobind::object(nanobind::borrow(exception)), [](nanobind::object* o) {
          const nanobind::gil_scoped_acquire gil;
          delete o;
        }) {}

  /// The Python exception object; use it with the GIL held.
  [[nodiscard]] nanobind::handle exception() const { return *exception_; }

 private:
  // Shared, so that copies of the exception need no GIL (an ensemble's worker thread may drop
  // the last one): its owner takes the GIL to release the object, as PythonLoad does its callable.
  std::shared_ptr<nanobind::object> exception_;
};

}  // namespace tumble::python
