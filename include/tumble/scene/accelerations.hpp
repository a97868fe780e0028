#pragma once
// What the loads make of a state: a body's angular acceleration and, for a body held at a fixed
// point, the reaction force the support exerts there. Unlike the observables (observables.hpp),
// these need the loads: each call evaluates every load of the scene at (t, state), as the
// right-hand side does (rhs.hpp), in a workspace of its own (so it allocates; it is meant for
// output, not for the hot path). Reference chapter, Eqs. (1.10) and (1.32).

#include <cstddef>
#include <tuple>
#include <type_traits>

#include "tumble/core/types.hpp"
#include "tumble/scene/observables.hpp"
#include "tumble/scene/rhs.hpp"
#include "tumble/scene/scene.hpp"
#include "tumble/scene/state.hpp"
#include "tumble/scene/workspace.hpp"

namespace tumble {

namespace detail {
/// f(entry, kinematics, wrench) for body b, with every load of the scene evaluated at (t, s).
template <class SceneT, class Body, class F>
auto with_loads(const SceneT& scene, BodyId<Body> b, const SceneStateView& s, double t, F&& f) {
  const auto& e = scene.entry(b);
  SceneWorkspace<SceneT> ws(scene);
  scene_kinematics(scene, ws, s.y, s.base);
  scene_loads(scene, ws, t,
              std::make_index_sequence<std::tuple_size_v<typename SceneT::LoadTypes>>{});
  return f(e, ws.kinematics(e), ws.wrench(e.id));
}
}  // namespace detail

/// The angular acceleration alpha = omegadot of body b at time t, body components, rad/s^2: what
/// G thetaddot + Gdot thetadot (Eq. 1.10) gives for the thetaddot of Eq. (1.32), computed from
/// the Newton-Euler closed form (RigidBody::velocity_rates) without thetaddot. The same in every
/// chart and in both state forms. The time is required: loads may depend on it (a user force, a
/// moment of t), and a forgotten one would silently evaluate them at t = 0.
template <class SceneT, class Body>
[[nodiscard]] Vector3<double> angular_acceleration(const SceneT& scene, BodyId<Body> b,
                                                   const SceneStateView& s, double t) {
  return detail::with_loads(scene, b, s, t, [&](const auto& e, const auto& k, const auto& w) {
    return e.body.velocity_rates(detail::theta_of(e, s), k, w).alpha;
  });
}

/// The force the support exerts on body b, held at its fixed point (ReferencePoint::fixed_point),
/// at time t, inertial components, N: the r-rows of Eq. (1.32) with rddot_oc = 0 (see
/// RigidBody::reaction_force), F_R = m a_g - F with F the resultant of the applied loads. The
/// time is required, as for angular_acceleration: the loads are evaluated at it.
template <class SceneT, class Body>
requires Body::fixed [[nodiscard]] Vector3<double> reaction_force(const SceneT& scene,
                                                                  BodyId<Body> b,
                                                                  const SceneStateView& s,
                                                                  double t) {
  return detail::with_loads(scene, b, s, t, [&](const auto& e, const auto& k, const auto& w) {
    return e.body.reaction_force(detail::rotation_of(e, s), k.omega, w);
  });
}

}  // namespace tumble
