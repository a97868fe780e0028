// Body (body.hpp) for Euler parameters, Rodrigues, modified Rodrigues and the rotation vector.

#include "body_impl.hpp"

namespace tumble::python {

std::shared_ptr<const Body> make_vector_body(std::string_view name, ReferencePoint reference,
                                             const MassProperties<double>& mp,
                                             const Eigen::Vector3d& fixed_point) {
  using Sets =
      std::tuple<EulerParameters, RodriguesParameters, ModifiedRodriguesParameters, RotationVector>;
  return detail::make_body_of(static_cast<Sets*>(nullptr), name, reference, mp, fixed_point);
}

}  // namespace tumble::python
