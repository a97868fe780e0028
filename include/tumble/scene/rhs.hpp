#pragma once
// The right-hand side of a scene: y' = f(t, y), per body in the scene's state form (state.hpp):
// - generalized, y_k = [q; qdot]: f_k = [qdot_k; qddot_k], where qddot_k solves
//   M qddot = f_v + Q (reference chapter, Eq. 1.32; Eq. 1.33 at the centroid) for the wrench W_k
//   of its loads (rigid_body.hpp, which goes from the wrench to the accelerations without forming
//   Q when the body has no other use for it);
// - quasi_velocities, y_k = [r_oc; theta; v; omega]: f_k = [v; G^{-1} omega; a_c; alpha], the
//   same Newton-Euler rates without thetaddot (RigidBody::quasi_rates). Three passes, each over
//   concrete types: the kinematics of every body (R only where a
// load or the offset frame needs it, composed with the body's chart base R0 from the state), the
// loads (one-body loads with the body's typed kinematics, couplings with both), then the
// accelerations. Nothing is allocated: the scratch lives in the workspace. A scene without load
// types (Loads<>) skips the first two passes: each body's rates come from its own block with a
// zero wrench, and nothing is written to the workspace. A mechanism (a scene with joints) adds,
// between the loads and the accelerations, the joints' reactions from the constraint solve
// (joints.hpp). FiniteCheck says who checks the result.

#include <cstddef>
#include <span>
#include <tuple>
#include <type_traits>

#include "tumble/force/concept.hpp"
#include "tumble/force/coupling.hpp"
#include "tumble/scene/detail/body_terms.hpp"
#include "tumble/scene/joints.hpp"
#include "tumble/scene/scene.hpp"
#include "tumble/scene/workspace.hpp"

namespace tumble {

/// Who checks the right-hand side for finiteness: rhs() itself, throwing NonFiniteError from the
/// body whose rates are not finite (what CVODE needs: it retries a step after such a failure),
/// or the caller, which then gets the values, non-finite ones included, and no exception
/// (OdeintIntegrator checks all the stages of a step at once, and rejects the step).
enum class FiniteCheck { each_call, by_caller };

namespace detail {

/// Pass 1: every body's kinematics at (y, base) into the workspace, wrenches cleared.
template <class SceneT, class Y>
void scene_kinematics(const SceneT& scene, SceneWorkspace<SceneT>& ws, const Y& y,
                      std::span<const Matrix3<double>> base) {
  scene.for_each_entry([&](const auto& e) {
    using Body = std::remove_cvref_t<decltype(e.body)>;
    using E = std::remove_cvref_t<decltype(e)>;
    auto& k = ws.kinematics(e);
    body_kinematics<E::form>(e.body, y.template segment<Body::nq>(e.offset),
                             y.template segment<E::rate_size>(e.rates), base[e.id],
                             e.needs_rotation, k, &k.theta_functions);
    ws.wrench(e.id) = Wrench<double>{};
  });
}

/// Pass 2: every load of type Load adds its wrench (couplings to both bodies).
template <class Load, class SceneT>
void scene_loads_of_type(const SceneT& scene, SceneWorkspace<SceneT>& ws, double t) {
  for (const auto& a : scene.template loads<Load>()) {
    if constexpr (CouplingElement<Load>) {
      a.load.apply(t, ws.view(a.a), ws.view(a.b), ws.wrench(a.a), ws.wrench(a.b));
    } else {
      scene.visit_entry(a.a,
                        [&](const auto& e) { a.load.apply(t, ws.kinematics(e), ws.wrench(e.id)); });
    }
  }
}

template <class SceneT, std::size_t... I>
void scene_loads([[maybe_unused]] const SceneT& scene, [[maybe_unused]] SceneWorkspace<SceneT>& ws,
                 [[maybe_unused]] double t, std::index_sequence<I...>) {
  (scene_loads_of_type<std::tuple_element_t<I, typename SceneT::LoadTypes>>(scene, ws, t), ...);
}

/// Pass 3 for one body: the rate of its block of y for its kinematics k and wrench w (checked for
/// finiteness when Checked); in [q; qdot], with the functions of theta that body_kinematics kept
/// in `theta_functions`.
template <bool Checked, class E, class Y, class K, class W, class Pre, class Ydot>
[[gnu::always_inline]] inline void entry_rates(const E& e, const Y& y, const K& k, const W& w,
                                               bool stabilize,
                                               [[maybe_unused]] const Pre& theta_functions,
                                               Ydot& ydot) {
  using Body = std::remove_cvref_t<decltype(e.body)>;
  constexpr int nq = Body::nq;
  const typename Body::Coords q = y.template segment<nq>(e.offset);
  if constexpr (E::quasi) {
    body_quasi_rates_into<Checked>(e.body, q, k, w, stabilize,
                                   ydot.template segment<Body::nx>(e.offset));
  } else {
    const typename Body::Coords qd = y.template segment<nq>(e.rates);
    ydot.template segment<nq>(e.offset) = qd;
    body_accelerations_into<Checked>(e.body, q, qd, k, w, stabilize,
                                     ydot.template segment<nq>(e.rates), &theta_functions);
  }
}

/// A scene without loads (and joints): each body's rates from its own block, with no wrench
/// (NoWrench: its terms left out, not multiplied by zero); nothing is written to the workspace
/// (no load reads it).
template <bool Checked, class SceneT, class Y, class Ydot>
[[gnu::always_inline]] inline void unloaded_rates(const SceneT& scene, SceneWorkspace<SceneT>& ws,
                                                  const Y& y, std::span<const Matrix3<double>> base,
                                                  Ydot& ydot) {
  scene.for_each_entry([&](const auto& e) {
    using E = std::remove_cvref_t<decltype(e)>;
    using Body = std::remove_cvref_t<decltype(e.body)>;
    typename Body::Kinematics k;
    detail::ThetaFunctions<Body, E::form> theta_functions;
    body_kinematics<E::form>(e.body, y.template segment<Body::nq>(e.offset),
                             y.template segment<E::rate_size>(e.rates), base[e.id],
                             Body::reference == ReferencePoint::offset, k, &theta_functions);
    entry_rates<Checked>(e, y, k, NoWrench{}, ws.stabilize_constraints, theta_functions, ydot);
  });
}

}  // namespace detail

/// y' = f(t, y) for the state (y, base) into ydot (any Eigen vectors of size scene.size(), e.g.
/// maps of an integrator's memory). Throws NonFiniteError on a non-finite result (which CVODE
/// treats as recoverable: it retries with a smaller step).
template <FiniteCheck Check = FiniteCheck::each_call, class SceneT, class Y, class Ydot>
void rhs(const SceneT& scene, SceneWorkspace<SceneT>& ws, double t, const Y& y,
         std::span<const Matrix3<double>> base, Ydot&& ydot) {
  constexpr bool checked = Check == FiniteCheck::each_call;
  if constexpr (!SceneT::has_loads && !SceneT::has_joints) {
    // detail::unloaded_rates written out: calling it here (the same work) made a lean body's
    // Fehlberg 7(8) run 17-19 % slower under GCC 12 -O3, and a loop of its per-body step 25 %
    // with N = Dynamic (docs/benchmarks/floors.md, 2026-11-27).
    scene.for_each_entry([&](const auto& e) {
      using E = std::remove_cvref_t<decltype(e)>;
      using Body = std::remove_cvref_t<decltype(e.body)>;
      typename Body::Kinematics k;
      detail::ThetaFunctions<Body, E::form> theta_functions;
      detail::body_kinematics<E::form>(
          e.body, y.template segment<Body::nq>(e.offset), y.template segment<E::rate_size>(e.rates),
          base[e.id], Body::reference == ReferencePoint::offset, k, &theta_functions);
      detail::entry_rates<checked>(e, y, k, NoWrench{}, ws.stabilize_constraints, theta_functions,
                                   ydot);
    });
  } else {
    if constexpr (!SceneT::has_joints) {
      // Load types listed but none attached (a scene type made for any loads, as the Python
      // package's): the same path, chosen at run time (14 % of a tumbling body's run).
      if (scene.load_count() == 0) {
        detail::unloaded_rates<checked>(scene, ws, y, base, ydot);
        return;
      }
    }
    detail::scene_kinematics(scene, ws, y, base);
    detail::scene_loads(scene, ws, t,
                        std::make_index_sequence<std::tuple_size_v<typename SceneT::LoadTypes>>{});
    if constexpr (SceneT::has_joints) {
      detail::constraint_forces(scene, ws);  // the joints' reactions join the loads' wrenches
    }
    scene.for_each_entry([&](const auto& e) {
      const auto& k = ws.kinematics(e);
      detail::entry_rates<checked>(e, y, k, ws.wrench(e.id), ws.stabilize_constraints,
                                   k.theta_functions, ydot);
    });
  }
}

/// The same for an owned state.
template <class SceneT, class Ydot>
void rhs(const SceneT& scene, SceneWorkspace<SceneT>& ws, double t, const SceneState& s,
         Ydot&& ydot) {
  rhs(scene, ws, t, s.y, std::span<const Matrix3<double>>(s.base), std::forward<Ydot>(ydot));
}

}  // namespace tumble
