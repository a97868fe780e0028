#pragma once
// The parameterizations and scalar types the generic suites run over.

#include <tuple>

#include <Eigen/Core>
#include <unsupported/Eigen/AutoDiff>

#include "tumble/orientation/euler_parameters.hpp"
#if __has_include("tumble/orientation/euler_angles.hpp")
#include "tumble/orientation/euler_angles.hpp"
#define TUMBLE_TEST_HAVE_EULER_ANGLES 1
#endif
#if __has_include("tumble/orientation/rodrigues.hpp")
#include "tumble/orientation/rodrigues.hpp"
#define TUMBLE_TEST_HAVE_RODRIGUES 1
#endif
#if __has_include("tumble/orientation/modified_rodrigues.hpp")
#include "tumble/orientation/modified_rodrigues.hpp"
#define TUMBLE_TEST_HAVE_MRP 1
#endif
#if __has_include("tumble/orientation/rotation_vector.hpp")
#include "tumble/orientation/rotation_vector.hpp"
#define TUMBLE_TEST_HAVE_ROTATION_VECTOR 1
#endif

namespace tumble::test {

/// Forward-mode AD scalar with a dynamic derivative vector (constants carry an empty one).
using AD = Eigen::AutoDiffScalar<Eigen::VectorXd>;

/// Every parameterization of tumble: 12 Euler sequences, Euler parameters, Gibbs, MRP and the
/// rotation vector.
using AllParameterizations = std::tuple<EulerParameters
#ifdef TUMBLE_TEST_HAVE_EULER_ANGLES
                                        ,
                                        EulerXYZ, EulerXZY, EulerYXZ, EulerYZX, EulerZXY, EulerZYX,
                                        EulerXYX, EulerXZX, EulerYXY, EulerYZY, EulerZXZ, EulerZYZ
#endif
#ifdef TUMBLE_TEST_HAVE_RODRIGUES
                                        ,
                                        RodriguesParameters
#endif
#ifdef TUMBLE_TEST_HAVE_MRP
                                        ,
                                        ModifiedRodriguesParameters
#endif
#ifdef TUMBLE_TEST_HAVE_ROTATION_VECTOR
                                        ,
                                        RotationVector
#endif
                                        >;

}  // namespace tumble::test
