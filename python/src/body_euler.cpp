// Body (body.hpp) for the 12 Euler sequences, in a translation unit of its own (compile memory).

#include "body_impl.hpp"

namespace tumble::python {

std::shared_ptr<const Body> make_euler_body(std::string_view name, ReferencePoint reference,
                                            const MassProperties<double>& mp,
                                            const Eigen::Vector3d& fixed_point) {
  using Sequences = std::tuple<EulerXYZ, EulerXZY, EulerYXZ, EulerYZX, EulerZXY, EulerZYX, EulerXYX,
                               EulerXZX, EulerYXY, EulerYZY, EulerZXZ, EulerZYZ>;
  return detail::make_body_of(static_cast<Sequences*>(nullptr), name, reference, mp, fixed_point);
}

}  // namespace tumble::python
