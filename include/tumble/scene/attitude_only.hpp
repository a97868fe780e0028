#pragma once
// The attitude-only form of a scene: the same bodies, each held at its centroid, with the same
// loads. A free body framed at its centroid (ReferencePoint::centroid) has the state
// [r_oc; theta; v; omega] (13 entries with Euler parameters); held at its centroid
// (ReferencePoint::fixed_point with the fixed point there) it has [theta; omega] (7), and its
// attitude obeys the same equations: at the centroid the rotation does not feel the translation
// (Eq. 1.33: m12 and f_v^r vanish), so where no load reads the translation the attitude is the
// same, and it costs about two thirds (docs/choosing.md: 1.4-1.5x faster to the same error).
//
// Where the user says so: `integrate(attitude_only(scene), ...)`. What "no load reads the
// translation" means is the user's to judge for their own loads: gravity, body moments and
// constant point forces are exact (their moment about the centroid does not depend on where the
// centroid is); a spring to the ground reads the position, which is now frozen at the centroid's
// initial place. Couplings (two-body loads read both positions) and joints are refused at compile
// time, and so are bodies framed away from their centroid (ReferencePoint::offset: their loads'
// points are given from another point).

#include <type_traits>

#include "tumble/body/rigid_body.hpp"
#include "tumble/force/concept.hpp"
#include "tumble/scene/observables.hpp"
#include "tumble/scene/scene.hpp"
#include "tumble/scene/state.hpp"

namespace tumble {

/// The type a body takes in the attitude-only form: held at its centroid, or as it was if held.
template <class Body> struct AttitudeOnlyBody {
  static_assert(Body::reference != ReferencePoint::offset,
                "attitude_only: a body framed away from its centroid (ReferencePoint::offset) "
                "cannot be held there with the same loads; frame it at its centroid");
  using type = RigidBody<typename Body::Param, ReferencePoint::fixed_point, typename Body::Scalar>;
};

template <class SceneT> struct AttitudeOnlyScene;
template <class... B, class... L, StateForm Form>
struct AttitudeOnlyScene<Scene<Bodies<B...>, Loads<L...>, Form, Joints<>>> {
  static_assert(!(CouplingElement<L> || ...),
                "attitude_only: a coupling between two bodies reads both positions, which the "
                "attitude-only form freezes");
  using type = Scene<Bodies<typename AttitudeOnlyBody<B>::type...>, Loads<L...>, Form>;
};

/// The scene type of attitude_only(SceneT).
template <class SceneT> using AttitudeOnly = typename AttitudeOnlyScene<SceneT>::type;

/// The handle of a body in the attitude-only form (ids are kept).
template <class Body>
[[nodiscard]] BodyId<typename AttitudeOnlyBody<Body>::type> attitude_id(BodyId<Body> b) {
  return {b.id, b.local};
}

/// The attitude-only form of `scene` at the state s: every body held at its centroid's position
/// in s, with its attitude and angular velocity from s, and the same loads.
template <class SceneT>
[[nodiscard]] AttitudeOnly<SceneT> attitude_only(const SceneT& scene, const SceneStateView& s) {
  AttitudeOnly<SceneT> out;
  for (int id = 0; id < scene.body_count(); ++id) {
    scene.visit_entry(id, [&](const auto& e) {
      using Body = std::remove_cvref_t<decltype(e.body)>;
      using Held = typename AttitudeOnlyBody<Body>::type;
      const InitialState is{.rotation = detail::rotation_of(e, s), .omega = detail::omega_of(e, s)};
      if constexpr (Body::fixed) {
        out.add(e.body, is);
      } else {
        out.add(Held(e.body.mass_properties(), detail::position_of(e, s)), is);
      }
    });
  }
  scene.for_each_load([&](const auto& at) {
    scene.visit_entry(at.a, [&](const auto& e) {
      using Held = typename AttitudeOnlyBody<std::remove_cvref_t<decltype(e.body)>>::type;
      out.add_load(BodyId<Held>{e.id, e.local}, at.load);
    });
  });
  return out;
}

/// The same at the scene's initial state.
template <class SceneT> [[nodiscard]] AttitudeOnly<SceneT> attitude_only(const SceneT& scene) {
  return attitude_only(scene, scene.initial_state());
}

}  // namespace tumble
