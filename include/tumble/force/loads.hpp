#pragma once
// Apply a set of force elements to one body: the wrench, the generalized force Q (Eq. 1.31) and
// the accelerations (Eq. 1.32). The rotation matrix is computed once, and only if one of the
// elements needs it (decided at compile time).

#include "tumble/body/rigid_body.hpp"
#include "tumble/force/concept.hpp"

namespace tumble {

template <class Body, ForceElement... F>
constexpr bool loads_need_rotation = (F::needs_rotation(Body::reference) || ...);

/// The wrench of all `elements` on `body` at time t.
template <class Body, ForceElement... F>
[[nodiscard]] Wrench<typename Body::Scalar> total_wrench(const Body& body,
                                                         const typename Body::Scalar& t,
                                                         const typename Body::Coords& q,
                                                         const typename Body::Coords& qdot,
                                                         const F&... elements) {
  [[maybe_unused]] const auto k =  // unused when there are no elements
      body.template kinematics<loads_need_rotation<Body, F...>>(q, qdot);
  Wrench<typename Body::Scalar> w;
  (elements.apply(t, k, w), ...);
  return w;
}

/// Q = L^T F summed over all `elements` (Eqs. 1.28-1.31).
template <class Body, ForceElement... F>
[[nodiscard]] typename Body::Coords generalized_force(const Body& body,
                                                      const typename Body::Scalar& t,
                                                      const typename Body::Coords& q,
                                                      const typename Body::Coords& qdot,
                                                      const F&... elements) {
  return Body::generalized_force(q, total_wrench(body, t, q, qdot, elements...));
}

/// qddot of `body` under `elements` (Eq. 1.32).
template <class Body, ForceElement... F>
[[nodiscard]] typename Body::Coords accelerations(const Body& body, const typename Body::Scalar& t,
                                                  const typename Body::Coords& q,
                                                  const typename Body::Coords& qdot,
                                                  const F&... elements) {
  const auto k = body.template kinematics<loads_need_rotation<Body, F...>>(q, qdot);
  Wrench<typename Body::Scalar> w;
  (elements.apply(t, k, w), ...);
  return body.accelerations(q, qdot, k, w);
}

}  // namespace tumble
