#pragma once
// Force elements: each adds its load on one body to that body's Wrench (force at the reference
// point in inertial components, moment about it in body components; reference chapter
// Eqs. 1.28-1.31). Each declares at compile time whether it reads the rotation matrix, so that R
// is not computed for a body whose loads do not need it.
//
// A force element F provides
//   static constexpr bool needs_rotation(ReferencePoint ref)
//   template <class S, ReferencePoint Ref>
//   void apply(const S& t, const BodyKinematics<S, Ref>& k, Wrench<S>& w) const
// The concept checks apply() for the centroid and offset frames; a body held at a fixed point
// (ReferencePoint::fixed_point) calls it with BodyKinematics<S, fixed_point>, whose position is the
// fixed point and whose velocity is zero, so an apply() templated on Ref serves all three.

#include <concepts>

#include "tumble/body/kinematics.hpp"
#include "tumble/body/wrench.hpp"

namespace tumble {

template <class F>
concept ForceElement = requires(const F& f, const double& t,
                                const BodyKinematics<double, ReferencePoint::centroid>& k0,
                                const BodyKinematics<double, ReferencePoint::offset>& k1,
                                Wrench<double>& w) {
  { F::needs_rotation(ReferencePoint::centroid) } -> std::convertible_to<bool>;
  f.apply(t, k0, w);
  f.apply(t, k1, w);
};

namespace detail {
template <class S, class Derived> auto cast(const Eigen::MatrixBase<Derived>& x) {
  return x.template cast<S>();
}
}  // namespace detail

}  // namespace tumble
