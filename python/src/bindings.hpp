#pragma once
// The parts of the Python module tumble._tumble, one source file each (split by topic so that
// no compiler process needs much memory; python/CMakeLists.txt).

#include <nanobind/nanobind.h>

namespace tumble::python {

void bind_errors(nanobind::module_& m);       // errors.cpp
void bind_orientation(nanobind::module_& m);  // orientation.cpp
void bind_body(nanobind::module_& m);         // body.cpp
void bind_scene(nanobind::module_& m);        // scene.cpp
void bind_events(nanobind::module_& m);       // events.cpp (after bind_scene: State)

}  // namespace tumble::python
