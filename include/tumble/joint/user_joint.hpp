#pragma once
// A joint written by the user: a callable that fills the M rows (C, J_a, J_b, gamma; see
// concept.hpp) from the two bodies' kinematics, in double. As a user load, it cannot be
// differentiated by tumble's forward-mode AD: a scene with one leaves CVODE's Jacobian to
// difference quotients (the other joints are written for any scalar type: scene/jacobian.hpp).

#include <functional>
#include <stdexcept>
#include <utility>

#include "tumble/joint/concept.hpp"

namespace tumble {

template <int M> class UserJoint {
  static_assert(M >= 1 && M <= 6, "a joint has 1 to 6 constraint equations");

 public:
  static constexpr int size = M;
  static constexpr const char* name = "UserJoint";
  using Function = std::function<void(const KinematicsView<double>&, const KinematicsView<double>&,
                                      ConstraintRows<double, M>&)>;

  explicit UserJoint(Function f) : f_(std::move(f)) {
    if (!f_) {
      throw std::invalid_argument("tumble::UserJoint: the function is empty");
    }
  }

  void evaluate(const KinematicsView<double>& a, const KinematicsView<double>& b,
                ConstraintRows<double, M>& r) const {
    f_(a, b, r);
  }

 private:
  Function f_;
};

static_assert(JointElement<UserJoint<1>>);

}  // namespace tumble
