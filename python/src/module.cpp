// The Python module tumble._tumble (re-exported by the package tumble, python/tumble).

#include <nanobind/nanobind.h>

#include "bindings.hpp"

NB_MODULE(_tumble, m) {
  m.doc() =
      "tumble's C++ core: orientation parameterizations, rigid bodies, scenes, the front door "
      "integrator and ensembles (SI units, rad).";
  tumble::python::bind_errors(m);
  tumble::python::bind_orientation(m);
  tumble::python::bind_body(m);
  tumble::python::bind_scene(m);
  tumble::python::bind_events(m);
}
