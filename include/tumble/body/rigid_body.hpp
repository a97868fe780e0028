#pragma once
// RigidBody<P, Ref, S>: the equations of motion of one free rigid body in the generalized
// coordinates q = [r_oc (3, inertial); theta (P::size)], exactly as derived in the reference
// chapter (Chapter 1, "Rigid body", Sec. 1.1-1.4):
//   point kinematics    Eqs. (1.1), (1.7)-(1.8), (1.11)-(1.12)
//   mass matrix M       Eqs. (1.21)-(1.23)
//   f_v                 Eqs. (1.26)-(1.27)
//   generalized force Q Eqs. (1.28)-(1.31)
//   M qddot = f_v + Q   Eq. (1.32), simplified at the centroid by Eq. (1.33)
//
// The accelerations are not found by factorizing M. Because M qddot = f_v + Q is the principle of
// virtual work written in the coordinates q, it is equivalent to the Newton-Euler equations of the
// body, which have a closed-form solution: with the wrench (F inertial, M_c body) reduced to c,
//   alpha = I_g^{-1} (M_c - r_g x F^f - omega x I_g omega)        (moment about the centroid)
//   a_c   = F/m - R (alpha x r_g + omega x (omega x r_g))           (centroid accelerates as F/m)
// and thetaddot follows from alpha = G thetaddot + Gdot thetadot (Eq. 1.10) through the
// parameterization (P::thetaddot), which for Euler parameters also imposes p.pddot = -|pdot|^2,
// the second derivative of the constraint |p| = 1 (the solution of the constrained system).
// At the centroid (Ref == centroid) r_g = 0, and the coupling terms are not computed at all.
//
// Held at a fixed point (Ref == fixed_point) the reference point c does not move (r_oc = const,
// rdot_oc = 0): q = theta alone. The theta-rows of Eq. (1.32) with rddot_oc = 0,
//   G^T I_c G thetaddot = f_v^theta + G^T M_c,
// are then the exact equations of motion (the reaction at c does no virtual work on theta), with
// the closed form alpha = I_c^{-1} (M_c - omega x I_c omega) about c; the r-rows,
//   m12 thetaddot = f_v^r + F + F_R,
// give the reaction force F_R (reaction_force). No translational term is computed.
//
// The pair (a_c, alpha) is public (velocity_rates): it is the whole right-hand side of the
// quasi-velocity state [r_oc; theta; v; omega] (quasi_rates), where rdot_oc = v, thetadot comes
// from the inverse map P::thetadot(theta, omega), vdot = a_c and omegadot = alpha; neither
// thetaddot nor Gdot thetadot is formed there.

#include <concepts>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>

#include <Eigen/Cholesky>

#include "tumble/body/kinematics.hpp"
#include "tumble/body/mass_properties.hpp"
#include "tumble/body/wrench.hpp"
#include "tumble/core/errors.hpp"
#include "tumble/core/math.hpp"
#include "tumble/core/types.hpp"
#include "tumble/orientation/concept.hpp"

namespace tumble {

/// The velocity rates of a body (Newton-Euler, see the file comment): the acceleration of the
/// reference point c, inertial components (a_c = rddot_oc), and the angular acceleration alpha,
/// body components (alpha = omegadot, Eq. 1.10).
template <class S> struct VelocityRates {
  Vector3<S> acceleration;
  Vector3<S> alpha;
};

namespace detail {
/// True when Gdot thetadot is identically zero for P (Euler parameters), so that it is skipped.
template <class P> constexpr bool gdot_vanishes() {
  if constexpr (requires { P::gdot_vanishes; }) {
    return P::gdot_vanishes;
  } else {
    return false;
  }
}
}  // namespace detail

template <Orientation P, ReferencePoint Ref = ReferencePoint::centroid, class S = double>
class RigidBody {
 public:
  using Param = P;
  using Scalar = S;
  static constexpr ReferencePoint reference = Ref;
  static constexpr bool at_centroid = Ref == ReferencePoint::centroid;
  static constexpr bool fixed = Ref == ReferencePoint::fixed_point;
  static constexpr int n_theta = P::size;
  static constexpr int n_r = fixed ? 0 : 3;  ///< translational coordinates: r_oc, none when fixed
  static constexpr int nq = n_r + n_theta;   ///< size of q (and of qdot)
  static constexpr int nv = n_r + 3;         ///< quasi-velocities: [v; omega], or omega alone
  static constexpr int nx = nq + nv;         ///< size of the quasi-velocity state [q; v; omega]

  using Theta = typename P::template Coords<S>;
  /// What R, G, Gdot thetadot and the inverse map share at one attitude (orientation/concept.hpp):
  /// every function below evaluates it once per call and passes it through.
  using Precomputed = typename P::template Precomputed<S>;
  using Coords = Vector<S, nq>;            ///< q, qdot, qddot, f_v, Q
  using MassMatrix = Matrix<S, nq, nq>;    ///< M (Eq. 1.23)
  using PointJacobian = Matrix<S, 3, nq>;  ///< L_r (Eq. 1.8)
  using Kinematics = BodyKinematics<S, Ref>;
  using QuasiCoords = Vector<S, nx>;  ///< [r_oc; theta; v; omega] (fixed: [theta; omega])

  /// \throws std::invalid_argument if Ref is centroid but the mass properties put the centroid
  ///         away from the reference point.
  explicit RigidBody(MassProperties<S> mass_properties) requires(!fixed)
      : mp_(std::move(mass_properties)) {
    if constexpr (at_centroid) {
      if (!(detail::value(mp_.centroid().squaredNorm()) == 0)) {
        throw std::invalid_argument(
            "tumble::RigidBody: a body framed at its centroid (ReferencePoint::centroid) needs a "
            "zero centroid offset; use ReferencePoint::offset for a body frame away from it");
      }
    }
  }

  /// A body held at its reference point c, which sits at `fixed_point` (r_oc, inertial
  /// components) for all time.
  /// \throws std::invalid_argument for a non-finite fixed point.
  RigidBody(MassProperties<S> mass_properties, const Vector3<S>& fixed_point) requires fixed
      : mp_(std::move(mass_properties)),
        pivot_(fixed_point) {
    if (!detail::all_finite(fixed_point)) {
      throw std::invalid_argument("tumble::RigidBody: the fixed point has a non-finite entry");
    }
  }
  /// The same, held at the inertial origin.
  explicit RigidBody(MassProperties<S> mass_properties) requires fixed
      : mp_(std::move(mass_properties)) {}  // not delegating: see pivot_

  /// The same body in another scalar type (for example Jet<N>, to differentiate).
  template <class T>
  requires(!std::is_same_v<T, S>) explicit RigidBody(const RigidBody<P, Ref, T>& other)
      : mp_(other.mass_properties()) {
    if constexpr (fixed) {
      pivot_ = other.fixed_point().template cast<S>();
    }
  }

  [[nodiscard]] const MassProperties<S>& mass_properties() const { return mp_; }
  /// Where the reference point c is held, inertial components (fixed_point only).
  [[nodiscard]] const Vector3<S>& fixed_point() const requires fixed { return pivot_; }

  // --- pieces of the state --------------------------------------------------------------------
  /// r_oc, from q; for a body held at a fixed point, that point (a member function there).
  [[nodiscard]] static Vector3<S> position(const Coords& q) requires(!fixed) {
    return q.template head<3>();
  }
  [[nodiscard]] Vector3<S> position(const Coords& /*q*/) const requires fixed { return pivot_; }
  [[nodiscard]] static Theta theta(const Coords& q) { return q.template tail<n_theta>(); }
  [[nodiscard]] static Matrix3<S> rotation(const Coords& q) { return P::rotation(theta(q)); }
  /// omega = G thetadot, body components (Eq. 1.5).
  [[nodiscard]] static Vector3<S> omega(const Coords& q, const Coords& qdot) {
    return angular_velocity<P, S>(theta(q), qdot.template tail<n_theta>());
  }
  /// qdot for a given velocity of the reference point (inertial) and omega (body): the inverse
  /// map of the parameterization. A fixed body has no velocity coordinates: `velocity` (zero) is
  /// not read.
  [[nodiscard]] static Coords qdot_from(const Coords& q,
                                        [[maybe_unused]] const Vector3<S>& velocity,
                                        const Vector3<S>& omega_body) {
    Coords qd;
    if constexpr (fixed) {
      qd = P::thetadot(theta(q), omega_body);
    } else {
      qd << velocity, P::thetadot(theta(q), omega_body);
    }
    return qd;
  }

  // --- point kinematics -----------------------------------------------------------------------
  /// Eq. (1.1): r_op = r_oc + R r_cp, with r_cp = `r` in body components (a member function
  /// for a body held at a fixed point, whose r_oc is its own).
  [[nodiscard]] static Vector3<S> point_position(const Coords& q,
                                                 const Vector3<S>& r) requires(!fixed) {
    return q.template head<3>() + rotation(q) * r;  // not position(q): see pivot_
  }
  [[nodiscard]] Vector3<S> point_position(const Coords& q,
                                          const Vector3<S>& r) const requires fixed {
    return pivot_ + rotation(q) * r;
  }
  /// Eq. (1.8): L_r = [I, -R S(r) G] (fixed: -R S(r) G).
  [[nodiscard]] static PointJacobian point_jacobian(const Coords& q, const Vector3<S>& r) {
    const Precomputed pre = P::precompute(theta(q));
    PointJacobian l;
    if constexpr (!fixed) {
      l.template leftCols<3>().setIdentity();
    }
    l.template rightCols<n_theta>() = -P::rotation(pre) * (skew(r) * P::G(pre));
    return l;
  }
  /// Eq. (1.7): rdot_op = L_r qdot = rdot_oc + R (omega x r) (rdot_oc = 0 when fixed).
  [[nodiscard]] static Vector3<S> point_velocity(const Coords& q, const Coords& qdot,
                                                 const Vector3<S>& r) {
    const Precomputed pre = P::precompute(theta(q));
    const Vector3<S> v =
        P::rotation(pre) * P::omega(pre, Theta(qdot.template tail<n_theta>())).cross(r);
    if constexpr (fixed) {
      return v;
    } else {
      return qdot.template head<3>() + v;
    }
  }
  /// Eq. (1.11): a_v = R [S(omega)^2 r - S(r) Gdot thetadot].
  [[nodiscard]] static Vector3<S> point_velocity_acceleration(const Coords& q, const Coords& qdot,
                                                              const Vector3<S>& r) {
    const Precomputed pre = P::precompute(theta(q));
    const Theta thd = qdot.template tail<n_theta>();
    const Vector3<S> w = P::omega(pre, thd);
    Vector3<S> a = w.cross(w.cross(r));
    if constexpr (!detail::gdot_vanishes<P>()) {
      a -= r.cross(P::Gdot_thetadot(pre, thd));
    }
    return P::rotation(pre) * a;
  }
  /// Eq. (1.12): rddot_op = L_r qddot + a_v.
  [[nodiscard]] static Vector3<S> point_acceleration(const Coords& q, const Coords& qdot,
                                                     const Coords& qddot, const Vector3<S>& r) {
    return point_jacobian(q, r) * qddot + point_velocity_acceleration(q, qdot, r);
  }

  // --- the terms of Eq. (1.32) ----------------------------------------------------------------
  /// Eq. (1.23): M = [m I, m12; m21, G^T I_c G], m12 = -R S(m r_g) G (Eq. 1.21b), zero at the
  /// centroid (Eq. 1.33). For Euler parameters M is singular with null vector [0; p]. Fixed:
  /// the theta-block G^T I_c G alone.
  [[nodiscard]] MassMatrix mass_matrix(const Coords& q) const {
    const Precomputed pre = P::precompute(theta(q));
    const Matrix<S, 3, n_theta> g = P::G(pre);
    MassMatrix m;
    m.template bottomRightCorner<n_theta, n_theta>() =
        g.transpose() * mp_.inertia_reference() * g;  // Eq. (1.21c), (1.22)
    if constexpr (!fixed) {
      m.template topLeftCorner<3, 3>() = mp_.mass() * Matrix3<S>::Identity();
      if constexpr (at_centroid) {
        m.template topRightCorner<3, n_theta>().setZero();
        m.template bottomLeftCorner<n_theta, 3>().setZero();
      } else {
        const Matrix<S, 3, n_theta> m12 = -P::rotation(pre) * (skew(mp_.first_moment()) * g);
        m.template topRightCorner<3, n_theta>() = m12;  // Eq. (1.21b)
        m.template bottomLeftCorner<n_theta, 3>() = m12.transpose();
      }
    }
    return m;
  }

  /// Eqs. (1.26)-(1.27): f_v = [f_v^r; f_v^theta] with
  ///   f_v^r     = -R S(omega)^2 (m r_g) + R S(m r_g) Gdot thetadot   (zero at the centroid)
  ///   f_v^theta = -G^T [S(omega) I_c omega + I_c Gdot thetadot]
  /// (f_v^theta alone when fixed).
  [[nodiscard]] Coords centrifugal_coriolis(const Coords& q, const Coords& qdot) const {
    const Precomputed pre = P::precompute(theta(q));
    const Theta thd = qdot.template tail<n_theta>();
    const Matrix<S, 3, n_theta> g = P::G(pre);
    const Vector3<S> w = P::omega(pre, thd);
    const Matrix3<S>& ic = mp_.inertia_reference();
    Vector3<S> inner = w.cross(ic * w);
    Vector3<S> gdot_thd = Vector3<S>::Zero();
    if constexpr (!detail::gdot_vanishes<P>()) {
      gdot_thd = P::Gdot_thetadot(pre, thd);
      inner += ic * gdot_thd;
    }
    Coords f;
    f.template tail<n_theta>() = -(g.transpose() * inner);  // Eq. (1.27)
    if constexpr (at_centroid) {
      f.template head<3>().setZero();  // Eq. (1.33)
    } else if constexpr (!fixed) {
      const Vector3<S>& s = mp_.first_moment();
      f.template head<n_r>() =
          P::rotation(pre) * (-w.cross(w.cross(s)) + s.cross(gdot_thd));  // Eq. (1.26)
    }
    return f;
  }

  /// Eq. (1.31): Q = [F; G^T M_c] for the wrench reduced to c (fixed: G^T M_c, the force at c
  /// does no virtual work).
  [[nodiscard]] static Coords generalized_force(const Coords& q, const Wrench<S>& w) {
    Coords f;
    if constexpr (fixed) {
      f = P::G(theta(q)).transpose() * w.moment;
    } else {
      f << w.force, P::G(theta(q)).transpose() * w.moment;
    }
    return f;
  }

  /// The wrench whose generalized force is Q: F = Q^r and M_c = (G G^T)^{-1} G Q^theta (= G^{-T}
  /// Q^theta for three-parameter sets). For Euler parameters the component of Q^theta along p is
  /// a constraint force and does no work: it is dropped, as the constrained system does. A fixed
  /// body's Q has no force rows: the force is zero.
  [[nodiscard]] static Wrench<S> wrench_from(const Coords& q, const Coords& gen_force) {
    const Matrix<S, 3, n_theta> g = P::G(theta(q));
    Wrench<S> w;
    if constexpr (!fixed) {
      w.force = gen_force.template head<3>();
    }
    w.moment = (g * g.transpose()).ldlt().solve(g * gen_force.template tail<n_theta>());
    return w;
  }

  /// The kinematic quantities force elements read. R is computed only when `with_rotation`
  /// (force elements declare at compile time whether they need it).
  template <bool with_rotation = true>
  [[nodiscard]] Kinematics kinematics(const Coords& q, const Coords& qdot) const {
    Kinematics k;
    k.mass_properties = &mp_;
    k.position = position(q);
    if constexpr (!fixed) {
      k.velocity = qdot.template head<3>();
    }
    const Precomputed pre = P::precompute(theta(q));
    k.omega = P::omega(pre, Theta(qdot.template tail<n_theta>()));
    if constexpr (with_rotation || !at_centroid) {
      k.rotation = P::rotation(pre);
    }
    return k;
  }

  /// qddot from M qddot = f_v + Q (Eq. 1.32; Eq. 1.33 at the centroid) for the loads reduced to
  /// the wrench `w`, through the Newton-Euler closed form described at the top of this file.
  /// \throws NonFiniteError when the result is not finite (non-finite state or load, or an
  ///         attitude exactly at a singularity of P).
  [[nodiscard]] Coords accelerations(const Coords& q, const Coords& qdot,
                                     const Wrench<S>& w) const {
    const Precomputed pre = P::precompute(theta(q));
    const Theta thd = qdot.template tail<n_theta>();
    const Vector3<S> om = P::omega(pre, thd);
    return accelerations_impl(q, pre, thd, om, w, nullptr);
  }

  /// qddot from M qddot = f_v + Q for a generalized force Q (Eq. 1.32).
  [[nodiscard]] Coords accelerations(const Coords& q, const Coords& qdot,
                                     const Coords& gen_force) const {
    return accelerations(q, qdot, wrench_from(q, gen_force));
  }

  /// The same, for a body and its kinematics already evaluated (the scene's hot path).
  [[nodiscard]] Coords accelerations(const Coords& q, const Coords& qdot, const Kinematics& k,
                                     const Wrench<S>& w) const {
    return accelerations_impl(q, P::precompute(theta(q)), Theta(qdot.template tail<n_theta>()),
                              k.omega, w, &k.rotation);
  }

  /// The velocity rates (a_c inertial, alpha body) for the attitude theta, the angular velocity
  /// omega (body) and the wrench w reduced to c: the Newton-Euler closed form of the file comment,
  /// equivalent to M qddot = f_v + Q (Eq. 1.32; Eq. 1.33 at the centroid). Not checked for
  /// finiteness: accelerations() and quasi_rates() check their whole result.
  [[nodiscard]] VelocityRates<S> velocity_rates(const Theta& th, const Vector3<S>& om,
                                                const Wrench<S>& w) const {
    return velocity_rates_impl([&] { return P::rotation(th); }, om, w);
  }
  /// The same for a body whose kinematics are evaluated (omega and, off the centroid, R from k;
  /// R may include a chart base).
  [[nodiscard]] VelocityRates<S> velocity_rates(const Theta& /*th*/, const Kinematics& k,
                                                const Wrench<S>& w) const {
    return velocity_rates_impl([&] { return k.rotation; }, k.omega, w);
  }
  /// The same, written into `acceleration` and `alpha` (writable 3-vectors or segments of one,
  /// such as the blocks of a state's rate): the scene's hot path. `acceleration` is not written
  /// for a body held at a fixed point (its a_c is zero and has no place in the state). Returned
  /// as a VelocityRates, the pair stayed in memory under GCC 12 -O3 even inlined, and each rate
  /// went through the stack on its way to y': 1.2x the time of an explicit run on one body
  /// (docs/benchmarks/floors.md, 2026-12-02). w = NoWrench{}: a body nothing loads, the wrench's
  /// terms left out.
  template <class W, class Acceleration, class Alpha>
  requires std::same_as<W, Wrench<S>> || std::same_as<W, NoWrench>
  [[gnu::always_inline]] void velocity_rates_into(const Kinematics& k, const W& w,
                                                  Acceleration&& acceleration,
                                                  Alpha&& alpha) const {
    rates_into([&] { return k.rotation; }, k.omega, w, acceleration, alpha);
  }

  /// The part of velocity_rates that is linear in the wrench: (a_c, alpha) for the wrench w at
  /// rest (omega = 0), with the attitude `rotation` (read off the centroid only): Eq. (1.32)
  /// through the file comment's closed form without its omega terms (Eq. 1.33 at the centroid).
  /// It is the
  /// inverse of the body's mass matrix in the velocities [v; omega], applied to w (its dual): what
  /// a joint's reaction -J^T lambda does to the body's accelerations (scene/joints.hpp). Zero
  /// translational acceleration for a body held at a fixed point.
  [[nodiscard]] VelocityRates<S> wrench_response(const Matrix3<S>& rotation,
                                                 const Wrench<S>& w) const {
    return velocity_rates_impl([&] { return rotation; }, Vector3<S>::Zero(), w);
  }

  /// Eq. (1.10): alpha = G thetaddot + Gdot thetadot, the angular acceleration in body
  /// components, from the generalized accelerations (e.g. those of accelerations()).
  [[nodiscard]] static Vector3<S> angular_acceleration(const Coords& q, const Coords& qdot,
                                                       const Coords& qddot) {
    const Precomputed pre = P::precompute(theta(q));
    Vector3<S> a = P::omega(pre, Theta(qddot.template tail<n_theta>()));
    if constexpr (!detail::gdot_vanishes<P>()) {
      a += P::Gdot_thetadot(pre, Theta(qdot.template tail<n_theta>()));
    }
    return a;
  }

  /// The force the support exerts on a body held at c (fixed_point), inertial components, for the
  /// attitude `rotation` (R, body -> inertial), omega (body) and the applied wrench w reduced to
  /// c: the r-rows of Eq. (1.32) with rddot_oc = 0, F_R = m12 thetaddot - f_v^r - F, which by
  /// Eqs. (1.21b), (1.26) and (1.10) is
  ///   F_R = R [alpha x m r_g + omega x (omega x m r_g)] - F = m a_g - F,
  /// with alpha from the theta-rows (velocity_rates): what the applied force F leaves of m a_g.
  [[nodiscard]] Vector3<S> reaction_force(const Matrix3<S>& rotation, const Vector3<S>& om,
                                          const Wrench<S>& w) const requires fixed {
    const Vector3<S> alpha = velocity_rates_impl([&] { return rotation; }, om, w).alpha;
    const Vector3<S>& s = mp_.first_moment();
    const Vector3<S> ab = alpha.cross(s) + om.cross(om.cross(s));
    return rotation * ab - w.force;
  }

  /// The rate of the quasi-velocity state x = [r_oc; theta; v; omega]:
  ///   xdot = [v; P::thetadot(theta, omega); a_c; alpha]
  /// (fixed: x = [theta; omega], xdot = [P::thetadot(theta, omega); alpha])
  /// (the inverse map of Eq. 1.5, then velocity_rates). For Euler parameters thetadot is tangent
  /// to |p| = 1 whatever |p| (p.L(p)^T omega = 0).
  /// \throws NonFiniteError when the result is not finite.
  [[nodiscard]] QuasiCoords quasi_rates(const QuasiCoords& x, const Wrench<S>& w) const {
    const Theta th = x.template segment<n_theta>(n_r);
    const Vector3<S> om = x.template tail<3>();
    Vector3<S> v = Vector3<S>::Zero();
    if constexpr (!fixed) {
      v = x.template segment<3>(nq);
    }
    const Precomputed pre = P::precompute(th);
    return quasi_rates_impl(x.template head<nq>(), pre, v, om,
                            velocity_rates_impl([&] { return P::rotation(pre); }, om, w), w);
  }
  /// The same, for a body and its kinematics already evaluated (the scene's hot path: v and omega
  /// are read from k).
  [[nodiscard]] QuasiCoords quasi_rates(const Coords& q, const Kinematics& k,
                                        const Wrench<S>& w) const {
    return quasi_rates_impl(q, P::precompute(theta(q)), k.velocity, k.omega,
                            velocity_rates_impl([&] { return k.rotation; }, k.omega, w), w);
  }

  // --- energy and momenta ---------------------------------------------------------------------
  /// T = 1/2 qdot^T M qdot = 1/2 m |v_g|^2 + 1/2 omega . I_g omega.
  [[nodiscard]] S kinetic_energy(const Coords& q, const Coords& qdot) const {
    const Vector3<S> vg = centroid_velocity(q, qdot);
    const Vector3<S> w = omega(q, qdot);
    return S(0.5) * (mp_.mass() * vg.squaredNorm() + w.dot(mp_.inertia_centroid() * w));
  }
  /// Velocity of the centroid, inertial components.
  [[nodiscard]] Vector3<S> centroid_velocity(const Coords& q, const Coords& qdot) const {
    if constexpr (at_centroid) {
      return qdot.template head<3>();
    } else {
      return point_velocity(q, qdot, mp_.centroid());
    }
  }
  /// Position of the centroid, inertial components.
  [[nodiscard]] Vector3<S> centroid_position(const Coords& q) const {
    if constexpr (at_centroid) {
      return q.template head<3>();
    } else {
      return point_position(q, mp_.centroid());
    }
  }
  /// Linear momentum m v_g, inertial components.
  [[nodiscard]] Vector3<S> linear_momentum(const Coords& q, const Coords& qdot) const {
    return mp_.mass() * centroid_velocity(q, qdot);
  }
  /// Angular momentum about the centroid, body components: I_g omega.
  [[nodiscard]] Vector3<S> angular_momentum_centroid(const Coords& q, const Coords& qdot) const {
    return mp_.inertia_centroid() * omega(q, qdot);
  }
  /// Angular momentum about the inertial origin O, inertial components:
  /// r_og x m v_g + R I_g omega.
  [[nodiscard]] Vector3<S> angular_momentum(const Coords& q, const Coords& qdot) const {
    return centroid_position(q).cross(linear_momentum(q, qdot)) +
           rotation(q) * angular_momentum_centroid(q, qdot);
  }

 private:
  /// rot: R when the caller has it (the kinematics of a scene), else nullptr (from pre).
  Coords accelerations_impl(const Coords& q, const Precomputed& pre, const Theta& thd,
                            const Vector3<S>& om, const Wrench<S>& w, const Matrix3<S>* rot) const {
    const VelocityRates<S> vr =
        velocity_rates_impl([&] { return rot ? Matrix3<S>(*rot) : P::rotation(pre); }, om, w);
    Coords qdd;
    if constexpr (!fixed) {
      qdd.template head<3>() = vr.acceleration;
    }
    qdd.template tail<n_theta>() = P::thetaddot(pre, thd, vr.alpha);  // Eq. (1.10)
    if (!detail::all_finite_fast(qdd)) [[unlikely]] {
      throw_non_finite(q, w);
    }
    return qdd;
  }

  QuasiCoords quasi_rates_impl(const Coords& q, const Precomputed& pre, const Vector3<S>& v,
                               const Vector3<S>& om, const VelocityRates<S>& vr,
                               const Wrench<S>& w) const {
    QuasiCoords xd;
    xd.template segment<n_theta>(n_r) = P::thetadot(pre, om);  // inverse of Eq. (1.5)
    xd.template tail<3>() = vr.alpha;
    if constexpr (!fixed) {
      xd.template head<3>() = v;
      xd.template segment<3>(nq) = vr.acceleration;
    }
    if (!detail::all_finite_fast(xd)) [[unlikely]] {
      throw_non_finite(q, w, true);
    }
    return xd;
  }

  /// rotation_fn(): R, called only off the centroid (a body at its centroid or held at a fixed
  /// point does not need it, and does not compute it).
  template <class RotationFn>
  VelocityRates<S> velocity_rates_impl(RotationFn&& rotation_fn, const Vector3<S>& om,
                                       const Wrench<S>& w) const {
    VelocityRates<S> vr;
    if constexpr (fixed) {
      vr.acceleration.setZero();
    }
    rates_into(rotation_fn, om, w, vr.acceleration, vr.alpha);
    return vr;
  }

  /// velocity_rates_impl into acc and alpha (acc not written when fixed).
  template <class RotationFn, class W, class Acc, class Alpha>
  [[gnu::always_inline]] void rates_into(RotationFn&& rotation_fn, const Vector3<S>& om, const W& w,
                                         Acc& acc, Alpha& alpha) const {
    constexpr bool loaded = !std::is_same_v<W, NoWrench>;
    // Products are evaluated into named vectors: small expression trees that the compiler inlines
    // whole (nested product expressions were left as out-of-line calls, 30% of the time).
    // Eq. (1.32) through the Newton-Euler closed form of the file comment; Eq. (1.33) at the
    // centroid, where r_g = 0 removes the coupling terms.
    if constexpr (at_centroid) {
      (void)rotation_fn;
      if constexpr (loaded) {
        alpha = mp_.euler_centroid(w.moment, om);  // I_g^-1 (M_g - omega x I_g omega)
        acc = w.force / mp_.mass();
      } else {
        alpha = mp_.euler_centroid(w, om);
        acc.setZero();
      }
    } else if constexpr (fixed) {
      // The theta-rows of Eq. (1.32) with rddot_oc = 0: I_c alpha = M_c - omega x I_c omega,
      // moments about the fixed point c; the force at c (reaction included) does not enter.
      (void)rotation_fn;
      (void)acc;
      if constexpr (loaded) {
        alpha = mp_.euler_reference(w.moment, om);
      } else {
        alpha = mp_.euler_reference(w, om);
      }
    } else {
      const Matrix3<S> r = rotation_fn();
      const Vector3<S>& rg = mp_.centroid();
      const Vector3<S> h = mp_.inertia_centroid() * om;  // angular momentum about g, body
      // Moment about the centroid: M_g = M_c - r_g x F^f.
      // Each "x - y" below is formed as -y, plus x when there is a load: the same bits.
      Vector3<S> mg = -om.cross(h);
      if constexpr (loaded) {
        const Vector3<S> fb = r.transpose() * w.force;
        mg += w.moment - rg.cross(fb);
      }
      const Vector3<S> al = mp_.inertia_centroid_inverse().lazyProduct(mg);
      const Vector3<S> ab = al.cross(rg) + om.cross(om.cross(rg));
      alpha = al;
      acc = -(r * ab);
      if constexpr (loaded) {
        acc += w.force / mp_.mass();
      }
    }
  }

  /// Cold: the attitude is read from q again.
  [[noreturn]] static void throw_non_finite(const Coords& q, const Wrench<S>& w,
                                            bool quasi = false) {
    std::ostringstream os;
    os << "tumble::RigidBody<" << P::name << ">::" << (quasi ? "quasi_rates" : "accelerations")
       << ": non-finite result; ";
    if (!detail::all_finite(q)) {
      os << "the state q has a non-finite entry";
    } else if (!detail::all_finite(w.force) || !detail::all_finite(w.moment)) {
      os << "the applied load has a non-finite entry";
    } else if (!(detail::value(P::singularity_distance(theta(q))) > 0)) {
      os << "the attitude is at a singularity of " << P::name
         << " (G is singular): re-center the chart or use another parameterization";
    } else {
      os << (quasi ? "the velocities (v, omega)" : "the rates qdot")
         << " have a non-finite entry or overflowed";
    }
    throw NonFiniteError(os.str());
  }

  MassProperties<S> mp_;
  // Where c is held (fixed_point; zero, and never read, for the other bodies). Every body has it,
  // not only fixed ones (an empty member elsewhere saved 3 scalars of 46), because the members
  // marked `requires fixed` read it, and their definitions must compile for every Ref: an explicit
  // instantiation (`template class RigidBody<P, Ref, S>;`) instantiates only the members whose
  // constraints hold ([temp.explicit]/10), but Clang 14 instantiates all of them
  // (llvm-project#44549, fixed in Clang 15). For the same reason the members of either kind call
  // no member constrained to the other kind (a fixed body's RigidBody(mass_properties) does not
  // delegate to its two-argument constructor; the static point_position does not call position).
  Vector3<S> pivot_ = Vector3<S>::Zero();
};

}  // namespace tumble
