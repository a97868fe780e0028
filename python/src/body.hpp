#pragma once
// A rigid body of any compiled parameterization and reference point behind a virtual interface:
// Python picks both by name at run time; each call is one virtual call into RigidBody<P, Ref>.
//
// Coordinates: q = [r_oc (3, inertial, m); theta (3 or 4)], qdot its rates; for a body held at a
// fixed point q = theta alone. Wrench: force in inertial components (N) at the reference point c,
// moment about c in body components (N m). Equation numbers: the reference chapter.

#include <memory>
#include <string>
#include <string_view>

#include <Eigen/Core>

#include "parameterizations.hpp"
#include "tumble/body/kinematics.hpp"
#include "tumble/body/mass_properties.hpp"

namespace tumble::python {

class Body {
 public:
  virtual ~Body() = default;
  [[nodiscard]] virtual const Parameterization& parameterization() const = 0;
  [[nodiscard]] virtual ReferencePoint reference() const = 0;
  [[nodiscard]] virtual const MassProperties<double>& mass_properties() const = 0;
  [[nodiscard]] virtual Eigen::Vector3d fixed_point() const = 0;  ///< zero unless fixed_point
  [[nodiscard]] virtual int nq() const = 0;
  /// The RigidBody<P, Ref> itself, for the scene that adds it (which knows P and Ref).
  [[nodiscard]] virtual const void* rigid_body() const = 0;
  [[nodiscard]] virtual Eigen::MatrixXd mass_matrix(const Eigen::VectorXd& q) const = 0;
  [[nodiscard]] virtual Eigen::VectorXd centrifugal_coriolis(const Eigen::VectorXd& q,
                                                             const Eigen::VectorXd& qdot) const = 0;
  [[nodiscard]] virtual Eigen::VectorXd generalized_force(const Eigen::VectorXd& q,
                                                          const Eigen::Vector3d& force,
                                                          const Eigen::Vector3d& moment) const = 0;
  [[nodiscard]] virtual Eigen::VectorXd accelerations(const Eigen::VectorXd& q,
                                                      const Eigen::VectorXd& qdot,
                                                      const Eigen::Vector3d& force,
                                                      const Eigen::Vector3d& moment) const = 0;
  [[nodiscard]] virtual Eigen::VectorXd accelerations_q(const Eigen::VectorXd& q,
                                                        const Eigen::VectorXd& qdot,
                                                        const Eigen::VectorXd& gen_force) const = 0;
  [[nodiscard]] virtual double kinetic_energy(const Eigen::VectorXd& q,
                                              const Eigen::VectorXd& qdot) const = 0;
  [[nodiscard]] virtual Eigen::Vector3d linear_momentum(const Eigen::VectorXd& q,
                                                        const Eigen::VectorXd& qdot) const = 0;
  [[nodiscard]] virtual Eigen::Vector3d angular_momentum(const Eigen::VectorXd& q,
                                                         const Eigen::VectorXd& qdot) const = 0;
  [[nodiscard]] virtual Eigen::Vector3d omega(const Eigen::VectorXd& q,
                                              const Eigen::VectorXd& qdot) const = 0;
};

/// The body of parameterization `name` framed at `reference`; `fixed_point` (inertial, m) is read
/// only for ReferencePoint::fixed_point. \throws std::invalid_argument for an unknown name.
std::shared_ptr<const Body> make_body(std::string_view name, ReferencePoint reference,
                                      const MassProperties<double>& mp,
                                      const Eigen::Vector3d& fixed_point);
/// The same for the 12 Euler sequences (body_euler.cpp) and the 4 others (body_vector.cpp);
/// null when `name` is not among them.
std::shared_ptr<const Body> make_euler_body(std::string_view name, ReferencePoint reference,
                                            const MassProperties<double>& mp,
                                            const Eigen::Vector3d& fixed_point);
std::shared_ptr<const Body> make_vector_body(std::string_view name, ReferencePoint reference,
                                             const MassProperties<double>& mp,
                                             const Eigen::Vector3d& fixed_point);

}  // namespace tumble::python
