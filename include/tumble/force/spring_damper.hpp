#pragma once
// A linear spring-damper between a body point p and a fixed point a of the inertial frame.
// With d = a - r_op, L = |d|, u = d / L and Ldot = -u . rdot_op (Eqs. 1.1, 1.4), the tension is
// T = k (L - L0) + c Ldot and the force on the body is T u at p (Eq. 1.28). A zero rest length
// (L0 = 0) gives the isotropic spring F = k d - c rdot_op, defined for every L.

#include <cmath>
#include <stdexcept>

#include "tumble/core/errors.hpp"
#include "tumble/core/math.hpp"
#include "tumble/force/concept.hpp"

namespace tumble {

struct SpringDamperParameters {
  double stiffness = 0;    ///< k >= 0, N/m
  double damping = 0;      ///< c >= 0, N s/m
  double rest_length = 0;  ///< L0 >= 0, m

  void validate(const char* who) const {
    auto bad = [](double x) { return !std::isfinite(x) || x < 0; };
    if (bad(stiffness) || bad(damping) || bad(rest_length)) {
      throw std::invalid_argument(std::string(who) +
                                  ": stiffness, damping and rest length must be finite and >= 0");
    }
  }
};

namespace detail {
/// The force on the end at `p` (velocity `vp`) of a spring-damper whose other end is at `a`
/// (velocity `va`).
template <class S>
Vector3<S> spring_damper_force(const SpringDamperParameters& sd, const Vector3<S>& p,
                               const Vector3<S>& vp, const Vector3<S>& a, const Vector3<S>& va) {
  using std::sqrt;
  const Vector3<S> d = a - p;
  const Vector3<S> dv = va - vp;
  const S k = S(sd.stiffness), c = S(sd.damping);
  if (sd.rest_length == 0) {
    return k * d + c * dv;
  }
  const S len2 = d.squaredNorm();
  if (!detail::isfinite(len2)) {
    throw NonFiniteError(
        "tumble::SpringDamper: the distance between the two ends is non-finite (a non-finite "
        "position in the state, or ends too far apart to represent)");
  }
  if (!(detail::value(len2) > 0)) {
    throw NonFiniteError(
        "tumble::SpringDamper: the two ends coincide, so the direction of a spring with a "
        "positive rest length is undefined");
  }
  const S len = sqrt(len2);
  const Vector3<S> u = d / len;
  const S tension = k * (len - S(sd.rest_length)) + c * u.dot(dv);
  return tension * u;
}

/// The elastic energy 1/2 k (L - L0)^2 of a spring-damper whose ends are at `p` and `a`.
template <class S>
S spring_potential_energy(const SpringDamperParameters& sd, const Vector3<S>& p,
                          const Vector3<S>& a) {
  using std::sqrt;
  const S stretch = sqrt((a - p).squaredNorm()) - S(sd.rest_length);
  return S(0.5) * S(sd.stiffness) * stretch * stretch;
}
}  // namespace detail

class SpringDamper {
 public:
  /// `point`: r_cp in body components; `anchor`: the fixed point, inertial components.
  SpringDamper(const Vector3<double>& point, const Vector3<double>& anchor,
               const SpringDamperParameters& parameters)
      : point_(point), anchor_(anchor), sd_(parameters) {
    sd_.validate("tumble::SpringDamper");
    if (!detail::all_finite(point) || !detail::all_finite(anchor)) {
      throw std::invalid_argument("tumble::SpringDamper: the point or the anchor is not finite");
    }
  }

  static constexpr bool needs_rotation(ReferencePoint /*ref*/) { return true; }

  template <class S, ReferencePoint Ref>
  void apply(const S& /*t*/, const BodyKinematics<S, Ref>& k, Wrench<S>& w) const {
    const Vector3<S> r = detail::cast<S>(point_);
    const Vector3<S> f =
        detail::spring_damper_force<S>(sd_, k.point_position(r), k.point_velocity(r),
                                       detail::cast<S>(anchor_), Vector3<S>::Zero());
    w.add_force(k.rotation, r, f);
  }

  /// Elastic energy 1/2 k (L - L0)^2.
  template <class S, ReferencePoint Ref>
  [[nodiscard]] S potential_energy(const BodyKinematics<S, Ref>& k) const {
    return detail::spring_potential_energy<S>(sd_, k.point_position(detail::cast<S>(point_)),
                                              detail::cast<S>(anchor_));
  }

  [[nodiscard]] const SpringDamperParameters& parameters() const { return sd_; }

 private:
  Vector3<double> point_;
  Vector3<double> anchor_;
  SpringDamperParameters sd_;
};

static_assert(ForceElement<SpringDamper>);

}  // namespace tumble
