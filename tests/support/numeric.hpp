#pragma once
// Error measures of the orientation tests, in long double: machine epsilon of a scalar type and
// the relative error of a matrix against a reference.

#include <algorithm>

#include "tumble/core/math.hpp"

namespace tumble::test {

/// Machine epsilon of S in long double (of its value type for AD scalars).
template <class S> long double eps() {
  return static_cast<long double>(tumble::detail::epsilon<S>());
}

/// |a - b| / max(|b|, 1) in long double (Frobenius norm for matrices).
template <class A, class B> long double rel_err(const A& a, const B& b) {
  const auto bl = b.template cast<long double>();
  return (a.template cast<long double>() - bl).norm() / std::max(bl.norm(), 1.0L);
}

}  // namespace tumble::test
