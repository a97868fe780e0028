#pragma once
// The projection of a scene's state onto the constraint manifold of its Euler-parameter bodies,
// |p| = 1 and p.pdot = 0 (what CVODE's projection with BDF applies after each step). In the
// quasi-velocity state form (state.hpp) the manifold is |p| = 1 alone: omega is free and
// pdot = 1/2 L(p)^T omega is tangent by construction, so only p is normalized.

#include <type_traits>

#include "tumble/core/types.hpp"
#include "tumble/scene/scene.hpp"

namespace tumble {

/// The correction `corr` that takes y onto the manifold: p -> p/|p| and pdot -> pdot - (p.pdot) p
/// (the orthogonal projection; p -> p/|p| alone in the quasi-velocity form); zero elsewhere. When
/// `err` is not empty (the local error estimate) its component normal to the manifold is removed
/// too, as CVODE's projection expects.
template <class SceneT, class Y, class C, class E>
void project(const SceneT& scene, const Y& y, C&& corr, E&& err) {
  corr.setZero();
  scene.for_each_entry([&](const auto& e) {
    using Body = std::remove_cvref_t<decltype(e.body)>;
    if constexpr (Body::Param::has_constraint && std::remove_cvref_t<decltype(e)>::quasi) {
      const int ip = e.offset + e.theta_at;
      const Vector4<double> p = y.template segment<4>(ip);
      const Vector4<double> pn = p / p.norm();
      corr.template segment<4>(ip) = pn - p;
      if (err.size() > 0) {
        const Vector4<double> ep = err.template segment<4>(ip);
        err.template segment<4>(ip) = ep - pn.dot(ep) * pn;
      }
    } else if constexpr (Body::Param::has_constraint) {
      const int ip = e.offset + e.theta_at, iv = e.rates + e.theta_at;
      const Vector4<double> p = y.template segment<4>(ip);
      const Vector4<double> pd = y.template segment<4>(iv);
      const Vector4<double> pn = p / p.norm();
      corr.template segment<4>(ip) = pn - p;
      corr.template segment<4>(iv) = -pn.dot(pd) * pn;
      if (err.size() > 0) {
        const Vector4<double> ep = err.template segment<4>(ip);
        const Vector4<double> ev = err.template segment<4>(iv);
        err.template segment<4>(ip) = ep - pn.dot(ep) * pn;
        err.template segment<4>(iv) = ev - pn.dot(ev) * pn;
      }
    }
  });
}

}  // namespace tumble
