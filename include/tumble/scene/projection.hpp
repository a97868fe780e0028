#pragma once
// The projection of a scene's state onto the constraint manifold of its Euler-parameter bodies,
// |p| = 1 and p.pdot = 0 (what CVODE's projection with BDF applies after each step). In the
// quasi-velocity state form (state.hpp) the manifold is |p| = 1 alone: omega is free and
// pdot = 1/2 L(p)^T omega is tangent by construction, so only p is normalized.
//
// CVODE's error estimate (`err`, when CVodeSetProjErrEst is on) loses its component normal to
// the manifold in the generalized form only. In the quasi-velocity form p's normal error is
// kept: there |p| is invariant under the exact flow, so the radial part of a step's error is
// pure truncation error of the same order as its tangential (phase) part, and the best measure
// of it. Projected away, the estimate misjudged BDF's steps: a body spinning at 2 rad/s about its
// major axis (8.5 s, rtol = atol = 1e-10) took 15815 steps to an attitude error of 1.7e-6 rad,
// against 300 steps and 5.7e-9 rad with the normal part kept (tests/integrate/
// quasi_velocities.test.cpp). In the generalized form, where the normal error of p and pdot also
// carries the drift of p.pdot, projecting it measured as good or better (that spinner from the
// identity: 298 against 318 steps; the tumbling body at 1e-10: 5e-5 against 2e-4 rad).

#include <type_traits>

#include "tumble/core/types.hpp"
#include "tumble/scene/scene.hpp"

namespace tumble {

/// The correction `corr` that takes y onto the manifold: p -> p/|p| and pdot -> pdot - (p.pdot) p
/// (the orthogonal projection; p -> p/|p| alone in the quasi-velocity form); zero elsewhere. When
/// `err` is not empty (the local error estimate) its component normal to the manifold is removed
/// too, as CVODE's projection expects, in the generalized form; the quasi-velocity form keeps it
/// whole (above).
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

/// The same map applied to y in place, without an error estimate: p -> p/|p| and, in the
/// generalized form, pdot -> pdot - (pn.pdot) pn with pn the new p. What an explicit integrator
/// applies after each step: no correction vector to clear and add back (adding p/|p| - p to p
/// rounds twice), and nothing for a body without the constraint.
template <class SceneT, class Y> void project_in_place(const SceneT& scene, Y& y) {
  scene.for_each_entry([&](const auto& e) {
    using Body = std::remove_cvref_t<decltype(e.body)>;
    if constexpr (Body::Param::has_constraint) {
      auto p = y.template segment<4>(e.offset + e.theta_at);
      p /= p.norm();
      if constexpr (!std::remove_cvref_t<decltype(e)>::quasi) {
        auto pd = y.template segment<4>(e.rates + e.theta_at);
        pd -= p.dot(pd) * p;
      }
    }
  });
}

}  // namespace tumble
