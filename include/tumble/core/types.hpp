#pragma once
// Fixed-size Eigen aliases used throughout tumble. Every type is templated on the scalar so the
// same code runs in double, float, long double and automatic-differentiation scalars.

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace tumble {

template <class S> using Vector3 = Eigen::Matrix<S, 3, 1>;
template <class S> using Vector4 = Eigen::Matrix<S, 4, 1>;
template <class S> using Matrix3 = Eigen::Matrix<S, 3, 3>;
template <class S, int N> using Vector = Eigen::Matrix<S, N, 1>;
template <class S, int R, int C> using Matrix = Eigen::Matrix<S, R, C>;

}  // namespace tumble
