#pragma once
// Loads between two bodies. A coupling element C provides
//   template <class S>
//   void apply(const S& t, const KinematicsView<S>& a, const KinematicsView<S>& b,
//              Wrench<S>& wa, Wrench<S>& wb) const
// and adds equal and opposite forces to the two bodies (so the total linear momentum is
// conserved, and the total angular momentum too when the forces are central).

#include <concepts>
#include <utility>

#include "tumble/core/errors.hpp"
#include "tumble/core/math.hpp"
#include "tumble/force/concept.hpp"
#include "tumble/force/spring_damper.hpp"

namespace tumble {

template <class C>
concept CouplingElement = requires(const C& c, const double& t, const KinematicsView<double>& ka,
                                   const KinematicsView<double>& kb, Wrench<double>& wa,
                                   Wrench<double>& wb) {
  c.apply(t, ka, kb, wa, wb);
};

/// A linear spring-damper between the body point `point_a` of body a and `point_b` of body b
/// (body components of each). Force law as for SpringDamper (spring_damper.hpp).
class SpringDamperBetween {
 public:
  SpringDamperBetween(const Vector3<double>& point_a, const Vector3<double>& point_b,
                      const SpringDamperParameters& parameters)
      : point_a_(point_a), point_b_(point_b), sd_(parameters) {
    sd_.validate("tumble::SpringDamperBetween");
    if (!detail::all_finite(point_a) || !detail::all_finite(point_b)) {
      throw std::invalid_argument("tumble::SpringDamperBetween: an attachment point is not finite");
    }
  }

  template <class S>
  void apply(const S& /*t*/, const KinematicsView<S>& a, const KinematicsView<S>& b, Wrench<S>& wa,
             Wrench<S>& wb) const {
    const Vector3<S> ra = detail::cast<S>(point_a_), rb = detail::cast<S>(point_b_);
    const Vector3<S> f =
        detail::spring_damper_force<S>(sd_, a.point_position(ra), a.point_velocity(ra),
                                       b.point_position(rb), b.point_velocity(rb));
    wa.add_force(a.rotation, ra, f);
    wb.add_force(b.rotation, rb, Vector3<S>(-f));
  }

  /// Elastic energy 1/2 k (L - L0)^2.
  template <class S>
  [[nodiscard]] S potential_energy(const KinematicsView<S>& a, const KinematicsView<S>& b) const {
    return detail::spring_potential_energy<S>(sd_, a.point_position(detail::cast<S>(point_a_)),
                                              b.point_position(detail::cast<S>(point_b_)));
  }

  [[nodiscard]] const SpringDamperParameters& parameters() const { return sd_; }

 private:
  Vector3<double> point_a_;
  Vector3<double> point_b_;
  SpringDamperParameters sd_;
};

static_assert(CouplingElement<SpringDamperBetween>);

namespace detail {
/// F called as f(t, ka, kb, wa, wb) in scalar type S.
template <class F, class S>
concept CouplingCallable = requires(const F& f, const S& t, const KinematicsView<S>& ka,
                                    const KinematicsView<S>& kb, Wrench<S>& wa, Wrench<S>& wb) {
  f(t, ka, kb, wa, wb);
};
}  // namespace detail

/// A user callable between two bodies: f(t, ka, kb, wa, wb) adds its loads to wa and wb.
/// \warning tumble cannot check that the loads are equal and opposite: momentum conservation is
///          the callable's responsibility.
template <class F> class UserCoupling {
 public:
  explicit UserCoupling(F f) : f_(std::move(f)) {}
  /// \throws NonFiniteError if the callable adds a non-finite load to either body.
  /// Available for the scalar types the callable accepts (see UserForce::apply). The callable
  /// adds its loads to zero wrenches, checked, then added to wa and wb (so a non-finite load is
  /// blamed on the callable that made it, not on a load applied before).
  template <class S>
  requires detail::CouplingCallable<F, S>
  void apply(const S& t, const KinematicsView<S>& a, const KinematicsView<S>& b, Wrench<S>& wa,
             Wrench<S>& wb) const {
    Wrench<S> ua, ub;
    f_(t, a, b, ua, ub);
    if (!detail::isfinite(ua.force.sum() + ua.moment.sum() + ub.force.sum() + ub.moment.sum()))
        [[unlikely]] {
      throw NonFiniteError("tumble::UserCoupling: the user coupling added a non-finite load");
    }
    wa += ua;
    wb += ub;
  }

 private:
  F f_;
};

}  // namespace tumble
