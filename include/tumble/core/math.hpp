#pragma once
// Small math helpers shared by every module: the skew-symmetric matrix S(a) of the reference
// chapter, scalar-type-aware constants and thresholds, and value extraction for AD scalars.

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>
#include <type_traits>

#include <Eigen/Core>

#include "tumble/core/types.hpp"

namespace tumble {

/// S(a) with S(a) b = a x b (reference chapter, Sec. 1.1.2).
template <class Derived>
[[nodiscard]] Matrix3<typename Derived::Scalar> skew(const Eigen::MatrixBase<Derived>& a) {
  using S = typename Derived::Scalar;
  Matrix3<S> m;
  m << S(0), -a(2), a(1),  //
      a(2), S(0), -a(0),   //
      -a(1), a(0), S(0);
  return m;
}

namespace detail {

/// The plain floating-point value of a scalar: itself for arithmetic types, `.value()` for
/// Eigen's AutoDiffScalar (recursively, so nested AD works too).
template <class S> [[nodiscard]] constexpr auto value(const S& x) {
  if constexpr (std::is_arithmetic_v<S>) {
    return x;
  } else {
    return value(x.value());
  }
}

template <class S> [[nodiscard]] bool isfinite(const S& x) {
  using std::isfinite;
  return isfinite(value(x));
}

template <class Derived> [[nodiscard]] bool all_finite(const Eigen::MatrixBase<Derived>& m) {
  for (Eigen::Index j = 0; j < m.cols(); ++j) {
    for (Eigen::Index i = 0; i < m.rows(); ++i) {
      if (!detail::isfinite(m(i, j))) {
        return false;
      }
    }
  }
  return true;
}

/// all_finite for a fixed-size vector on the hot path: x * 0 == 0 holds exactly for finite x and
/// fails for inf and NaN, and the products and comparisons are independent (SIMD, no dependent
/// chain of additions as in isfinite(sum)), so the check costs a few cycles of latency.
template <class Derived> [[nodiscard]] bool all_finite_fast(const Eigen::MatrixBase<Derived>& v) {
  using S = typename Derived::Scalar;
  if constexpr (std::is_arithmetic_v<S>) {
    return ((v.array() * S(0)) == S(0)).all();
  } else {
    return all_finite(v);
  }
}

/// Machine epsilon of the scalar type (of its value type for AD scalars).
template <class S> [[nodiscard]] constexpr auto epsilon() {
  using V = decltype(value(std::declval<S>()));
  return std::numeric_limits<V>::epsilon();
}

template <class S> [[nodiscard]] S pi() {
  using V = decltype(value(std::declval<S>()));
  return S(V(3.141592653589793238462643383279502884L));
}

/// atan for scalars that only provide atan2 (Eigen's AutoDiffScalar). For AD scalars the 1 gets
/// zero derivatives sized like those of x: Eigen's atan2 subtracts the two derivative vectors
/// without resizing the empty one of a constant (an assertion failure otherwise).
template <class S> [[nodiscard]] S atan(const S& x) {
  using std::atan2;
  if constexpr (std::is_arithmetic_v<S>) {
    return atan2(x, S(1));
  } else {
    S one(1);
    one.derivatives().setZero(x.derivatives().size());
    return atan2(x, one);
  }
}

/// For automatic differentiation scalars (Eigen's AutoDiffScalar): give every entry whose
/// derivative vector is empty (a constant) zero derivatives of the size the others have. Eigen
/// reconciles an empty derivative vector with a full one only between plain vectors, not inside a
/// composite expression, where debug builds assert on the size mismatch. A no-op for arithmetic
/// scalars. Returns the copies, made coherent, as a tuple.
template <class... M> [[nodiscard]] auto coherent(const M&... m) {
  std::tuple<typename M::PlainObject...> copies(m...);
  if constexpr (!(std::is_arithmetic_v<typename M::Scalar> && ...)) {
    const auto for_each_entry = [&copies](auto&& f) {
      std::apply(
          [&](auto&... c) {
            (..., [&] {
              for (Eigen::Index i = 0; i < c.size(); ++i) {
                f(c(i));
              }
            }());
          },
          copies);
    };
    Eigen::Index n = 0;
    for_each_entry([&](const auto& x) { n = std::max(n, x.derivatives().size()); });
    for_each_entry([&](auto& x) {
      if (x.derivatives().size() == 0) {
        x.derivatives().setZero(n);
      }
    });
  }
  return copies;
}

/// Horner evaluation of c[0] + c[1] x + c[2] x^2 + ... with coefficients given in long double
/// and rounded to the scalar's value type once.
template <class S, std::size_t N> [[nodiscard]] S horner(const long double (&c)[N], const S& x) {
  using V = decltype(value(std::declval<S>()));
  S r = S(V(c[N - 1]));
  for (std::size_t k = N - 1; k-- > 0;) {
    r = r * x + S(V(c[k]));
  }
  return r;
}

}  // namespace detail
}  // namespace tumble
