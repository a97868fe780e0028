#pragma once
// tumble_bench: tumble's scene for one problem, the part shared by every integrator that runs a
// tumble scene (CVODE's SceneIntegrator, work_precision/tumble.hpp; Boost.Odeint's
// OdeintIntegrator, work_precision/tumble_d.cpp).
//
// The scene is what a user would write for each problem. For the torque-free problems, whose
// questions are about attitude only: a body held at its centroid (ReferencePoint::fixed_point,
// the fixed point at the centroid; state [theta; thetadot] or [theta; omega], 7 or 6 entries, as
// the hand-written floors [p; omega]), or, with Translation::free, a free body framed at its
// centroid (ReferencePoint::centroid, 13 or 12 entries: the same attitude, with r and v carried
// along and integrated to no purpose). Framed at a point off
// its centroid (ReferencePoint::offset) with UniformGravity for the thrown body; and with
// UniformGravity and a SpringDamper from its reference point (the tip) to the inertial origin for
// the stiff tops. The state form (StateForm: [q; qdot] or [q; v; omega]) is a template argument.

#include <Eigen/Core>

#include "common/bench.hpp"
#include "tumble/tumble.hpp"

namespace tumble::bench {

inline InitialState initial_state(const Problem& p) {
  return {.position = p.position0, .rotation = p.r0, .velocity = p.velocity0, .omega = p.omega0};
}

inline MassProperties<> mass_properties(const Problem& p) {
  return MassProperties<>::about_centroid(p.mass, Eigen::Matrix3d(p.inertia.asDiagonal()),
                                          p.centroid);
}

/// What a method records at an output time, read from a state of the scene. Flattened: the
/// floors' samples (floors/rhs.hpp) are inlined into their observers, and this unit's inlining
/// budget (work_precision/tumble_d.cpp) would otherwise leave tumble's accessors called.
template <class SceneT, class Body>
[[gnu::flatten]] Sample scene_sample(const SceneT& scene, BodyId<Body> id,
                                     const SceneStateView& y) {
  Sample s;
  s.rotation = tumble::rotation(scene, id, y);
  s.omega = tumble::omega(scene, id, y);
  s.position = tumble::position(scene, id, y);
  s.velocity = tumble::velocity(scene, id, y);
  return s;
}

/// How a torque-free body is modelled: held at its centroid (attitude only) or free.
enum class Translation { attitude_only, free };

/// Calls `go.template operator()<SceneT, Body>(build)` with the scene type of problem p for
/// parameterization P in state form Form; `build(scene)` adds the body and its loads to an empty
/// SceneT and returns the body's id. Returns what go returns (a Run).
template <class P, StateForm Form, Translation T = Translation::attitude_only, class Go>
Run visit_problem_scene(const Problem& p, Go&& go) {
  switch (p.kind) {
    case ProblemKind::tumbling:
    case ProblemKind::minor_axis:
    case ProblemKind::major_axis:
    case ProblemKind::spinner: {
      if constexpr (T == Translation::attitude_only) {
        // The torque-free problems start at rest at the origin (work_precision/problems.cpp):
        // the centroid stays there, and holding it there changes nothing of the attitude.
        using Body = RigidBody<P, ReferencePoint::fixed_point>;
        using SceneT = Scene<Bodies<Body>, Loads<>, Form>;
        return go.template operator()<SceneT, Body>([&](SceneT& scene) {
          return scene.add(Body(mass_properties(p), p.position0), initial_state(p));
        });
      } else {
        using Body = RigidBody<P>;
        using SceneT = Scene<Bodies<Body>, Loads<>, Form>;
        return go.template operator()<SceneT, Body>(
            [&](SceneT& scene) { return scene.add(Body(mass_properties(p)), initial_state(p)); });
      }
    }
    case ProblemKind::gravity_offset: {
      using Body = RigidBody<P, ReferencePoint::offset>;
      using SceneT = Scene<Bodies<Body>, Loads<UniformGravity>, Form>;
      return go.template operator()<SceneT, Body>([&](SceneT& scene) {
        const auto id = scene.add(Body(mass_properties(p)), initial_state(p));
        scene.add_load(id, UniformGravity(p.gravity));
        return id;
      });
    }
    case ProblemKind::stiff_top: {
      using Body = RigidBody<P, ReferencePoint::offset>;
      using SceneT = Scene<Bodies<Body>, Loads<UniformGravity, SpringDamper>, Form>;
      return go.template operator()<SceneT, Body>([&](SceneT& scene) {
        const auto id = scene.add(Body(mass_properties(p)), initial_state(p));
        scene.add_load(id, UniformGravity(p.gravity));
        scene.add_load(
            id, SpringDamper(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                             {.stiffness = p.stiffness, .damping = p.damping, .rest_length = 0.0}));
        return id;
      });
    }
  }
  Run failed;
  failed.ok = false;
  failed.error = "unknown problem";
  return failed;
}

}  // namespace tumble::bench
