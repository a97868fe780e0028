#pragma once
// A user callable as a force element: f(t, kinematics) returns the Wrench it applies (force in
// inertial components at the reference point, moment about it in body components; use
// Wrench::add_force to place a force at a body point). `NeedsRotation = false` declares that the
// callable never reads kinematics.rotation, so R is not computed for it.

#include <concepts>
#include <type_traits>
#include <utility>

#include "tumble/core/errors.hpp"
#include "tumble/core/math.hpp"
#include "tumble/force/concept.hpp"

namespace tumble {

namespace detail {
/// F called as f(t, kinematics) in scalar type S returns a Wrench<S>.
template <class F, class S, ReferencePoint Ref>
concept ForceCallable = requires(const F& f, const S& t, const BodyKinematics<S, Ref>& k) {
  { f(t, k) } -> std::convertible_to<Wrench<S>>;
};
}  // namespace detail

template <class F, bool NeedsRotation = true> class UserForce {
 public:
  explicit UserForce(F f) : f_(std::move(f)) {}

  static constexpr bool needs_rotation(ReferencePoint /*ref*/) { return NeedsRotation; }

  /// \throws NonFiniteError if the callable returns a non-finite wrench.
  /// Available for the scalar types the callable accepts: a callable written for any scalar (a
  /// template) lets a scene differentiate it exactly (scene/jacobian.hpp).
  template <class S, ReferencePoint Ref>
  requires detail::ForceCallable<F, S, Ref>
  void apply(const S& t, const BodyKinematics<S, Ref>& k, Wrench<S>& w) const {
    const Wrench<S> u = f_(t, k);
    if (!detail::isfinite(u.force.sum() + u.moment.sum())) [[unlikely]] {
      throw NonFiniteError("tumble::UserForce: the user force returned a non-finite wrench");
    }
    w += u;
  }

 private:
  F f_;
};

template <bool NeedsRotation = true, class F> UserForce<F, NeedsRotation> make_user_force(F f) {
  return UserForce<F, NeedsRotation>(std::move(f));
}

}  // namespace tumble
