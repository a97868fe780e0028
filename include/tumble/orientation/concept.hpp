#pragma once
// The common interface of every orientation parameterization, written once as a C++20 concept.
//
// Reference: Chapter 1, "Rigid body" (the "reference chapter"), Sec. 1.1.
// Conventions (docs/conventions.md): R maps body components to inertial ones, r_F = R r_f;
// omega is the angular velocity of the body frame relative to the inertial frame, expressed in
// the body frame, omega = G(theta) thetadot (Eq. 1.5).
//
// A parameterization is a stateless type P with
//   P::size                      number of coordinates (3, or 4 for Euler parameters)
//   P::has_constraint            true when the coordinates obey one holonomic constraint
//   P::name                      a readable name ("EulerZYX", "EulerParameters", ...)
//   P::Coords<S>                 Eigen::Matrix<S, size, 1>
// and, for every scalar type S, the static functions
//   rotation(theta)              R(theta)                                              (Eq. 1.1)
//   G(theta)                     3 x size, omega = G thetadot                           (Eq. 1.5)
//   Gdot_thetadot(theta, td)     the product Gdot thetadot of Eq. (1.10)
//   thetadot(theta, omega)       the inverse map; for constrained sets the rate tangent to the
//                                constraint
//   thetaddot(theta, td, alpha)  parameter accelerations for a body angular acceleration alpha:
//                                G thetaddot = alpha - Gdot thetadot (Eq. 1.10), plus the
//                                constraint's second derivative for constrained sets
//   from_rotation(R), to_quaternion(theta), from_quaternion(q)   conversions
//   singularity_distance(theta)  angle in rad to the nearest attitude where G is singular
//                                (+infinity when there is none)
//   canonical(theta)             the canonical representative (normalized quaternion, MRP
//                                shadow set, ...), the identity map where there is no choice
//   omega(theta, thetadot)       omega = G thetadot written out, without forming G  (Eq. 1.5)
// and, when has_constraint, constraint(theta) (zero on the constraint manifold).
//
// What is shared at one attitude. R, G, Gdot thetadot and the inverse map of a three-parameter
// set need the same transcendental or rational functions of theta (the sines and cosines of the
// Euler angles, the coefficients (1 - cos phi) / phi^2, ... of the rotation vector, 1 + s.s of
// Gibbs and MRP). A call of the equations of motion needs several of them at one theta, so each
// parameterization has
//   Precomputed<S>               those functions at one theta (and theta itself)
//   precompute(theta)            builds it
// and rotation, G, omega, Gdot_thetadot, thetadot and thetaddot take a Precomputed<S> in place of
// theta as well: RigidBody evaluates them once per call and passes them through. The overloads of
// theta are precompute(theta) followed by the overload of Precomputed<S>, so both give the same
// values. Functions used on their own (one R, one thetadot) may call the theta overloads.

#include <concepts>
#include <string_view>
#include <tuple>
#include <type_traits>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "tumble/core/math.hpp"
#include "tumble/core/types.hpp"

namespace tumble {

template <class P>
concept Orientation = requires {
  { P::size } -> std::convertible_to<int>;
  { P::has_constraint } -> std::convertible_to<bool>;
  { P::name } -> std::convertible_to<std::string_view>;
  typename P::template Coords<double>;
}
&&(P::size == 3 || P::size == 4) &&
    requires(const typename P::template Coords<double>& theta, const Vector3<double>& w,
             const Matrix3<double>& R, const Eigen::Quaterniond& q) {
  { P::rotation(theta) } -> std::same_as<Matrix3<double>>;
  { P::G(theta) } -> std::same_as<Matrix<double, 3, P::size>>;
  { P::Gdot_thetadot(theta, theta) } -> std::same_as<Vector3<double>>;
  { P::thetadot(theta, w) } -> std::same_as<typename P::template Coords<double>>;
  { P::thetaddot(theta, theta, w) } -> std::same_as<typename P::template Coords<double>>;
  { P::from_rotation(R) } -> std::same_as<typename P::template Coords<double>>;
  { P::to_quaternion(theta) } -> std::same_as<Eigen::Quaterniond>;
  { P::from_quaternion(q) } -> std::same_as<typename P::template Coords<double>>;
  { P::singularity_distance(theta) } -> std::same_as<double>;
  { P::canonical(theta) } -> std::same_as<typename P::template Coords<double>>;
  { P::omega(theta, theta) } -> std::same_as<Vector3<double>>;
  { P::precompute(theta) } -> std::same_as<typename P::template Precomputed<double>>;
}
&&requires(const typename P::template Precomputed<double>& pre,
           const typename P::template Coords<double>& td, const Vector3<double>& w) {
  { P::rotation(pre) } -> std::same_as<Matrix3<double>>;
  { P::G(pre) } -> std::same_as<Matrix<double, 3, P::size>>;
  { P::omega(pre, td) } -> std::same_as<Vector3<double>>;
  { P::Gdot_thetadot(pre, td) } -> std::same_as<Vector3<double>>;
  { P::thetadot(pre, w) } -> std::same_as<typename P::template Coords<double>>;
  { P::thetaddot(pre, td, w) } -> std::same_as<typename P::template Coords<double>>;
}
&&(!P::has_constraint || requires(const typename P::template Coords<double>& theta) {
  { P::constraint(theta) } -> std::same_as<double>;
});

namespace detail {
/// f(P::precompute(theta), args...): the body of every overload of theta (concept.hpp, "what is
/// shared at one attitude"). For AD scalars theta and args are first made coherent (constants
/// with empty derivative vectors get zero ones, see detail::coherent), so that the precomputed
/// functions and the arguments combine in any expression.
template <class P, class F, class Theta, class... A>
[[nodiscard]] auto with_precomputed(F&& f, const Theta& theta, const A&... args) {
  if constexpr (std::is_arithmetic_v<typename Theta::Scalar>) {
    return f(P::precompute(theta), args...);
  } else {
    return std::apply([&f](const auto& th, const auto&... a) { return f(P::precompute(th), a...); },
                      coherent(theta, args...));
  }
}
}  // namespace detail

/// omega = G(theta) thetadot (Eq. 1.5), through P::omega (the product written out).
template <Orientation P, class S>
[[nodiscard]] Vector3<S> angular_velocity(const typename P::template Coords<S>& theta,
                                          const typename P::template Coords<S>& thetadot) {
  return P::omega(theta, thetadot);
}

/// Convert the coordinates of one parameterization into another through the unit quaternion
/// (exact up to rounding; no trigonometric round trip through a matrix).
/// Usage: `auto g = convert<RodriguesParameters, EulerZYX>(angles);`
template <Orientation To, Orientation From, class Derived>
[[nodiscard]] auto convert(const Eigen::MatrixBase<Derived>& theta) {
  using S = typename Derived::Scalar;
  const typename From::template Coords<S> from = theta;
  return To::from_quaternion(From::to_quaternion(from));
}

}  // namespace tumble
