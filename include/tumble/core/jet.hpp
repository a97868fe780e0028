#pragma once
// Forward-mode automatic differentiation in a fixed number N of directions: Jet<N> is Eigen's
// AutoDiffScalar over an N-vector of derivatives held by value (no heap allocation; constants get
// zero derivatives of the full size). Evaluating a function of x in Jet<N> with x seeded along
// unit directions gives its value and, exactly up to rounding, N columns of its Jacobian.
//
// tumble's code is written for any scalar (see core/types.hpp), so the bodies, the
// parameterizations and the force elements run in Jet<N> unchanged; the scene uses this for its
// Jacobian df/dy (scene/jacobian.hpp).

#include <Eigen/Core>
#include <unsupported/Eigen/AutoDiff>

#include "tumble/core/types.hpp"

namespace tumble {

template <int N> using Jet = Eigen::AutoDiffScalar<Eigen::Matrix<double, N, 1>>;

namespace detail {

/// The jets of x with x(i) seeded along direction first + i.
template <int N, class Derived>
[[nodiscard]] Eigen::Matrix<Jet<N>, Derived::RowsAtCompileTime, 1> seed(
    const Eigen::MatrixBase<Derived>& x, int first) {
  Eigen::Matrix<Jet<N>, Derived::RowsAtCompileTime, 1> j(x.size());
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    j(i) = Jet<N>(x(i), N, first + static_cast<int>(i));
  }
  return j;
}

/// The derivatives of a vector of jets, one row per entry: d v / d (directions).
template <int N, int R>
[[nodiscard]] Eigen::Matrix<double, R, N> derivatives(const Eigen::Matrix<Jet<N>, R, 1>& v) {
  Eigen::Matrix<double, R, N> d;
  for (int i = 0; i < R; ++i) {
    d.row(i) = v(i).derivatives().transpose();
  }
  return d;
}

}  // namespace detail
}  // namespace tumble
