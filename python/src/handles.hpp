#pragma once
// What the Python classes hold, shared by the binding sources.

#include <memory>
#include <string>

#include <nanobind/nanobind.h>

#include "body.hpp"
#include "tumble/scene/state.hpp"

namespace tumble::python {

/// tumble.RigidBody: an immutable body, shared by the scenes it is added to.
struct BodyHandle {
  std::shared_ptr<const Body> body;
};

/// tumble.State: y and the chart bases of every body (a whole state: the same attitude always).
struct PyState {
  SceneState state;
};

ReferencePoint reference_point(const std::string& name);  // body.cpp
const char* reference_name(ReferencePoint r);             // body.cpp

}  // namespace tumble::python
