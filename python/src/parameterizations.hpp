#pragma once
// The orientation parameterizations the Python module knows, as a run-time interface over the
// compile-time ones of include/tumble/orientation: Python picks one by name, then each call is
// one virtual call into the C++ static function (nothing computed in Python).
//
// Units: angles and rotation vectors in rad, angular velocities in rad/s (body components).
// Conventions (docs/conventions.md): R maps body components to inertial ones; omega = G thetadot
// (Eq. 1.5 of the reference chapter); quaternions scalar first (w, x, y, z).

#include <memory>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

#include <Eigen/Core>

#include "tumble/orientation/euler_angles.hpp"
#include "tumble/orientation/euler_parameters.hpp"
#include "tumble/orientation/modified_rodrigues.hpp"
#include "tumble/orientation/rodrigues.hpp"
#include "tumble/orientation/rotation_vector.hpp"

namespace tumble::python {

/// All 16 parameterizations of the library, in the order Python lists them.
using AllParameterizations =
    std::tuple<EulerXYZ, EulerXZY, EulerYXZ, EulerYZX, EulerZXY, EulerZYX, EulerXYX, EulerXZX,
               EulerYXY, EulerYZY, EulerZXZ, EulerZYZ, EulerParameters, RodriguesParameters,
               ModifiedRodriguesParameters, RotationVector>;

/// One parameterization behind a virtual interface, coordinates as dynamic Eigen vectors.
class Parameterization {
 public:
  virtual ~Parameterization() = default;
  [[nodiscard]] virtual std::string_view name() const = 0;
  [[nodiscard]] virtual int size() const = 0;
  [[nodiscard]] virtual bool has_constraint() const = 0;
  [[nodiscard]] virtual Eigen::Matrix3d rotation(const Eigen::VectorXd& theta) const = 0;
  [[nodiscard]] virtual Eigen::MatrixXd G(const Eigen::VectorXd& theta) const = 0;
  [[nodiscard]] virtual Eigen::Vector3d Gdot_thetadot(const Eigen::VectorXd& theta,
                                                      const Eigen::VectorXd& thetadot) const = 0;
  [[nodiscard]] virtual Eigen::VectorXd thetadot(const Eigen::VectorXd& theta,
                                                 const Eigen::Vector3d& omega) const = 0;
  [[nodiscard]] virtual Eigen::Vector3d omega(const Eigen::VectorXd& theta,
                                              const Eigen::VectorXd& thetadot) const = 0;
  [[nodiscard]] virtual Eigen::VectorXd from_rotation(const Eigen::Matrix3d& r) const = 0;
  /// q = (w, x, y, z).
  [[nodiscard]] virtual Eigen::VectorXd from_quaternion(const Eigen::Vector4d& q) const = 0;
  [[nodiscard]] virtual Eigen::Vector4d to_quaternion(const Eigen::VectorXd& theta) const = 0;
  [[nodiscard]] virtual double singularity_distance(const Eigen::VectorXd& theta) const = 0;
  [[nodiscard]] virtual Eigen::VectorXd canonical(const Eigen::VectorXd& theta) const = 0;
};

/// The interface of P (stateless, so one constant object per parameterization).
const Parameterization& parameterization(std::string_view name);
/// All of them, in the order of AllParameterizations.
const std::vector<const Parameterization*>& parameterizations();

}  // namespace tumble::python
