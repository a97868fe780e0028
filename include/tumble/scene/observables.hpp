#pragma once
// What can be read from a scene and a state: each body's attitude, angular velocity, position and
// velocity, and the scene's energy, momenta and constraint drift. Every function is a const
// function of the scene (the model) and a state (a SceneState or a view of an integrator's
// state), so that a saved state reads the same whenever and by whichever copy of the scene it is
// read. Units: SI (m, m/s, rad/s, J, kg m/s, kg m^2/s); vectors in inertial components unless
// said otherwise (omega is in body components, as everywhere in tumble). A body held at a fixed
// point (ReferencePoint::fixed_point) has no translational state: its position is its fixed point
// and its velocity zero. What needs the loads (angular accelerations, reaction forces) is in
// accelerations.hpp.

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <tuple>
#include <type_traits>

#include <Eigen/Geometry>

#include "tumble/core/types.hpp"
#include "tumble/force/coupling.hpp"
#include "tumble/scene/detail/body_terms.hpp"
#include "tumble/scene/scene.hpp"
#include "tumble/scene/state.hpp"

namespace tumble {

namespace detail {
template <class Entry> auto theta_of(const Entry& e, const SceneStateView& s) {
  using Body = std::remove_cvref_t<decltype(e.body)>;
  return typename Body::Theta(s.y.template segment<Body::n_theta>(e.offset + e.theta_at));
}
/// R = R0 R(theta), Eq. (1.1) with the chart base.
template <class Entry> Matrix3<double> rotation_of(const Entry& e, const SceneStateView& s) {
  using P = typename std::remove_cvref_t<decltype(e.body)>::Param;
  const Matrix3<double> r = P::rotation(theta_of(e, s));
  if constexpr (Chart<P>::has_singularity) {
    return s.base[e.id] * r;
  } else {
    return r;
  }
}
/// omega, body components: read from the state in the quasi-velocity form, else G thetadot
/// (Eq. 1.5), the same in every chart (R0 is constant).
template <class Entry> Vector3<double> omega_of(const Entry& e, const SceneStateView& s) {
  using Body = std::remove_cvref_t<decltype(e.body)>;
  if constexpr (Entry::quasi) {
    return s.y.template segment<3>(e.rates + e.theta_at);
  } else {
    const typename Body::Theta thd = s.y.template segment<Body::n_theta>(e.rates + e.theta_at);
    return angular_velocity<typename Body::Param, double>(theta_of(e, s), thd);
  }
}
/// r_oc: from the state, or the fixed point.
template <class Entry> Vector3<double> position_of(const Entry& e, const SceneStateView& s) {
  if constexpr (std::remove_cvref_t<decltype(e.body)>::fixed) {
    return e.body.fixed_point();
  } else {
    return s.y.template segment<3>(e.offset);
  }
}
/// rdot_oc: from the state (the rates start with v in both forms), or zero at a fixed point.
template <class Entry> Vector3<double> velocity_of(const Entry& e, const SceneStateView& s) {
  if constexpr (std::remove_cvref_t<decltype(e.body)>::fixed) {
    return Vector3<double>::Zero();
  } else {
    return s.y.template segment<3>(e.rates);
  }
}
/// rdot of the centroid, Eq. (1.4) with r_cp = r_cg.
template <class Entry>
Vector3<double> centroid_velocity_of(const Entry& e, const SceneStateView& s) {
  using Body = std::remove_cvref_t<decltype(e.body)>;
  const Vector3<double> v = velocity_of(e, s);
  if constexpr (Body::at_centroid) {
    return v;
  } else {
    return v + rotation_of(e, s) * omega_of(e, s).cross(e.body.mass_properties().centroid());
  }
}
/// The full kinematics of body e (with R), as its loads see them.
template <class Entry> auto kinematics_of(const Entry& e, const SceneStateView& s) {
  using Body = std::remove_cvref_t<decltype(e.body)>;
  BodyKinematics<double, Body::reference> k;
  body_kinematics<Entry::form>(e.body, s.y.template segment<Body::nq>(e.offset),
                               s.y.template segment<Entry::rate_size>(e.rates), s.base[e.id], true,
                               k);
  return k;
}
}  // namespace detail

/// R of body b (body -> inertial), chart base included.
template <class SceneT, class Body>
[[nodiscard]] Matrix3<double> rotation(const SceneT& scene, BodyId<Body> b,
                                       const SceneStateView& s) {
  return detail::rotation_of(scene.entry(b), s);
}
/// The unit quaternion of body b's R (body -> inertial, chart base included), with w >= 0: from
/// its parameters (P::to_quaternion), normalized, not through R (half the work of R and Shepperd's
/// method; the two agree to rounding). The base of a chart, constant between switches, is
/// converted only when it is not the identity.
template <class SceneT, class Body>
[[nodiscard]] Eigen::Quaterniond quaternion(const SceneT& scene, BodyId<Body> b,
                                            const SceneStateView& s) {
  using P = typename Body::Param;
  const auto& e = scene.entry(b);
  Eigen::Quaterniond q = P::to_quaternion(detail::theta_of(e, s));
  if constexpr (Chart<P>::has_singularity) {
    const Matrix3<double>& base = s.base[e.id];
    if (!base.isIdentity(0.0)) {
      q = Eigen::Quaterniond(base) * q;
    }
  }
  q.normalize();
  if (q.w() < 0) {
    q.coeffs() = -q.coeffs();
  }
  return q;
}
/// omega of body b, body components, rad/s.
template <class SceneT, class Body>
[[nodiscard]] Vector3<double> omega(const SceneT& scene, BodyId<Body> b, const SceneStateView& s) {
  return detail::omega_of(scene.entry(b), s);
}
/// r_oc of body b's reference point, inertial, m (its fixed point, if held).
template <class SceneT, class Body>
[[nodiscard]] Vector3<double> position(const SceneT& scene, BodyId<Body> b,
                                       const SceneStateView& s) {
  return detail::position_of(scene.entry(b), s);
}
/// rdot_oc of body b's reference point, inertial, m/s (zero, if held at a fixed point).
template <class SceneT, class Body>
[[nodiscard]] Vector3<double> velocity(const SceneT& scene, BodyId<Body> b,
                                       const SceneStateView& s) {
  return detail::velocity_of(scene.entry(b), s);
}
/// r_og of body b's centroid, inertial, m.
template <class SceneT, class Body>
[[nodiscard]] Vector3<double> centroid_position(const SceneT& scene, BodyId<Body> b,
                                                const SceneStateView& s) {
  const auto& e = scene.entry(b);
  return position(scene, b, s) + detail::rotation_of(e, s) * e.body.mass_properties().centroid();
}

/// Sets the velocity (inertial, m/s) and the angular velocity (body, rad/s) of body b in s, e.g.
/// in an event action (an impulse). The attitude and the chart are unchanged.
/// \throws std::invalid_argument for a nonzero v on a body held at a fixed point (whose own form,
///         set_velocity(scene, b, s, omega_body), sets omega only).
template <class SceneT, class Body>
void set_velocity(const SceneT& scene, BodyId<Body> b, SceneState& s, const Vector3<double>& v,
                  const Vector3<double>& omega_body) {
  const auto& e = scene.entry(b);
  if constexpr (Body::fixed) {
    if (!v.isZero(0)) {
      throw std::invalid_argument("tumble::set_velocity: body " + std::to_string(b.id) +
                                  " is held at a fixed point: its velocity is zero");
    }
  } else {
    s.y.template segment<3>(e.rates) = v;
  }
  if constexpr (std::remove_cvref_t<decltype(e)>::quasi) {
    s.y.template segment<3>(e.rates + e.theta_at) = omega_body;
  } else {
    s.y.template segment<Body::n_theta>(e.rates + e.theta_at) =
        Body::Param::thetadot(detail::theta_of(e, s), omega_body);
  }
}

/// Sets the angular velocity (body, rad/s) of body b, held at a fixed point, in s: its only
/// velocity (set_velocity with v = 0). The attitude and the chart are unchanged.
template <class SceneT, class Body>
requires Body::fixed void set_velocity(const SceneT& scene, BodyId<Body> b, SceneState& s,
                                       const Vector3<double>& omega_body) {
  set_velocity(scene, b, s, Vector3<double>::Zero(), omega_body);
}

/// Sum of the kinetic energies, J: per body T = 1/2 qdot^T M qdot (M of Eq. 1.23)
/// = 1/2 m |v_g|^2 + 1/2 omega . I_g omega.
template <class SceneT>
[[nodiscard]] double kinetic_energy(const SceneT& scene, const SceneStateView& s) {
  double t = 0;
  scene.for_each_entry([&](const auto& e) {
    using Body = std::remove_cvref_t<decltype(e.body)>;
    const Vector3<double> w = detail::omega_of(e, s);
    const auto& mp = e.body.mass_properties();
    // |v_g|^2: a body held at a fixed point has v_g = R (omega x r_g), of the same norm as
    // omega x r_g (R is a rotation), so no R is formed for it.
    double vg2 = 0.0;
    if constexpr (Body::fixed) {
      vg2 = w.cross(mp.centroid()).squaredNorm();
    } else {
      vg2 = detail::centroid_velocity_of(e, s).squaredNorm();
    }
    t += 0.5 * (mp.mass() * vg2 + w.dot(mp.inertia_centroid() * w));
  });
  return t;
}

/// Sum of the potential energies of the loads that have one (gravity, springs), J. User loads
/// have none.
template <class SceneT>
[[nodiscard]] double potential_energy(const SceneT& scene, const SceneStateView& s) {
  double v = 0;
  scene.for_each_load([&](const auto& a) {
    using Load = std::remove_cvref_t<decltype(a.load)>;
    if constexpr (CouplingElement<Load>) {
      scene.visit_entry(a.a, [&](const auto& ea) {
        scene.visit_entry(a.b, [&](const auto& eb) {
          const auto ka = detail::kinematics_of(ea, s);
          const auto kb = detail::kinematics_of(eb, s);
          if constexpr (requires { a.load.potential_energy(ka, kb); }) {
            v += a.load.potential_energy(ka, kb);
          }
        });
      });
    } else {
      scene.visit_entry(a.a, [&](const auto& e) {
        const auto k = detail::kinematics_of(e, s);
        if constexpr (requires { a.load.potential_energy(k); }) {
          v += a.load.potential_energy(k);
        }
      });
    }
  });
  return v;
}

/// T + V, J.
template <class SceneT> [[nodiscard]] double energy(const SceneT& scene, const SceneStateView& s) {
  return kinetic_energy(scene, s) + potential_energy(scene, s);
}

/// Total linear momentum, inertial components, kg m/s.
template <class SceneT>
[[nodiscard]] Vector3<double> linear_momentum(const SceneT& scene, const SceneStateView& s) {
  Vector3<double> p = Vector3<double>::Zero();
  scene.for_each_entry([&](const auto& e) {
    p += e.body.mass_properties().mass() * detail::centroid_velocity_of(e, s);
  });
  return p;
}

/// Total angular momentum about the inertial origin, inertial components, kg m^2/s.
template <class SceneT>
[[nodiscard]] Vector3<double> angular_momentum(const SceneT& scene, const SceneStateView& s) {
  Vector3<double> h = Vector3<double>::Zero();
  scene.for_each_entry([&](const auto& e) {
    const auto& mp = e.body.mass_properties();
    const Matrix3<double> r = detail::rotation_of(e, s);
    const Vector3<double> rg = detail::position_of(e, s) + r * mp.centroid();
    h += rg.cross(mp.mass() * detail::centroid_velocity_of(e, s)) +
         r * (mp.inertia_centroid() * detail::omega_of(e, s));
  });
  return h;
}

/// The largest violation of |p| = 1 and p.pdot = 0 over the Euler-parameter bodies (|p| = 1
/// alone in the quasi-velocity form, where pdot is not in the state and p.pdot = 0 by
/// construction).
template <class SceneT>
[[nodiscard]] double constraint_drift(const SceneT& scene, const SceneStateView& s) {
  double d = 0;
  scene.for_each_entry([&](const auto& e) {
    using Body = std::remove_cvref_t<decltype(e.body)>;
    if constexpr (Body::Param::has_constraint && std::remove_cvref_t<decltype(e)>::quasi) {
      const Vector4<double> p = s.y.template segment<4>(e.offset + e.theta_at);
      d = std::max(d, std::abs(p.norm() - 1.0));
    } else if constexpr (Body::Param::has_constraint) {
      const Vector4<double> p = s.y.template segment<4>(e.offset + e.theta_at);
      const Vector4<double> pd = s.y.template segment<4>(e.rates + e.theta_at);
      d = std::max({d, std::abs(p.norm() - 1.0), std::abs(p.dot(pd))});
    }
  });
  return d;
}

}  // namespace tumble
