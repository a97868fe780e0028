#pragma once
// The per-body pieces that the scene's algorithms share, in any scalar type (double in the
// right-hand side and the observables, Jet<N> in the Jacobian): a body's kinematics from its
// coordinates, its rates and its chart base, and the rate of its block of the state with the
// constraint stabilization of Euler parameters, for either state form (state.hpp).

#include <cmath>
#include <cstddef>
#include <type_traits>

#include "tumble/body/kinematics.hpp"
#include "tumble/body/rigid_body.hpp"
#include "tumble/body/wrench.hpp"
#include "tumble/core/math.hpp"
#include "tumble/core/types.hpp"
#include "tumble/scene/chart.hpp"
#include "tumble/scene/state.hpp"

namespace tumble::detail {

/// The kinematics loads read, Eqs. (1.1), (1.4)-(1.5): the mass properties, r_oc, rdot_oc,
/// omega and, when with_rotation, R = R0 R(theta) with the chart base R0, from `body` (in the
/// scalar of k), its coordinates q and its rates in the state form Form: qd = qdot (omega = G
/// thetadot, Eq. 1.5) or qd = [v; omega] (omega read as is, no G). A body held at a fixed point
/// has q = theta and qd = thetadot or omega: r_oc is its fixed point and rdot_oc = 0. Forced
/// inline: GCC 12 left it out of line in the right-hand side, which cost 35% of an offset
/// Euler-parameter right-hand side (150 -> 202 ns; 151 ns inlined).
/// `theta_functions`: where to keep, in the [q; qdot] form, the functions of theta that omega
/// used (P::Precomputed: the trigonometric functions of Euler angles, the series of the rotation
/// vector), for body_accelerations_into to use again; nullptr (the default) keeps nothing.
template <StateForm Form, class Body, class Q, class Qd, class S, class Pre = std::nullptr_t>
[[gnu::always_inline]] inline void body_kinematics(const Body& body, const Q& q, const Qd& qd,
                                                   const Matrix3<double>& base, bool with_rotation,
                                                   BodyKinematics<S, Body::reference>& k,
                                                   [[maybe_unused]] Pre theta_functions = nullptr) {
  using P = typename Body::Param;
  const typename P::template Coords<S> th = q.template tail<Body::n_theta>();
  k.mass_properties = &body.mass_properties();
  if constexpr (Body::fixed) {
    k.position = body.fixed_point();
    k.velocity.setZero();
  } else {
    k.position = q.template head<3>();
    k.velocity = qd.template head<3>();
  }
  if constexpr (Form == StateForm::quasi_velocities) {
    k.omega = qd.template tail<3>();
    if (with_rotation) {
      k.rotation = P::rotation(th);
    }
  } else {
    // omega and R share the functions of theta (orientation/concept.hpp): evaluated once.
    const typename P::template Precomputed<S> pre = P::precompute(th);
    const typename P::template Coords<S> thd = qd.template tail<Body::n_theta>();
    k.omega = P::omega(pre, thd);
    if (with_rotation) {
      k.rotation = P::rotation(pre);
    }
    if constexpr (!std::is_null_pointer_v<Pre>) {
      *theta_functions = pre;
    }
  }
  if (with_rotation) {
    if constexpr (Chart<P>::has_singularity) {  // Euler parameters never leave their chart
      k.rotation = (base.template cast<S>() * k.rotation).eval();
    }
  }
}

/// w as a Wrench: NoWrench as a zero one, for the cold paths that name a non-finite rate's cause.
template <class S, class W> Wrench<S> as_wrench(const W& w) {
  if constexpr (std::is_same_v<W, NoWrench>) {
    return Wrench<S>{};
  } else {
    return w;
  }
}

/// qddot of `body` (Eq. 1.32 through RigidBody::accelerations) for the wrench w (or NoWrench: no
/// load at all), written into
/// qdd (a writable vector of size nq, such as the body's block of y'). For Euler parameters with
/// `stabilize`, the constraint acceleration is Baumgarte-stabilized:
///   p.pddot = -|pdot|^2 - 2 g (p.pdot) - g^2 (|p|^2 - 1)/2,  g = |omega|,
/// so that a drift of |p| = 1 decays on the body's own time scale without adding stiffness (used
/// with Adams, which cannot project; BDF projects instead).
/// qddot comes from the body's public pieces (velocity_rates_into, P::thetaddot of Eq. 1.10)
/// straight into qdd: a temporary between them cost a fifth of an explicit run on one body
/// (RigidBody::velocity_rates_into). Checked: a non-finite result throws NonFiniteError, naming
/// its cause, through RigidBody::accelerations (the same values, computed again on that cold
/// path); else unchecked, for a caller that checks the results itself (rhs.hpp,
/// FiniteCheck::by_caller). `theta_functions`: those body_kinematics kept at this q (thetaddot
/// then evaluates no function of theta again), or nullptr (the default: evaluated here).
template <bool Checked = true, class JBody, class W, class Qdd, class Pre = std::nullptr_t>
[[gnu::always_inline]] inline void body_accelerations_into(
    const JBody& body, const typename JBody::Coords& q, const typename JBody::Coords& qd,
    const typename JBody::Kinematics& k, const W& w, [[maybe_unused]] bool stabilize, Qdd&& qdd,
    [[maybe_unused]] Pre theta_functions = nullptr) {
  using S = typename JBody::Scalar;
  using Theta = typename JBody::Theta;
  const Theta th = q.template tail<JBody::n_theta>();
  Vector3<S> alpha;
  if constexpr (JBody::fixed) {
    Vector3<S> none;  // not written: a body held at a fixed point has no a_c
    body.velocity_rates_into(k, w, none, alpha);
  } else {
    body.velocity_rates_into(k, w, qdd.template head<3>(), alpha);
  }
  const Theta thd = qd.template tail<JBody::n_theta>();
  if constexpr (std::is_null_pointer_v<Pre>) {  // Eq. (1.10) solved for thetaddot
    qdd.template tail<JBody::n_theta>() = JBody::Param::thetaddot(th, thd, alpha);
  } else {
    qdd.template tail<JBody::n_theta>() = JBody::Param::thetaddot(*theta_functions, thd, alpha);
  }
  if constexpr (Checked) {
    if (!detail::all_finite_fast(qdd)) [[unlikely]] {
      qdd = body.accelerations(q, qd, k, as_wrench<S>(w));  // the same: throws, naming the cause
    }
  }
  if constexpr (JBody::Param::has_constraint) {
    if (stabilize) {
      // The body imposed p.pddot = -|pdot|^2 assuming |p| = 1; add the difference along p.
      using std::sqrt;
      const Vector4<S> p = q.template tail<4>();
      const Vector4<S> pd = qd.template tail<4>();
      const S pp = p.squaredNorm();
      const S g2 = k.omega.squaredNorm();
      // g = |omega| is not differentiable at omega = 0, where its jet would be 0/0: take the
      // one-sided derivative 0 there (the term 2 g (p.pdot) vanishes on the manifold anyway).
      S g = S(0);
      if (detail::value(g2) > 0) {
        g = sqrt(g2);
      }
      const S nu = -(pd.squaredNorm() + S(2) * g * p.dot(pd) + S(0.5) * g2 * (pp - S(1))) / pp;
      qdd.template tail<4>() += (nu + pd.squaredNorm()) * p;
    }
  }
}

/// The same, returned.
template <bool Checked = true, class JBody>
[[gnu::always_inline]] inline Vector<typename JBody::Scalar, JBody::nq> body_accelerations(
    const JBody& body, const typename JBody::Coords& q, const typename JBody::Coords& qd,
    const typename JBody::Kinematics& k, const Wrench<typename JBody::Scalar>& w, bool stabilize) {
  typename JBody::Coords qdd;
  body_accelerations_into<Checked>(body, q, qd, k, w, stabilize, qdd);
  return qdd;
}

/// The rate of body's quasi-velocity block x = [r_oc; theta; v; omega] (RigidBody::quasi_rates):
/// [v; P::thetadot(theta, omega); a_c; alpha], for the wrench w and the kinematics k at x (held at
/// a fixed point: x = [theta; omega], its rate [P::thetadot(theta, omega); alpha]), written into
/// xd (a writable vector of size nx, such as the body's block of y').
///
/// Euler parameters with `stabilize` (Adams, which cannot project): pdot = 1/2 L(p)^T omega is
/// tangent to every sphere |p| = const (p.L(p)^T omega = 0 for any p), so |p| is kept in exact
/// arithmetic only, and the integrator's local errors make it drift as a random walk. A
/// first-order correction along p pulls it back:
///   pdot += -(g/2) (|p|^2 - 1) p,   g = |omega|.
/// Then with c = |p|^2 - 1, dc/dt = 2 p.pdot = -g |p|^2 c = -g (1 + c) c: the drift decays at the
/// rate g near the manifold, the body's own angular rate, so the correction adds no time scale
/// faster than the motion itself (no stiffness for Adams) and vanishes on the manifold (the
/// physics is unchanged). A tumbling body has g > 0; at rest nothing moves and nothing drifts.
/// With BDF the integrator projects instead (projection.hpp), and stabilize is false.
/// Forced inline, as body_kinematics: GCC 12 called it out of line from the right-hand side, where
/// it took a fifth of an explicit run's time (perf, Odeint Fehlberg 7(8) on one body).
/// The rate comes from the body's public pieces (velocity_rates_into, P::thetadot) straight into
/// xd; Checked: a non-finite result throws through RigidBody::quasi_rates, as for
/// body_accelerations_into.
template <bool Checked = true, class JBody, class W, class Xd>
[[gnu::always_inline]] inline void body_quasi_rates_into(const JBody& body,
                                                         const typename JBody::Coords& q,
                                                         const typename JBody::Kinematics& k,
                                                         const W& w,
                                                         [[maybe_unused]] bool stabilize, Xd&& xd) {
  using S = typename JBody::Scalar;
  const typename JBody::Theta th = q.template tail<JBody::n_theta>();
  xd.template segment<JBody::n_theta>(JBody::n_r) = JBody::Param::thetadot(th, k.omega);
  if constexpr (JBody::fixed) {
    Vector3<S> none;  // not written: a body held at a fixed point has no a_c
    body.velocity_rates_into(k, w, none, xd.template tail<3>());
  } else {
    xd.template head<3>() = k.velocity;
    body.velocity_rates_into(k, w, xd.template segment<3>(JBody::nq), xd.template tail<3>());
  }
  if constexpr (Checked) {
    if (!detail::all_finite_fast(xd)) [[unlikely]] {
      xd = body.quasi_rates(q, k, as_wrench<S>(w));  // the same values: throws, naming the cause
    }
  }
  if constexpr (JBody::Param::has_constraint) {
    if (stabilize) {
      using std::sqrt;
      const Vector4<S> p = q.template tail<4>();
      const S g2 = k.omega.squaredNorm();
      // g = |omega| is not differentiable at omega = 0, where its jet would be 0/0: take the
      // one-sided derivative 0 there (the correction vanishes on the manifold anyway).
      S g = S(0);
      if (detail::value(g2) > 0) {
        g = sqrt(g2);
      }
      xd.template segment<4>(JBody::n_r) -= (S(0.5) * g * (p.squaredNorm() - S(1))) * p;
    }
  }
}

/// The same, returned.
template <bool Checked = true, class JBody>
[[gnu::always_inline]] inline Vector<typename JBody::Scalar, JBody::nx> body_quasi_rates(
    const JBody& body, const typename JBody::Coords& q, const typename JBody::Kinematics& k,
    const Wrench<typename JBody::Scalar>& w, bool stabilize) {
  typename JBody::QuasiCoords xd;
  body_quasi_rates_into<Checked>(body, q, k, w, stabilize, xd);
  return xd;
}

}  // namespace tumble::detail
