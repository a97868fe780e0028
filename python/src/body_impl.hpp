#pragma once
// Body (body.hpp) for RigidBody<P, Ref>: included by body_euler.cpp and body_vector.cpp only.

#include <memory>
#include <string_view>
#include <tuple>

#include "body.hpp"
#include "tumble/body/rigid_body.hpp"

namespace tumble::python::detail {

template <class P, ReferencePoint Ref> class BodyOf final : public Body {
  using RB = RigidBody<P, Ref>;
  using Coords = typename RB::Coords;

 public:
  BodyOf(const MassProperties<double>& mp, const Eigen::Vector3d& fixed_point)
      : body_(make(mp, fixed_point)) {}

  [[nodiscard]] const Parameterization& parameterization() const override {
    return python::parameterization(P::name);
  }
  [[nodiscard]] ReferencePoint reference() const override { return Ref; }
  [[nodiscard]] const MassProperties<double>& mass_properties() const override {
    return body_.mass_properties();
  }
  [[nodiscard]] Eigen::Vector3d fixed_point() const override {
    if constexpr (RB::fixed) {
      return body_.fixed_point();
    } else {
      return Eigen::Vector3d::Zero();
    }
  }
  [[nodiscard]] int nq() const override { return RB::nq; }
  [[nodiscard]] const void* rigid_body() const override { return &body_; }
  [[nodiscard]] Eigen::MatrixXd mass_matrix(const Eigen::VectorXd& q) const override {
    return body_.mass_matrix(Coords(q));  // Eq. (1.23)
  }
  [[nodiscard]] Eigen::VectorXd centrifugal_coriolis(const Eigen::VectorXd& q,
                                                     const Eigen::VectorXd& qdot) const override {
    return body_.centrifugal_coriolis(Coords(q), Coords(qdot));  // Eqs. (1.26)-(1.27)
  }
  [[nodiscard]] Eigen::VectorXd generalized_force(const Eigen::VectorXd& q,
                                                  const Eigen::Vector3d& force,
                                                  const Eigen::Vector3d& moment) const override {
    return body_.generalized_force(Coords(q), Wrench<double>{force, moment});  // Eq. (1.31)
  }
  [[nodiscard]] Eigen::VectorXd accelerations(const Eigen::VectorXd& q, const Eigen::VectorXd& qdot,
                                              const Eigen::Vector3d& force,
                                              const Eigen::Vector3d& moment) const override {
    return body_.accelerations(Coords(q), Coords(qdot), Wrench<double>{force, moment});
  }
  [[nodiscard]] Eigen::VectorXd accelerations_q(const Eigen::VectorXd& q,
                                                const Eigen::VectorXd& qdot,
                                                const Eigen::VectorXd& gen_force) const override {
    return body_.accelerations(Coords(q), Coords(qdot), Coords(gen_force));  // Eq. (1.32)
  }
  [[nodiscard]] double kinetic_energy(const Eigen::VectorXd& q,
                                      const Eigen::VectorXd& qdot) const override {
    return body_.kinetic_energy(Coords(q), Coords(qdot));
  }
  [[nodiscard]] Eigen::Vector3d linear_momentum(const Eigen::VectorXd& q,
                                                const Eigen::VectorXd& qdot) const override {
    return body_.linear_momentum(Coords(q), Coords(qdot));
  }
  [[nodiscard]] Eigen::Vector3d angular_momentum(const Eigen::VectorXd& q,
                                                 const Eigen::VectorXd& qdot) const override {
    return body_.angular_momentum(Coords(q), Coords(qdot));
  }
  [[nodiscard]] Eigen::Vector3d omega(const Eigen::VectorXd& q,
                                      const Eigen::VectorXd& qdot) const override {
    return RB::omega(Coords(q), Coords(qdot));  // Eq. (1.5)
  }

 private:
  static RB make(const MassProperties<double>& mp, const Eigen::Vector3d& fixed_point) {
    if constexpr (RB::fixed) {
      return RB(mp, fixed_point);
    } else {
      return RB(mp);
    }
  }
  RB body_;
};

template <class... P>
std::shared_ptr<const Body> make_body_of(std::tuple<P...>* /*types*/, std::string_view name,
                                         ReferencePoint reference, const MassProperties<double>& mp,
                                         const Eigen::Vector3d& fixed_point) {
  std::shared_ptr<const Body> body;
  const auto try_one = [&]<class Q>(Q* /*type*/) {
    if (body || Q::name != name) {
      return;
    }
    switch (reference) {
      case ReferencePoint::centroid:
        body = std::make_shared<BodyOf<Q, ReferencePoint::centroid>>(mp, fixed_point);
        break;
      case ReferencePoint::offset:
        body = std::make_shared<BodyOf<Q, ReferencePoint::offset>>(mp, fixed_point);
        break;
      case ReferencePoint::fixed_point:
        body = std::make_shared<BodyOf<Q, ReferencePoint::fixed_point>>(mp, fixed_point);
        break;
    }
  };
  (try_one(static_cast<P*>(nullptr)), ...);
  return body;
}

}  // namespace tumble::python::detail
