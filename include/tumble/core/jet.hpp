#pragma once
// Forward-mode automatic differentiation in a fixed number N of directions. A Jet<N> carries a
// value a and its derivatives v (an N-vector, held by value: no heap allocation; constants get
// zero derivatives of the full size). Evaluating a function of x in Jet<N> with x seeded along
// unit directions gives its value and, exactly up to rounding, N columns of its Jacobian: every
// operation applies the chain rule, (a, v) * (b, w) = (a b, b v + a w), f(a, v) = (f(a), f'(a) v).
//
// tumble's code is written for any scalar (see core/types.hpp), so the bodies, the
// parameterizations and the force elements run in Jet<N> unchanged; the scene uses this for its
// Jacobian df/dy (scene/jacobian.hpp). Every operation evaluates at once into a Jet (no
// expression templates): Eigen's AutoDiffScalar, used here before, builds a nested expression type
// per formula. With this type the test suite's Jacobian sources compile in 10-14% less time and
// 15-20% less memory, and the Jacobian costs the same at run time (docs/benchmarks/per-call.md).
//
// The elementary functions are hidden friends, found by argument-dependent lookup from generic
// code that writes `using std::sin; sin(x)`, as tumble's does (and Eigen's numext functions).
// Comparisons compare values; the derivative of abs at 0 is taken from the positive side.

#include <cmath>

#include <Eigen/Core>

#include "tumble/core/types.hpp"

namespace tumble {

template <int N> class Jet {
 public:
  using Derivatives = Eigen::Matrix<double, N, 1>;
  static constexpr int directions = N;

  /// Zero, with zero derivatives.
  Jet() : a_(0.0), v_(Derivatives::Zero()) {}
  /// A constant: zero derivatives. Implicit, like a double's conversion to any scalar type.
  Jet(double a) : a_(a), v_(Derivatives::Zero()) {}  // NOLINT(google-explicit-constructor)
  /// The variable of direction i: derivative 1 along i, 0 along the others. (The size argument
  /// must be N; it keeps the signature of Eigen's AutoDiffScalar(value, size, index).)
  Jet(double a, [[maybe_unused]] int size, int i) : a_(a), v_(Derivatives::Unit(i)) {
    eigen_assert(size == N);
  }
  Jet(double a, const Derivatives& v) : a_(a), v_(v) {}

  [[nodiscard]] double value() const { return a_; }
  double& value() { return a_; }
  [[nodiscard]] const Derivatives& derivatives() const { return v_; }
  Derivatives& derivatives() { return v_; }

  Jet& operator+=(const Jet& b) {
    a_ += b.a_;
    v_ += b.v_;
    return *this;
  }
  Jet& operator-=(const Jet& b) {
    a_ -= b.a_;
    v_ -= b.v_;
    return *this;
  }
  Jet& operator*=(const Jet& b) {
    v_ = b.a_ * v_ + a_ * b.v_;
    a_ *= b.a_;
    return *this;
  }
  Jet& operator/=(const Jet& b) {
    const double inv = 1.0 / b.a_;
    a_ *= inv;
    v_ = (v_ - a_ * b.v_) * inv;
    return *this;
  }
  Jet& operator+=(double b) {
    a_ += b;
    return *this;
  }
  Jet& operator-=(double b) {
    a_ -= b;
    return *this;
  }
  Jet& operator*=(double b) {
    a_ *= b;
    v_ *= b;
    return *this;
  }
  Jet& operator/=(double b) { return *this *= 1.0 / b; }

  friend Jet operator+(const Jet& a) { return a; }
  friend Jet operator-(const Jet& a) { return Jet(-a.a_, -a.v_); }
  friend Jet operator+(Jet a, const Jet& b) { return a += b; }
  friend Jet operator-(Jet a, const Jet& b) { return a -= b; }
  friend Jet operator*(Jet a, const Jet& b) { return a *= b; }
  friend Jet operator/(Jet a, const Jet& b) { return a /= b; }
  friend Jet operator+(Jet a, double b) { return a += b; }
  friend Jet operator+(double a, Jet b) { return b += a; }
  friend Jet operator-(Jet a, double b) { return a -= b; }
  friend Jet operator-(double a, const Jet& b) { return Jet(a - b.a_, -b.v_); }
  friend Jet operator*(Jet a, double b) { return a *= b; }
  friend Jet operator*(double a, Jet b) { return b *= a; }
  friend Jet operator/(Jet a, double b) { return a /= b; }
  friend Jet operator/(double a, const Jet& b) {
    const double inv = 1.0 / b.a_;
    const double r = a * inv;
    return Jet(r, (-r * inv) * b.v_);
  }

  // Comparisons compare the values (what a branch on the value of x means).
  friend bool operator==(const Jet& a, const Jet& b) { return a.a_ == b.a_; }
  friend bool operator!=(const Jet& a, const Jet& b) { return a.a_ != b.a_; }
  friend bool operator<(const Jet& a, const Jet& b) { return a.a_ < b.a_; }
  friend bool operator<=(const Jet& a, const Jet& b) { return a.a_ <= b.a_; }
  friend bool operator>(const Jet& a, const Jet& b) { return a.a_ > b.a_; }
  friend bool operator>=(const Jet& a, const Jet& b) { return a.a_ >= b.a_; }
  friend bool operator==(const Jet& a, double b) { return a.a_ == b; }
  friend bool operator!=(const Jet& a, double b) { return a.a_ != b; }
  friend bool operator<(const Jet& a, double b) { return a.a_ < b; }
  friend bool operator<=(const Jet& a, double b) { return a.a_ <= b; }
  friend bool operator>(const Jet& a, double b) { return a.a_ > b; }
  friend bool operator>=(const Jet& a, double b) { return a.a_ >= b; }
  friend bool operator==(double a, const Jet& b) { return a == b.a_; }
  friend bool operator!=(double a, const Jet& b) { return a != b.a_; }
  friend bool operator<(double a, const Jet& b) { return a < b.a_; }
  friend bool operator<=(double a, const Jet& b) { return a <= b.a_; }
  friend bool operator>(double a, const Jet& b) { return a > b.a_; }
  friend bool operator>=(double a, const Jet& b) { return a >= b.a_; }

  // Elementary functions: f(a, v) = (f(a), f'(a) v).
  friend Jet sqrt(const Jet& x) {
    const double s = std::sqrt(x.a_);
    return Jet(s, (0.5 / s) * x.v_);
  }
  friend Jet sin(const Jet& x) { return Jet(std::sin(x.a_), std::cos(x.a_) * x.v_); }
  friend Jet cos(const Jet& x) { return Jet(std::cos(x.a_), -std::sin(x.a_) * x.v_); }
  friend Jet tan(const Jet& x) {
    const double t = std::tan(x.a_);
    return Jet(t, (1.0 + t * t) * x.v_);
  }
  friend Jet asin(const Jet& x) {
    return Jet(std::asin(x.a_), (1.0 / std::sqrt(1.0 - x.a_ * x.a_)) * x.v_);
  }
  friend Jet acos(const Jet& x) {
    return Jet(std::acos(x.a_), (-1.0 / std::sqrt(1.0 - x.a_ * x.a_)) * x.v_);
  }
  friend Jet atan(const Jet& x) { return Jet(std::atan(x.a_), (1.0 / (1.0 + x.a_ * x.a_)) * x.v_); }
  /// d atan2(y, x) = (x dy - y dx) / (x^2 + y^2).
  friend Jet atan2(const Jet& y, const Jet& x) {
    const double inv = 1.0 / (x.a_ * x.a_ + y.a_ * y.a_);
    return Jet(std::atan2(y.a_, x.a_), (x.a_ * inv) * y.v_ - (y.a_ * inv) * x.v_);
  }
  friend Jet exp(const Jet& x) {
    const double e = std::exp(x.a_);
    return Jet(e, e * x.v_);
  }
  friend Jet log(const Jet& x) { return Jet(std::log(x.a_), (1.0 / x.a_) * x.v_); }
  /// x^p for a constant exponent p.
  friend Jet pow(const Jet& x, double p) {
    const double r = std::pow(x.a_, p);
    return Jet(r, (p * std::pow(x.a_, p - 1.0)) * x.v_);
  }
  friend Jet abs(const Jet& x) { return x.a_ < 0 ? -x : x; }
  friend Jet fabs(const Jet& x) { return abs(x); }
  friend Jet abs2(const Jet& x) { return x * x; }
  friend bool isfinite(const Jet& x) { return std::isfinite(x.a_); }
  friend bool isnan(const Jet& x) { return std::isnan(x.a_); }
  friend bool isinf(const Jet& x) { return std::isinf(x.a_); }

 private:
  double a_;
  Derivatives v_;
};

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

namespace Eigen {

/// Jet<N> as an Eigen scalar: a real, non-integer type whose precision is that of double.
template <int N> struct NumTraits<tumble::Jet<N>> : NumTraits<double> {
  using Real = tumble::Jet<N>;
  using NonInteger = tumble::Jet<N>;
  using Nested = tumble::Jet<N>;
  using Literal = double;
  enum {
    IsComplex = 0,
    IsInteger = 0,
    IsSigned = 1,
    RequireInitialization = 1,
    ReadCost = N + 1,
    AddCost = N + 1,
    MulCost = 2 * N + 1
  };
};

/// Jet<N> mixed with double in Eigen expressions (a matrix of jets times a double, and so on)
/// gives Jet<N>.
template <int N, class Op> struct ScalarBinaryOpTraits<tumble::Jet<N>, double, Op> {
  using ReturnType = tumble::Jet<N>;
};
template <int N, class Op> struct ScalarBinaryOpTraits<double, tumble::Jet<N>, Op> {
  using ReturnType = tumble::Jet<N>;
};

}  // namespace Eigen
