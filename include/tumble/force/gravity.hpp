#pragma once
// Uniform gravity: the force m g (inertial components) at the centroid. For a body framed at its
// centroid it is a pure force and needs no rotation matrix; off the centroid (a frame at an offset
// or at a fixed point) it adds the moment r_g x (R^T m g) about the reference point (Eq. 1.30).

#include <stdexcept>

#include "tumble/core/math.hpp"
#include "tumble/force/concept.hpp"

namespace tumble {

class UniformGravity {
 public:
  /// `g`: the gravitational acceleration, inertial components (e.g. (0, 0, -9.81) m/s^2).
  explicit UniformGravity(const Vector3<double>& g) : g_(g) {
    if (!detail::all_finite(g)) {
      throw std::invalid_argument("tumble::UniformGravity: g has a non-finite entry");
    }
  }
  [[nodiscard]] const Vector3<double>& g() const { return g_; }

  /// V = -m g . r_og (zero at the inertial origin).
  template <class S, ReferencePoint Ref>
  [[nodiscard]] S potential_energy(const BodyKinematics<S, Ref>& k) const {
    Vector3<S> rg = k.position;
    if constexpr (Ref != ReferencePoint::centroid) {
      rg = k.point_position(k.mass_properties->centroid());
    }
    return -k.mass_properties->mass() * detail::cast<S>(g_).dot(rg);
  }

  static constexpr bool needs_rotation(ReferencePoint ref) {
    return ref != ReferencePoint::centroid;
  }

  template <class S, ReferencePoint Ref>
  void apply(const S& /*t*/, const BodyKinematics<S, Ref>& k, Wrench<S>& w) const {
    const Vector3<S> f = k.mass_properties->mass() * detail::cast<S>(g_);
    if constexpr (Ref == ReferencePoint::centroid) {
      w.add_force_at_reference(f);
    } else {
      w.add_force(k.rotation, k.mass_properties->centroid(), f);
    }
  }

 private:
  Vector3<double> g_;
};

static_assert(ForceElement<UniformGravity>);

}  // namespace tumble
