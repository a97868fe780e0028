// Jet<N> (core/jet.hpp): every operation and elementary function against the derivative of its
// closed form, and against central differences of the double function; Eigen's vector operations
// in jets against the same operations in double.

#include "tumble/core/jet.hpp"

#include <cmath>
#include <functional>

#include <Eigen/Geometry>

#include "support/catch.hpp"
#include "tumble/core/math.hpp"

namespace {

using tumble::Jet;
using J2 = Jet<2>;

/// The jet of f at (x, y), seeded along directions 0 and 1.
template <class F> J2 at(F f, double x, double y) { return f(J2(x, 2, 0), J2(y, 2, 1)); }

/// d f / d(x, y) by central differences of the double function, step h.
Eigen::Vector2d central(const std::function<double(double, double)>& f, double x, double y) {
  const double h = 1e-6;
  return {(f(x + h, y) - f(x - h, y)) / (2 * h), (f(x, y + h) - f(x, y - h)) / (2 * h)};
}

}  // namespace

TEST_CASE("Jet: arithmetic applies the chain rule", "[core][jet]") {
  const double x = 0.7, y = -1.3;
  // (a, v) op (b, w): value and derivatives against the closed forms.
  const J2 p = at([](auto a, auto b) { return a * b; }, x, y);
  CHECK(p.value() == x * y);
  CHECK(p.derivatives() == Eigen::Vector2d(y, x));
  const J2 q = at([](auto a, auto b) { return a / b; }, x, y);
  CHECK(q.value() == Approx(x / y).epsilon(1e-15));
  CHECK(q.derivatives()(0) == Approx(1 / y).epsilon(1e-15));
  CHECK(q.derivatives()(1) == Approx(-x / (y * y)).epsilon(1e-15));
  const J2 s = at([](auto a, auto b) { return 2.0 - a + b * 3.0 - (-a) / 4.0 + 1.0 / b; }, x, y);
  CHECK(s.value() == Approx(2 - x + 3 * y + x / 4 + 1 / y).epsilon(1e-15));
  CHECK(s.derivatives()(0) == Approx(-1 + 0.25).epsilon(1e-15));
  CHECK(s.derivatives()(1) == Approx(3 - 1 / (y * y)).epsilon(1e-15));
  // Compound assignment gives the same as the binary operators.
  J2 c(x, 2, 0);
  c *= J2(y, 2, 1);
  c /= 2.0;
  c += 1.0;
  c -= J2(x, 2, 0);
  CHECK(c.value() == Approx(x * y / 2 + 1 - x).epsilon(1e-15));
  CHECK(c.derivatives()(0) == Approx(y / 2 - 1).epsilon(1e-15));
  CHECK(c.derivatives()(1) == Approx(x / 2).epsilon(1e-15));
  // A constant has zero derivatives of the full size.
  const J2 k(5.0);
  CHECK(k.derivatives() == Eigen::Vector2d::Zero());
}

TEST_CASE("Jet: elementary functions against central differences", "[core][jet]") {
  struct Case {
    const char* name;
    std::function<J2(J2, J2)> jet;
    std::function<double(double, double)> plain;
    double x, y;
  };
  using std::abs, std::acos, std::asin, std::atan, std::atan2, std::cos, std::exp, std::log,
      std::pow, std::sin, std::sqrt, std::tan;
  const Case cases[] = {
      {"sqrt", [](J2 a, J2 b) { return sqrt(a * b); },
       [](double a, double b) { return sqrt(a * b); }, 0.8, 1.7},
      {"sin", [](J2 a, J2 b) { return sin(a - 2.0 * b); },
       [](double a, double b) { return sin(a - 2 * b); }, 0.3, 0.9},
      {"cos", [](J2 a, J2 b) { return cos(a * b); }, [](double a, double b) { return cos(a * b); },
       0.3, 0.9},
      {"tan", [](J2 a, J2 b) { return tan(a + b); }, [](double a, double b) { return tan(a + b); },
       0.2, 0.5},
      {"asin", [](J2 a, J2 b) { return asin(a * b); },
       [](double a, double b) { return asin(a * b); }, 0.4, 0.9},
      {"acos", [](J2 a, J2 b) { return acos(a - b); },
       [](double a, double b) { return acos(a - b); }, 0.4, -0.2},
      {"atan", [](J2 a, J2 b) { return atan(a / b); },
       [](double a, double b) { return atan(a / b); }, 1.4, 0.6},
      {"atan2", [](J2 a, J2 b) { return atan2(a, b); },
       [](double a, double b) { return atan2(a, b); }, -0.4, -0.9},
      {"exp", [](J2 a, J2 b) { return exp(a * b); }, [](double a, double b) { return exp(a * b); },
       0.5, -1.1},
      {"log", [](J2 a, J2 b) { return log(a * a + b); },
       [](double a, double b) { return log(a * a + b); }, 0.5, 1.1},
      {"pow", [](J2 a, J2 b) { return pow(a + b, 2.5); },
       [](double a, double b) { return pow(a + b, 2.5); }, 0.5, 1.1},
      {"abs", [](J2 a, J2 b) { return abs(a - b); }, [](double a, double b) { return abs(a - b); },
       0.5, 1.1},
  };
  for (const Case& c : cases) {
    INFO(c.name);
    const J2 j = at(c.jet, c.x, c.y);
    CHECK(j.value() == Approx(c.plain(c.x, c.y)).epsilon(1e-15));
    const Eigen::Vector2d fd = central(c.plain, c.x, c.y);
    // Central differences with h = 1e-6 are accurate to about 1e-9 here.
    CHECK((j.derivatives() - fd).norm() < 1e-8 * (1 + fd.norm()));
  }
}

TEST_CASE("Jet: comparisons and classification look at the value", "[core][jet]") {
  const J2 a(1.0, 2, 0), b(2.0, 2, 1);
  CHECK(a < b);
  CHECK(a <= b);
  CHECK(b > a);
  CHECK(b >= 2.0);
  CHECK(a == 1.0);
  CHECK(a != b);
  CHECK(0.5 < a);
  CHECK(isfinite(a));
  CHECK_FALSE(isfinite(a / 0.0));
  CHECK(isinf(a / 0.0));
  CHECK(isnan(J2(std::nan(""))));
  // tumble's value() sees through the jet.
  CHECK(tumble::detail::value(b) == 2.0);
}

TEST_CASE("Jet: Eigen vectors of jets agree with double and with finite differences",
          "[core][jet]") {
  // f(x) = normalized(u(x)) x (w . u(x)), u(x) = (x0, x1, x0 x1): value against double, the
  // derivatives against central differences.
  const auto f = [](const auto& x0, const auto& x1) {
    using S = std::decay_t<decltype(x0)>;
    const Eigen::Matrix<S, 3, 1> u(x0, x1, x0 * x1);
    const Eigen::Matrix<S, 3, 1> w(S(0.3), S(-0.2), S(0.9));
    return Eigen::Matrix<S, 3, 1>(u.normalized().cross(w) * w.dot(u) + u * 2.0);
  };
  const double x0 = 0.6, x1 = -1.4, h = 1e-6;
  const auto j = f(J2(x0, 2, 0), J2(x1, 2, 1));
  const Eigen::Vector3d v = f(x0, x1);
  const Eigen::Matrix<double, 3, 2> fd =
      (Eigen::Matrix<double, 3, 2>() << (f(x0 + h, x1) - f(x0 - h, x1)) / (2 * h),
       (f(x0, x1 + h) - f(x0, x1 - h)) / (2 * h))
          .finished();
  const Eigen::Matrix<double, 3, 2> d = tumble::detail::derivatives(j);
  for (int i = 0; i < 3; ++i) {
    CHECK(j(i).value() == Approx(v(i)).epsilon(1e-14));
  }
  CHECK((d - fd).norm() < 1e-8 * (1 + fd.norm()));
  // seed() and derivatives() are each other's inverse on the identity.
  const auto s = tumble::detail::seed<3>(Eigen::Vector3d(1, 2, 3), 0);
  CHECK(tumble::detail::derivatives(s) == Eigen::Matrix3d::Identity());
}
