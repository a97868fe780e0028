// The generic property suite of the orientation parameterizations: every P in
// tumble::test::AllParameterizations, in double, float and an AD scalar (Eigen's
// AutoDiffScalar), is held to the same properties, each against an independent reference.
//
// Reference chapter: Chapter 1, "Rigid body", Sec. 1.1: R (Eq. 1.1),
// S(omega) = R^T Rdot with omega = G thetadot (Eqs. 1.3, 1.5), alpha = Gdot thetadot +
// G thetaddot (Eq. 1.10). Conventions: docs/conventions.md.
//
// Independent references used below:
//   * Eigen's quaternion-to-matrix conversion for R (round trips, conversions);
//   * central differences in long double with Richardson extrapolation
//     (tests/support/finite_difference.hpp) and forward-mode AD along one direction, for
//     R^T Rdot, Gdot thetadot and the derivatives of every function;
//   * the defining identities: G thetadot(theta, omega) = omega, G thetaddot + Gdot thetadot =
//     alpha, the constraint and its derivatives for Euler parameters;
//   * 50-digit values computed by tests/orientation/reference/make_reference.py with mpmath from
//     the definitions of R (never from the C++ formulas), with G and Gdot thetadot from
//     numerical differentiation of R at high precision;
//   * angles known from the construction of near-singular states.
//
// Tolerances. Every tolerance is k * eps_S * scale: eps_S is the epsilon of the scalar under
// test (double's for AD) and the scale is the size of the terms the checked quantity is made of
// (stated at each check). The constants k:
//   kEval = 32  one evaluation of a closed form (R, G, G thetadot, Gdot thetadot, a quaternion):
//               every entry is a sum of at most four products of factors that are each a few
//               roundings (sin, cos, atan2 and sqrt within 1 ulp in glibc) from the inputs, so at
//               most ~10 eps of the scale; the reference adds its own error (AD in double:
//               again <= ~10 eps; long double differences: below eps_double / 10, see
//               finite_difference.hpp), hence 32.
//   kTwo  = 64  two chained evaluations (coordinates -> rotation -> coordinates, canonical()).
//   cond(G)     the inverse map and thetaddot solve G x = b. Any closed form of G^-1 whose
//               entries carry relative errors ~eps leaves |G x - b| <= c eps |G| |G^-1| |b|
//               = c eps cond(G) |b|, so those tolerances are kEval eps cond(G) * scale, with
//               cond(G) = sigma_max / sigma_3 from an SVD of G in long double. This is how the
//               identities are checked near the singular attitudes too.
// A check against finite differences adds the differences' own error bound (`error` of
// richardson_derivative) to the tolerance; for well-conditioned states that bound is first
// required to be below 4 eps_double * scale (an eighth of the double tolerance), so the
// differences are sharp enough to test double.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <unsupported/Eigen/AutoDiff>

#if __has_include(<sys/wait.h>) && __has_include(<unistd.h>)
#include <sys/wait.h>
#include <unistd.h>
#define TUMBLE_TEST_HAVE_FORK 1
#else
#define TUMBLE_TEST_HAVE_FORK 0
#endif

#include "orientation/reference/reference_values.hpp"
#include "support/catch.hpp"
#include "support/finite_difference.hpp"
#include "support/numeric.hpp"
#include "support/parameterizations.hpp"
#include "support/random.hpp"
#include "support/type_product.hpp"
#include "tumble/core/math.hpp"
#include "tumble/core/types.hpp"
#include "tumble/orientation/concept.hpp"

namespace {

namespace detail = tumble::detail;
namespace test = tumble::test;
using test::AD;
using tumble::convert;
using tumble::EulerParameters;
using tumble::Matrix;
using tumble::Matrix3;
using tumble::Orientation;
using tumble::skew;
using tumble::Vector3;
using tumble::Vector4;
using LD = long double;

using Scalars = std::tuple<double, float, AD>;
// The build compiles this file in slices of the parameterizations (tests/CMakeLists.txt); the
// pairs are sliced by their first member.
#define TUMBLE_CASES TUMBLE_TEST_SLICED_NAME(Cases)
#define TUMBLE_PAIRS TUMBLE_TEST_SLICED_NAME(Pairs)
using TUMBLE_CASES = test::Product<TUMBLE_TEST_PARAMETERIZATIONS, Scalars>;
using TUMBLE_PAIRS = test::Product<TUMBLE_TEST_PARAMETERIZATIONS, test::AllParameterizations>;

template <class P, class S> using Coords = typename P::template Coords<S>;
template <class P, class S> using GMatrix = Matrix<S, 3, P::size>;

constexpr LD kEval = 32;
constexpr LD kTwo = 64;
constexpr int kRandomStates = 50;
const LD kPi = std::acos(-1.0L);
const LD kInf = std::numeric_limits<LD>::infinity();

template <class S> constexpr std::string_view scalar_name() {
  if constexpr (std::is_same_v<S, double>) {
    return "double";
  } else if constexpr (std::is_same_v<S, float>) {
    return "float";
  } else if constexpr (std::is_same_v<S, long double>) {
    return "long double";
  } else {
    return "AD";
  }
}

using test::eps;
const LD kEpsD = eps<double>();

/// The value type of S (double for AD).
template <class S> using ValueOf = decltype(detail::value(std::declval<S>()));

template <class D> auto to_ld(const Eigen::MatrixBase<D>& m) {
  return m.unaryExpr([](const typename D::Scalar& x) { return static_cast<LD>(detail::value(x)); })
      .eval();
}
template <class D> auto to_d(const Eigen::MatrixBase<D>& m) {
  return m
      .unaryExpr([](const typename D::Scalar& x) { return static_cast<double>(detail::value(x)); })
      .eval();
}
/// Rounds (or converts) to the scalar under test; AD scalars get no derivatives (constants).
template <class S, class D> auto to_s(const Eigen::MatrixBase<D>& m) {
  return m
      .unaryExpr(
          [](const typename D::Scalar& x) { return S(static_cast<ValueOf<S>>(detail::value(x))); })
      .eval();
}
template <class D> LD max_abs(const Eigen::MatrixBase<D>& m) {
  return to_ld(m).cwiseAbs().maxCoeff();
}
template <class D> LD norm(const Eigen::MatrixBase<D>& m) { return to_ld(m).norm(); }
template <class D> bool finite(const Eigen::MatrixBase<D>& m) { return detail::all_finite(m); }

/// The kind of chart, for the few properties that depend on where a chart is singular.
enum class Kind {
  kEulerParameters,
  kTaitBryan,
  kProperEuler,
  kGibbs,
  kMrp,
  kRotationVector,
  kOther
};

template <class P> constexpr Kind kind_of() {
  if constexpr (std::is_same_v<P, EulerParameters>) {
    return Kind::kEulerParameters;
  } else if constexpr (requires { P::is_tait_bryan; }) {
    return P::is_tait_bryan ? Kind::kTaitBryan : Kind::kProperEuler;
  } else if constexpr (P::name == "RodriguesParameters") {
    return Kind::kGibbs;
  } else if constexpr (P::name == "ModifiedRodriguesParameters") {
    return Kind::kMrp;
  } else if constexpr (P::name == "RotationVector") {
    return Kind::kRotationVector;
  } else {
    return Kind::kOther;
  }
}

/// The length in coordinate space on which R(theta) varies, for the finite-difference steps:
/// the Gibbs vector and MRP are rational in theta with complex poles at distance
/// sqrt(1 + |theta|^2) (1 + theta.theta = 0), the other charts are trigonometric or polynomial.
template <class P> LD chart_length(const Coords<P, LD>& theta) {
  if constexpr (kind_of<P>() == Kind::kGibbs || kind_of<P>() == Kind::kMrp) {
    return std::sqrt(1 + theta.squaredNorm());
  } else {
    return 1;
  }
}

/// Singular values of G in long double (3 of them; for Euler parameters the 3 x 4 G has rank 3).
template <class P>
[[gnu::noinline]] Eigen::Matrix<LD, 3, 1> singular_values(const Coords<P, LD>& theta) {
  const GMatrix<P, LD> g = P::G(theta);
  Eigen::JacobiSVD<GMatrix<P, LD>> svd(g);
  return svd.singularValues().template head<3>();
}
template <class P> LD cond_G(const Coords<P, LD>& theta) {
  const auto sv = singular_values<P>(theta);
  return sv(2) > 0 ? sv(0) / sv(2) : kInf;
}

/// The gradient of the constraint by AD (Euler parameters: 2 p).
template <class P> [[gnu::noinline]] Coords<P, LD> constraint_gradient(const Coords<P, LD>& theta) {
  Coords<P, AD> x;
  for (int i = 0; i < P::size; ++i) {
    x(i) = AD(static_cast<double>(theta(i)), P::size, i);
  }
  const AD c = P::constraint(x);
  Coords<P, LD> g = Coords<P, LD>::Zero();
  for (int i = 0; i < P::size && i < c.derivatives().size(); ++i) {
    g(i) = c.derivatives()(i);
  }
  return g;
}

/// A random rate; for constrained sets projected onto the tangent space of the constraint.
template <class P>
Coords<P, double> random_rate(test::Random& rng, const Coords<P, double>& theta) {
  Coords<P, double> td;
  for (int i = 0; i < P::size; ++i) {
    td(i) = rng.normal();
  }
  if constexpr (P::has_constraint) {
    const Coords<P, double> g =
        constraint_gradient<P>(theta.template cast<LD>()).template cast<double>();
    td -= (g.dot(td) / g.squaredNorm()) * g;
  }
  return td;
}

template <class P> struct State {
  Coords<P, double> theta;
  Coords<P, double> thetadot;
  Vector3<double> omega;
  Vector3<double> alpha;
};

/// 50 reproducible states: even ones from a uniformly random attitude (P::from_quaternion, the
/// principal coordinates), odd ones raw coordinates (N(0, 1.5^2) components: rotation vectors
/// beyond pi, MRP in the shadow region, any Euler angles; for Euler parameters a random unit
/// quaternion with either sign of e0).
template <class P>
std::vector<State<P>> random_states(std::uint64_t seed, int count = kRandomStates) {
  test::Random rng(seed);
  std::vector<State<P>> out;
  for (int i = 0; i < count; ++i) {
    State<P> s;
    if (i % 2 == 0) {
      s.theta = P::from_quaternion(rng.quaternion());
    } else if constexpr (P::size == 4) {
      Eigen::Vector4d v(rng.normal(), rng.normal(), rng.normal(), rng.normal());
      s.theta = v.normalized();
    } else {
      s.theta = rng.vector(1.5);
    }
    s.thetadot = random_rate<P>(rng, s.theta);
    s.omega = rng.vector();
    s.alpha = rng.vector();
    out.push_back(s);
  }
  return out;
}

template <class D> std::string str(const Eigen::MatrixBase<D>& m) {
  std::string s = "(";
  char buf[40];
  for (Eigen::Index i = 0; i < m.size(); ++i) {
    std::snprintf(buf, sizeof buf, "%s%.17Lg", i ? ", " : "", static_cast<LD>(detail::value(m(i))));
    s += buf;
  }
  return s + ")";
}

/// The largest error seen per property, in units of eps_S * scale (for the report).
struct Worst {
  LD kinematics = 0;
  LD gdot = 0;
  LD inverse = 0;
  LD thetaddot = 0;
  LD fd_error = 0;  // the largest finite-difference error bound, in units of eps_double * scale
  void update(LD& slot, LD err, LD unit) {
    if (unit > 0) {
      slot = std::max(slot, err / unit);
    }
  }
};

// ------------------------------------------------------------------------------------------------
// Independent references, per parameterization (in long double, or by AD in double). They do not
// depend on the scalar under test, so they are instantiated once per P, not once per (P, S).
// ------------------------------------------------------------------------------------------------

/// R^T Rdot along theta + t thetadot by long double differences of P::rotation; the error bound
/// is that of the differences times 3 (|R^T E|_max <= 3 |E|_max for |R_ij| <= 1).
template <class P>
[[gnu::noinline]] test::FdDerivative<Matrix3<LD>> rt_rdot_fd(const Coords<P, LD>& th,
                                                             const Coords<P, LD>& td) {
  using CL = Coords<P, LD>;
  const LD h0 = chart_length<P>(th) / (8 * td.norm());
  const auto fd = test::richardson_derivative(
      [&](LD h) { return Matrix3<LD>(P::rotation(CL(th + h * td))); }, h0);
  return {P::rotation(th).transpose() * fd.value, 3 * fd.error};
}

/// R^T Rdot along theta + t thetadot with Rdot by AD of P::rotation.
template <class P>
[[gnu::noinline]] Matrix3<LD> rt_rdot_ad(const Coords<P, LD>& th, const Coords<P, LD>& td) {
  const auto r = P::rotation(Coords<P, AD>(test::ad_seed(th, td)));
  return (test::ad_values(r).transpose() * test::ad_derivatives(r)).template cast<LD>();
}

/// d/dt [G(theta + t thetadot) thetadot] by long double differences of P::G.
template <class P>
[[gnu::noinline]] test::FdDerivative<Vector3<LD>> gdot_td_fd(const Coords<P, LD>& th,
                                                             const Coords<P, LD>& td) {
  using CL = Coords<P, LD>;
  const LD h0 = chart_length<P>(th) / (8 * td.norm());
  return test::richardson_derivative([&](LD h) { return Vector3<LD>(P::G(CL(th + h * td)) * td); },
                                     h0);
}

/// Gdot = d/dt G(theta + t thetadot) by AD of P::G.
template <class P>
[[gnu::noinline]] GMatrix<P, LD> gdot_ad(const Coords<P, LD>& th, const Coords<P, LD>& td) {
  return test::ad_derivatives(P::G(Coords<P, AD>(test::ad_seed(th, td)))).template cast<LD>();
}

/// d/dt [G(theta(t)) thetadot(t)] at t = 0 by AD, along theta(t) = theta + t td + t^2/2 tdd,
/// thetadot(t) = td + t tdd: the angular acceleration of that motion, without Gdot_thetadot.
template <class P>
[[gnu::noinline]] Vector3<LD> omega_dot_ad(const Coords<P, LD>& th, const Coords<P, LD>& td,
                                           const Coords<P, LD>& tdd) {
  const Vector3<AD> w =
      P::G(Coords<P, AD>(test::ad_seed(th, td))) * Coords<P, AD>(test::ad_seed(td, tdd));
  return test::ad_derivatives(w).template cast<LD>();
}

/// The long double solution of G x = omega, plus grad c . x = 0 for constrained sets.
template <class P>
[[gnu::noinline]] Coords<P, LD> solve_inverse(const Coords<P, LD>& th, const Vector3<LD>& w) {
  const GMatrix<P, LD> g = P::G(th);
  if constexpr (P::has_constraint) {
    Eigen::Matrix<LD, P::size, P::size> a;
    a.template topRows<3>() = g;
    a.template bottomRows<P::size - 3>() = constraint_gradient<P>(th).transpose();
    Coords<P, LD> b = Coords<P, LD>::Zero();
    b.template head<3>() = w;
    return a.fullPivLu().solve(b);
  } else {
    return g.fullPivLu().solve(w);
  }
}

template <class P> [[gnu::noinline]] GMatrix<P, LD> g_ld(const Coords<P, LD>& th) {
  return P::G(th);
}
template <class P>
[[gnu::noinline]] Vector3<LD> gdot_td_ld(const Coords<P, LD>& th, const Coords<P, LD>& td) {
  return P::Gdot_thetadot(th, td);
}

/// d^2/dt^2 c(theta + t td + t^2/2 tdd) by long double differences of P::constraint.
template <class P>
[[gnu::noinline]] test::FdDerivative<LD> constraint_second_derivative(const Coords<P, LD>& th,
                                                                      const Coords<P, LD>& td,
                                                                      const Coords<P, LD>& tdd) {
  using CL = Coords<P, LD>;
  // For a polynomial constraint (Euler parameters: degree 4 in t along this path) three levels
  // are exact up to rounding, and few levels keep the steps, and so the rounding, large.
  const LD h0 = 1 / (td.norm() + std::sqrt(tdd.norm()));
  return test::richardson_second_derivative(
      [&](LD t) { return LD(P::constraint(CL(th + t * td + (t * t / 2) * tdd))); }, h0, 3);
}

// ------------------------------------------------------------------------------------------------
// The checks, shared by the random, near-zero, near-singular and cross-parameterization cases.
// ------------------------------------------------------------------------------------------------

/// S(G thetadot) = R^T Rdot (Eqs. 1.3, 1.5), with Rdot by differences of P::rotation along
/// thetadot in long double and by AD. Scale: |G|_F |thetadot|, which bounds |omega|.
/// `sharp`: require the differences to be accurate to 4 eps_double * scale, an eighth of the double
/// tolerance (well-conditioned states; near a singularity the AD comparison is the sharp one).
template <class P, class S>
void check_kinematics(const Coords<P, S>& theta, const Coords<P, S>& td, bool sharp, Worst& worst) {
  const Coords<P, LD> th = to_ld(theta);
  const Coords<P, LD> tdl = to_ld(td);
  const Vector3<S> w = P::G(theta) * td;
  REQUIRE(finite(w));
  const Vector3<LD> wl = to_ld(w);
  const LD scale = g_ld<P>(th).norm() * tdl.norm();
  if (!(scale > 0)) {
    CHECK(max_abs(w) == 0);
    return;
  }
  const auto fd = rt_rdot_fd<P>(th, tdl);
  const Matrix3<LD> w_ad = rt_rdot_ad<P>(th, tdl);
  const LD err_fd = max_abs(skew(wl) - fd.value);
  const LD err_ad = max_abs(skew(wl) - w_ad);
  INFO("kinematics: theta = " << str(theta) << ", thetadot = " << str(td) << ", omega = " << str(w)
                              << ", R^T Rdot (AD) = " << str(w_ad) << ", scale = " << double(scale)
                              << ", fd error bound = " << double(fd.error));
  if (sharp) {
    CHECK(fd.error <= 4 * kEpsD * scale);
  }
  CHECK(err_fd <= kEval * eps<S>() * scale + fd.error);
  CHECK(err_ad <= kEval * (eps<S>() + kEpsD) * scale);
  worst.update(worst.kinematics, err_ad, eps<S>() * scale);
  worst.update(worst.fd_error, fd.error, kEpsD * scale);
}

/// Gdot thetadot = d/dt [G(theta + t thetadot) thetadot] (Eq. 1.10), by long double differences of
/// P::G and by AD. Scale: |Gdot|_F |thetadot| with Gdot = d/dt G(theta + t thetadot) from AD.
template <class P, class S>
void check_gdot(const Coords<P, S>& theta, const Coords<P, S>& td, bool sharp, Worst& worst) {
  const Coords<P, LD> th = to_ld(theta);
  const Coords<P, LD> tdl = to_ld(td);
  const Vector3<S> gdt = P::Gdot_thetadot(theta, td);
  REQUIRE(finite(gdt));
  const GMatrix<P, LD> gdot = gdot_ad<P>(th, tdl);
  const Vector3<LD> ref_ad = gdot * tdl;
  const LD scale = gdot.norm() * tdl.norm();
  if (!(scale > 0)) {
    CHECK(max_abs(gdt) == 0);
    return;
  }
  const auto fd = gdot_td_fd<P>(th, tdl);
  const LD err_fd = max_abs(to_ld(gdt) - fd.value);
  const LD err_ad = max_abs(to_ld(gdt) - ref_ad);
  INFO("Gdot thetadot: theta = " << str(theta) << ", thetadot = " << str(td)
                                 << ", Gdot thetadot = " << str(gdt) << ", AD: " << str(ref_ad)
                                 << ", differences: " << str(fd.value)
                                 << ", scale = " << double(scale));
  if (sharp) {
    CHECK(fd.error <= 4 * kEpsD * scale);
  }
  CHECK(err_fd <= kEval * eps<S>() * scale + fd.error);
  CHECK(err_ad <= kEval * (eps<S>() + kEpsD) * scale);
  worst.update(worst.gdot, err_ad, eps<S>() * scale);
}

/// The inverse map: G thetadot(theta, omega) = omega, the rate tangent to the constraint for
/// constrained sets, and the forward error against a long double solve. Tolerances scaled by
/// cond(G) (see the file comment).
template <class P, class S>
void check_inverse(const Coords<P, S>& theta, const Vector3<double>& omega, Worst& worst) {
  const Coords<P, LD> th = to_ld(theta);
  const LD cond = cond_G<P>(th);
  REQUIRE(std::isfinite(static_cast<double>(cond)));
  const Vector3<S> w = to_s<S>(omega);
  const Coords<P, S> td = P::thetadot(theta, w);
  REQUIRE(finite(td));
  const Coords<P, LD> tdl = to_ld(td);
  const LD residual = max_abs(g_ld<P>(th) * tdl - to_ld(w));
  const Coords<P, LD> x = solve_inverse<P>(th, to_ld(w));
  const LD tol = kEval * eps<S>() * cond;
  INFO("inverse map: theta = " << str(theta) << ", omega = " << str(w) << ", thetadot = " << str(td)
                               << ", long double solve = " << str(x)
                               << ", cond(G) = " << double(cond));
  CHECK(residual <= tol * norm(w));
  CHECK(max_abs(tdl - x) <= tol * x.norm());
  if constexpr (P::has_constraint) {
    const Coords<P, LD> grad = constraint_gradient<P>(th);
    CHECK(std::fabs(grad.dot(tdl)) <= kEval * eps<S>() * grad.norm() * tdl.norm());
  }
  worst.update(worst.inverse, residual, eps<S>() * cond * norm(w));
}

/// thetaddot(theta, td, alpha): G thetaddot + Gdot thetadot = alpha (Eq. 1.10), checked with G
/// and Gdot thetadot in long double and, independently of Gdot_thetadot, as the AD derivative of
/// omega(t) = G(theta(t)) thetadot(t) along theta(t) = theta + t td + t^2/2 thetaddot. For
/// constrained sets the constraint's second derivative along that path vanishes (Euler
/// parameters: p . pddot = -|pdot|^2). Scale: |alpha| + |Gdot|_F |td|, times cond(G).
template <class P, class S>
void check_thetaddot(const Coords<P, S>& theta, const Coords<P, S>& td,
                     const Vector3<double>& alpha, Worst& worst) {
  const Coords<P, LD> th = to_ld(theta);
  const Coords<P, LD> tdl = to_ld(td);
  const LD cond = cond_G<P>(th);
  REQUIRE(std::isfinite(static_cast<double>(cond)));
  const Vector3<S> a = to_s<S>(alpha);
  const Coords<P, S> tdd = P::thetaddot(theta, td, a);
  REQUIRE(finite(tdd));
  const Coords<P, LD> tddl = to_ld(tdd);
  const LD scale = cond * (norm(a) + gdot_ad<P>(th, tdl).norm() * tdl.norm());
  const Vector3<LD> lhs = g_ld<P>(th) * tddl + gdot_td_ld<P>(th, tdl);
  const Vector3<LD> alpha_ad = omega_dot_ad<P>(th, tdl, tddl);
  INFO("thetaddot: theta = " << str(theta) << ", thetadot = " << str(td) << ", alpha = " << str(a)
                             << ", thetaddot = " << str(tdd) << ", G tdd + Gdot td = " << str(lhs)
                             << ", AD alpha = " << str(alpha_ad) << ", cond(G) = " << double(cond));
  const LD err = max_abs(lhs - to_ld(a));
  CHECK(err <= kEval * eps<S>() * scale);
  CHECK(max_abs(alpha_ad - to_ld(a)) <= kEval * (eps<S>() + kEpsD) * scale);
  if constexpr (P::has_constraint) {
    const auto c2 = constraint_second_derivative<P>(th, tdl, tddl);
    const Coords<P, LD> grad = constraint_gradient<P>(th);
    // Scale: |grad c| |tdd| + |H| |td|^2 with H = 2 I for |p|^2 - 1.
    const LD cscale = grad.norm() * tddl.norm() + 2 * tdl.squaredNorm();
    CHECK(std::fabs(c2.value) <= kEval * eps<S>() * cscale + c2.error);
    if constexpr (std::is_same_v<P, EulerParameters>) {
      CHECK(std::fabs(th.dot(tddl) + tdl.squaredNorm()) <= kEval * eps<S>() * cscale);
    }
  }
  worst.update(worst.thetaddot, err, eps<S>() * scale);
}

/// R orthonormal with det +1. Scale 1 (|R_ij| <= 1).
template <class P, class S> void check_orthonormal(const Coords<P, S>& theta) {
  const Matrix3<LD> r = to_ld(P::rotation(theta));
  INFO("orthonormality: theta = " << str(theta) << ", R = " << str(r));
  CHECK(max_abs(r.transpose() * r - Matrix3<LD>::Identity()) <= kEval * eps<S>());
  CHECK(std::fabs(r.determinant() - 1) <= kEval * eps<S>());
}

/// Every kinematic identity at one state: with the given rate, and with the rate of a finite
/// omega (thetadot(theta, omega), large near a singularity).
template <class P, class S>
void check_all_identities(const Coords<P, S>& theta, const Coords<P, S>& td,
                          const Vector3<double>& omega, const Vector3<double>& alpha, bool sharp,
                          Worst& worst) {
  check_orthonormal<P, S>(theta);
  check_kinematics<P, S>(theta, td, sharp, worst);
  check_gdot<P, S>(theta, td, sharp, worst);
  if (!(cond_G<P>(to_ld(theta)) * eps<S>() < 1)) {
    // No digit of G^-1 is determined in S: the state is singular in S (proper Euler angles at
    // the identity, where sin t2 = 0 exactly, or a state nearer to lock than S resolves).
    return;
  }
  check_inverse<P, S>(theta, omega, worst);
  check_thetaddot<P, S>(theta, td, alpha, worst);
  const Coords<P, S> td_omega = P::thetadot(theta, to_s<S>(omega));
  check_kinematics<P, S>(theta, td_omega, false, worst);
  check_gdot<P, S>(theta, td_omega, false, worst);
  check_thetaddot<P, S>(theta, td_omega, alpha, worst);
}

// ------------------------------------------------------------------------------------------------
// Static interface and identity
// ------------------------------------------------------------------------------------------------

template <class P, class S> constexpr bool signatures_for_scalar() {
  using C = Coords<P, S>;
  static_assert(C::RowsAtCompileTime == P::size && C::ColsAtCompileTime == 1);
  const C* theta = nullptr;
  const Vector3<S>* w = nullptr;
  const Matrix3<S>* r = nullptr;
  const Eigen::Quaternion<S>* q = nullptr;
  static_assert(std::is_same_v<decltype(P::rotation(*theta)), Matrix3<S>>);
  static_assert(std::is_same_v<decltype(P::G(*theta)), GMatrix<P, S>>);
  static_assert(std::is_same_v<decltype(P::Gdot_thetadot(*theta, *theta)), Vector3<S>>);
  static_assert(std::is_same_v<decltype(P::thetadot(*theta, *w)), C>);
  static_assert(std::is_same_v<decltype(P::thetaddot(*theta, *theta, *w)), C>);
  static_assert(std::is_same_v<decltype(P::from_rotation(*r)), C>);
  static_assert(std::is_same_v<decltype(P::to_quaternion(*theta)), Eigen::Quaternion<S>>);
  static_assert(std::is_same_v<decltype(P::from_quaternion(*q)), C>);
  static_assert(std::is_same_v<decltype(P::singularity_distance(*theta)), S>);
  static_assert(std::is_same_v<decltype(P::canonical(*theta)), C>);
  static_assert(std::is_same_v<decltype(P::omega(*theta, *theta)), Vector3<S>>);
  // The overloads of the precomputed functions of theta (concept.hpp).
  using Pre = typename P::template Precomputed<S>;
  const Pre* pre = nullptr;
  static_assert(std::is_same_v<decltype(P::precompute(*theta)), Pre>);
  static_assert(std::is_same_v<decltype(P::rotation(*pre)), Matrix3<S>>);
  static_assert(std::is_same_v<decltype(P::G(*pre)), GMatrix<P, S>>);
  static_assert(std::is_same_v<decltype(P::omega(*pre, *theta)), Vector3<S>>);
  static_assert(std::is_same_v<decltype(P::Gdot_thetadot(*pre, *theta)), Vector3<S>>);
  static_assert(std::is_same_v<decltype(P::thetadot(*pre, *w)), C>);
  static_assert(std::is_same_v<decltype(P::thetaddot(*pre, *theta, *w)), C>);
  if constexpr (P::has_constraint) {
    static_assert(std::is_same_v<decltype(P::constraint(*theta)), S>);
  }
  return true;
}

/// Takes the address of every function for S, which instantiates its definition (so that members
/// no test calls still compile, for long double as well).
template <class P, class S> int instantiate_all() {
  // The functions of theta and their overloads of P::Precomputed<S> (concept.hpp): the casts
  // pick one overload each.
  using C = Coords<P, S>;
  using Pre = typename P::template Precomputed<S>;
  using V3 = Vector3<S>;
  const void* fns[] = {
      reinterpret_cast<const void*>(static_cast<Matrix3<S> (*)(const C&)>(&P::rotation)),
      reinterpret_cast<const void*>(static_cast<GMatrix<P, S> (*)(const C&)>(&P::G)),
      reinterpret_cast<const void*>(static_cast<V3 (*)(const C&, const C&)>(&P::omega)),
      reinterpret_cast<const void*>(static_cast<V3 (*)(const C&, const C&)>(&P::Gdot_thetadot)),
      reinterpret_cast<const void*>(static_cast<C (*)(const C&, const V3&)>(&P::thetadot)),
      reinterpret_cast<const void*>(
          static_cast<C (*)(const C&, const C&, const V3&)>(&P::thetaddot)),
      reinterpret_cast<const void*>(static_cast<Pre (*)(const C&)>(&P::precompute)),
      reinterpret_cast<const void*>(static_cast<Matrix3<S> (*)(const Pre&)>(&P::rotation)),
      reinterpret_cast<const void*>(static_cast<GMatrix<P, S> (*)(const Pre&)>(&P::G)),
      reinterpret_cast<const void*>(static_cast<V3 (*)(const Pre&, const C&)>(&P::omega)),
      reinterpret_cast<const void*>(static_cast<V3 (*)(const Pre&, const C&)>(&P::Gdot_thetadot)),
      reinterpret_cast<const void*>(static_cast<C (*)(const Pre&, const V3&)>(&P::thetadot)),
      reinterpret_cast<const void*>(
          static_cast<C (*)(const Pre&, const C&, const V3&)>(&P::thetaddot)),
      reinterpret_cast<const void*>(&P::template from_rotation<S>),
      reinterpret_cast<const void*>(&P::template to_quaternion<S>),
      reinterpret_cast<const void*>(&P::template from_quaternion<S>),
      reinterpret_cast<const void*>(&P::template singularity_distance<S>),
      reinterpret_cast<const void*>(&P::template canonical<S>),
  };
  int n = 0;
  for (const void* f : fns) {
    n += f != nullptr;
  }
  if constexpr (P::has_constraint) {
    n += &P::template constraint<S> != nullptr;
  }
  return n;
}

/// The distance to the nearest singular attitude at the identity, from where each chart is
/// singular (docs/conventions.md): none for Euler parameters, pi/2 to t2 = +-pi/2 (Tait-Bryan),
/// 0 (proper Euler angles are singular at t2 = 0), pi to the rotations by pi (Gibbs), 2 pi to the
/// rotation by 2 pi (MRP, rotation vector).
template <class P> LD identity_distance() {
  switch (kind_of<P>()) {
    case Kind::kEulerParameters:
      return kInf;
    case Kind::kTaitBryan:
      return kPi / 2;
    case Kind::kProperEuler:
      return 0;
    case Kind::kGibbs:
      return kPi;
    case Kind::kMrp:
    case Kind::kRotationVector:
      return 2 * kPi;
    case Kind::kOther:
      break;
  }
  return -1;
}

TEMPLATE_LIST_TEST_CASE("properties: static interface and the identity",
                        "[orientation][properties]", TUMBLE_CASES) {
  using P = typename TestType::First;
  using S = typename TestType::Second;
  using C = Coords<P, S>;
  static_assert(Orientation<P>);
  static_assert(std::is_empty_v<P>, "parameterizations are stateless");
  static_assert(P::size == 3 || P::size == 4);
  static_assert(P::has_constraint == (P::size == 4), "four coordinates of SO(3) need a constraint");
  constexpr std::string_view name = P::name;
  static_assert(!name.empty());
  static_assert(signatures_for_scalar<P, S>() && signatures_for_scalar<P, long double>());
  STATIC_REQUIRE(kind_of<P>() != Kind::kOther);  // a new chart: teach this suite its singularities
  INFO(P::name << " in " << scalar_name<S>());

  const C theta0 = P::from_rotation(Matrix3<S>(Matrix3<S>::Identity()));
  REQUIRE(finite(theta0));
  CHECK(max_abs(to_ld(P::rotation(theta0)) - Matrix3<LD>::Identity()) <= kEval * eps<S>());
  const Eigen::Quaternion<S> q0 = P::to_quaternion(theta0);
  CHECK(std::fabs(std::fabs(static_cast<LD>(detail::value(q0.w()))) - 1) <= kEval * eps<S>());
  CHECK(max_abs(to_ld(q0.vec())) <= kEval * eps<S>());

  // Zero rates give zero omega, zero Gdot thetadot, and zero parameter rates and accelerations:
  // every map is linear (or bilinear) in the rates, so the zeros are exact.
  const C zero = C::Zero();
  const Vector3<S> w0 = Vector3<S>::Zero();
  CHECK(max_abs(P::G(theta0) * zero) == 0);
  CHECK(max_abs(P::Gdot_thetadot(theta0, zero)) == 0);
  const LD d0 = static_cast<LD>(detail::value(P::singularity_distance(theta0)));
  const LD expected = identity_distance<P>();
  if (std::isinf(static_cast<double>(expected))) {
    CHECK(std::isinf(static_cast<double>(d0)));
  } else {
    CHECK(std::fabs(d0 - expected) <= 4 * eps<S>() * 2 * kPi);
  }
  if (d0 > 0) {  // the inverse map exists at the identity
    CHECK(max_abs(P::thetadot(theta0, w0)) == 0);
    CHECK(max_abs(P::thetaddot(theta0, zero, w0)) == 0);
    // ... and is the inverse of G there.
    const Vector3<S> w = to_s<S>(Vector3<double>(0.3, -0.2, 0.5));
    CHECK(max_abs(to_ld(P::G(theta0) * P::thetadot(theta0, w)) - to_ld(w)) <=
          kEval * eps<S>() * norm(w));
  }
  if constexpr (P::has_constraint) {
    CHECK(std::fabs(static_cast<LD>(detail::value(P::constraint(theta0)))) <= kEval * eps<S>());
  }
  CHECK(instantiate_all<P, S>() > 0);
  CHECK(instantiate_all<P, long double>() > 0);
}

// ------------------------------------------------------------------------------------------------
// Round trips and conversions
// ------------------------------------------------------------------------------------------------

TEMPLATE_LIST_TEST_CASE("properties: round trips rotation -> coordinates -> rotation and through "
                        "the quaternion",
                        "[orientation][properties]", TUMBLE_CASES) {
  using P = typename TestType::First;
  using S = typename TestType::Second;
  using C = Coords<P, S>;
  INFO(P::name << " in " << scalar_name<S>());
  test::Random rng(11);
  for (int i = 0; i < kRandomStates; ++i) {
    const Eigen::Quaterniond qd = rng.quaternion();
    // The reference: Eigen's quaternion -> matrix, rounded to S (and so exactly the input).
    const Matrix3<S> r = to_s<S>(qd.toRotationMatrix());
    const Eigen::Quaternion<S> q(to_s<S>(qd.coeffs()));  // (x, y, z, w) storage
    INFO("q = " << str(qd.coeffs()) << " (x, y, z, w)");

    const C theta = P::from_rotation(r);
    REQUIRE(finite(theta));
    CHECK(max_abs(to_ld(P::rotation(theta)) - to_ld(r)) <= kTwo * eps<S>());

    const C theta_q = P::from_quaternion(q);
    REQUIRE(finite(theta_q));
    const Eigen::Matrix<LD, 4, 1> back = to_ld(P::to_quaternion(theta_q).coeffs());
    const Eigen::Matrix<LD, 4, 1> ref = to_ld(q.coeffs());
    CHECK(std::min(max_abs(back - ref), max_abs(back + ref)) <= kTwo * eps<S>());
    // Both routes give the same attitude.
    CHECK(max_abs(to_ld(P::rotation(theta_q)) - to_ld(r)) <= kTwo * eps<S>());
  }
}

TEMPLATE_LIST_TEST_CASE("properties: convert<To, From> reproduces R for every pair",
                        "[orientation][properties]", TUMBLE_PAIRS) {
  using To = typename TestType::First;
  using From = typename TestType::Second;
  INFO(From::name << " -> " << To::name);
  test::Random rng(12);
  for (int i = 0; i < kRandomStates; ++i) {
    const Eigen::Quaterniond q = rng.quaternion();
    const Coords<From, double> from = From::from_quaternion(q);
    const Coords<To, double> to = convert<To, From>(from);
    INFO("from = " << str(from) << ", to = " << str(to));
    REQUIRE(finite(to));
    // Eigen's matrix of q is the independent reference; both charts must reproduce it.
    CHECK(max_abs(To::rotation(to) - q.toRotationMatrix()) <= kTwo * kEpsD);
    CHECK(max_abs(To::rotation(to) - From::rotation(from)) <= kTwo * kEpsD);
  }
}

TEMPLATE_LIST_TEST_CASE("properties: R is orthonormal with det +1", "[orientation][properties]",
                        TUMBLE_CASES) {
  using P = typename TestType::First;
  using S = typename TestType::Second;
  INFO(P::name << " in " << scalar_name<S>());
  for (const auto& s : random_states<P>(13)) {
    check_orthonormal<P, S>(to_s<S>(s.theta));
  }
}

// ------------------------------------------------------------------------------------------------
// Kinematics on random states
// ------------------------------------------------------------------------------------------------

TEMPLATE_LIST_TEST_CASE("properties: kinematics S(G thetadot) = R^T Rdot",
                        "[orientation][properties]", TUMBLE_CASES) {
  using P = typename TestType::First;
  using S = typename TestType::Second;
  INFO(P::name << " in " << scalar_name<S>());
  Worst worst;
  for (const auto& s : random_states<P>(21)) {
    check_kinematics<P, S>(to_s<S>(s.theta), to_s<S>(s.thetadot), true, worst);
  }
}

TEMPLATE_LIST_TEST_CASE("properties: Gdot thetadot against differences and AD of G",
                        "[orientation][properties]", TUMBLE_CASES) {
  using P = typename TestType::First;
  using S = typename TestType::Second;
  INFO(P::name << " in " << scalar_name<S>());
  Worst worst;
  for (const auto& s : random_states<P>(22)) {
    check_gdot<P, S>(to_s<S>(s.theta), to_s<S>(s.thetadot), true, worst);
  }
}

TEMPLATE_LIST_TEST_CASE("properties: inverse map G thetadot(theta, omega) = omega",
                        "[orientation][properties]", TUMBLE_CASES) {
  using P = typename TestType::First;
  using S = typename TestType::Second;
  INFO(P::name << " in " << scalar_name<S>());
  Worst worst;
  for (const auto& s : random_states<P>(23)) {
    check_inverse<P, S>(to_s<S>(s.theta), s.omega, worst);
  }
}

TEMPLATE_LIST_TEST_CASE("properties: thetaddot satisfies G thetaddot + Gdot thetadot = alpha",
                        "[orientation][properties]", TUMBLE_CASES) {
  using P = typename TestType::First;
  using S = typename TestType::Second;
  INFO(P::name << " in " << scalar_name<S>());
  Worst worst;
  for (const auto& s : random_states<P>(24)) {
    check_thetaddot<P, S>(to_s<S>(s.theta), to_s<S>(s.thetadot), s.alpha, worst);
  }
}

// ------------------------------------------------------------------------------------------------
// Near-zero and near-singular inputs
// ------------------------------------------------------------------------------------------------

/// Coordinates at and near the identity: exactly the identity (from_rotation(I)), small
/// rotations through from_quaternion, and raw coordinates of norm 1e-12 ... 2.1 along random
/// directions (through every small-angle threshold a chart may use: they are derived from the
/// scalar's epsilon, e.g. ~1e-4 ... 2 for the rotation vector).
template <class P> std::vector<Coords<P, double>> near_zero_states() {
  test::Random rng(31);
  std::vector<Coords<P, double>> out;
  out.push_back(P::from_rotation(Eigen::Matrix3d(Eigen::Matrix3d::Identity())));
  for (const double a : {1e-8, 1e-12}) {
    const Eigen::Vector3d n = rng.vector().normalized();
    out.push_back(P::from_quaternion(Eigen::Quaterniond(Eigen::AngleAxisd(a, n))));
  }
  for (const double a : {1e-12, 1e-8, 1e-6, 1e-5, 1e-4, 1e-3, 1e-2, 0.1, 0.5, 1.1, 1.7, 2.1}) {
    const Eigen::Vector3d n = rng.vector().normalized();
    if constexpr (P::size == 4) {
      out.push_back(Eigen::Vector4d(1, a * n(0), a * n(1), a * n(2)).normalized());
    } else {
      out.push_back(a * n);
    }
  }
  return out;
}

TEMPLATE_LIST_TEST_CASE("properties: near-zero inputs (and exactly zero, also for AD)",
                        "[orientation][properties]", TUMBLE_CASES) {
  using P = typename TestType::First;
  using S = typename TestType::Second;
  INFO(P::name << " in " << scalar_name<S>());
  test::Random rng(32);
  Worst worst;
  for (const auto& theta : near_zero_states<P>()) {
    const Coords<P, S> th = to_s<S>(theta);
    const Coords<P, S> td = to_s<S>(random_rate<P>(rng, theta));
    const Vector3<double> omega = rng.vector();
    const Vector3<double> alpha = rng.vector();
    INFO("near-zero state " << str(th) << ", cond(G) = " << double(cond_G<P>(to_ld(th))));
    check_all_identities<P, S>(th, td, omega, alpha, true, worst);
    // R close to I: |R - I| <= the rotation angle, known from the construction (<= |theta| up
    // to a chart-dependent factor of at most 4 for MRP).
    CHECK(max_abs(to_ld(P::rotation(th)) - Matrix3<LD>::Identity()) <=
          4 * to_ld(th).template tail<3>().norm() + kEval * eps<S>());
  }
}

/// A state near a singular attitude with the distance known from its construction.
template <class P, class S> struct NearSingular {
  Coords<P, S> theta;
  LD distance;  // computed from the rounded coordinates in long double
  std::string what;
};

/// For each chart, coordinates at the distance delta (before rounding to S) from a singular
/// attitude, on both sides where both exist:
///   Tait-Bryan  t2 = +-(pi/2 - delta);         distance | |t2| - pi/2 |
///   proper      t2 = delta, -delta, pi - delta; distance min(|t2|, pi - |t2|)
///   Gibbs       phi = pi - delta, g = n tan(phi/2);     distance pi - 2 atan|g| = 2 atan(1/|g|)
///   MRP         phi = 2 pi - delta, s = n tan(phi/4);   distance 2 pi - 4 atan|s| = 4 atan(1/|s|)
///   rotation vector  phi = 2 pi -+ delta, v = phi n;    distance |2 pi - |v||
template <class P, class S>
std::vector<NearSingular<P, S>> near_singular_states(LD delta, test::Random& rng) {
  std::vector<NearSingular<P, S>> out;
  const auto add = [&](const Coords<P, LD>& theta, const std::string& what, auto distance) {
    const Coords<P, S> t = to_s<S>(theta);
    out.push_back({t, distance(to_ld(t)), what});
  };
  const Vector3<LD> n = rng.vector().normalized().template cast<LD>();
  const LD t1 = rng.uniform(-3, 3);
  const LD t3 = rng.uniform(-3, 3);
  constexpr Kind kind = kind_of<P>();
  if constexpr (kind == Kind::kTaitBryan) {
    const auto d = [](const Coords<P, LD>& t) { return std::fabs(std::fabs(t(1)) - kPi / 2); };
    add(Coords<P, LD>(t1, kPi / 2 - delta, t3), "t2 = pi/2 - delta", d);
    add(Coords<P, LD>(t1, -(kPi / 2 - delta), t3), "t2 = -(pi/2 - delta)", d);
  } else if constexpr (kind == Kind::kProperEuler) {
    const auto d = [](const Coords<P, LD>& t) {
      return std::min(std::fabs(t(1)), kPi - std::fabs(t(1)));
    };
    add(Coords<P, LD>(t1, delta, t3), "t2 = delta", d);
    add(Coords<P, LD>(t1, -delta, t3), "t2 = -delta", d);
    add(Coords<P, LD>(t1, kPi - delta, t3), "t2 = pi - delta", d);
  } else if constexpr (kind == Kind::kGibbs) {
    add(Coords<P, LD>(std::tan((kPi - delta) / 2) * n), "phi = pi - delta",
        [](const Coords<P, LD>& g) { return 2 * std::atan(1 / g.norm()); });
  } else if constexpr (kind == Kind::kMrp) {
    add(Coords<P, LD>(std::tan((2 * kPi - delta) / 4) * n), "phi = 2 pi - delta",
        [](const Coords<P, LD>& s) { return 4 * std::atan(1 / s.norm()); });
  } else if constexpr (kind == Kind::kRotationVector) {
    const auto d = [](const Coords<P, LD>& v) { return std::fabs(2 * kPi - v.norm()); };
    add(Coords<P, LD>((2 * kPi - delta) * n), "phi = 2 pi - delta", d);
    add(Coords<P, LD>((2 * kPi + delta) * n), "phi = 2 pi + delta", d);
  }
  return out;
}

TEMPLATE_LIST_TEST_CASE("properties: near-singular inputs: identities scaled by cond(G), and "
                        "singularity_distance",
                        "[orientation][properties]", TUMBLE_CASES) {
  using P = typename TestType::First;
  using S = typename TestType::Second;
  INFO(P::name << " in " << scalar_name<S>());
  test::Random rng(41);
  Worst worst;
  // 1e-4 degrees (the Gibbs vector at 179.9999 degrees), 1e-6 rad and 1e-9 rad.
  for (const LD delta : {1e-4L * kPi / 180, 1e-6L, 1e-9L}) {
    for (const auto& s : near_singular_states<P, S>(delta, rng)) {
      const LD cond = cond_G<P>(to_ld(s.theta));
      INFO(s.what << ", delta = " << double(delta) << ": theta = " << str(s.theta)
                  << ", distance from the construction = " << double(s.distance)
                  << ", cond(G) = " << double(cond));
      // The distance: a difference of angles of at most 2 pi, each within an ulp or two of its
      // value in S (pi itself is rounded to S), so within 4 eps_S * 2 pi.
      const LD d = static_cast<LD>(detail::value(P::singularity_distance(s.theta)));
      CHECK(std::fabs(d - s.distance) <= 4 * eps<S>() * 2 * kPi);
      // A state nearer to the singular attitude than S resolves there (one ulp of an angle of
      // up to 2 pi, 2 pi eps_S: 7.5e-7 in float) is the singular attitude itself in S; float at
      // 1e-9 rad is one. Its identities are not defined in S (for MRP in float the parameter
      // rates of a finite omega, ~|s|^2 = 1.6e19, then overflow in |sdot|^2).
      const Coords<P, double> td = random_rate<P>(rng, to_d(s.theta));
      const Vector3<double> omega = rng.vector();
      const Vector3<double> alpha = rng.vector();
      if (s.distance > 2 * kPi * eps<S>()) {
        check_all_identities<P, S>(s.theta, to_s<S>(td), omega, alpha, false, worst);
      }
    }
  }
  if constexpr (kind_of<P>() == Kind::kEulerParameters) {
    for (const auto& s : random_states<P>(42)) {
      CHECK(std::isinf(
          static_cast<double>(detail::value(P::singularity_distance(to_s<S>(s.theta))))));
    }
  }
}

// ------------------------------------------------------------------------------------------------
// canonical()
// ------------------------------------------------------------------------------------------------

/// The attitude of any coordinates, independently of P::rotation: Eigen's matrix of the
/// normalized quaternion.
template <class P, class S> Matrix3<LD> attitude(const Coords<P, S>& theta) {
  const Eigen::Quaternion<LD> q(to_ld(P::to_quaternion(theta).coeffs()));
  return q.normalized().toRotationMatrix();
}

TEMPLATE_LIST_TEST_CASE("properties: canonical() keeps the attitude and satisfies the constraint",
                        "[orientation][properties]", TUMBLE_CASES) {
  using P = typename TestType::First;
  using S = typename TestType::Second;
  using C = Coords<P, S>;
  INFO(P::name << " in " << scalar_name<S>());
  test::Random rng(51);
  for (const auto& s : random_states<P>(52)) {
    Coords<P, double> raw = s.theta;
    if constexpr (P::has_constraint) {
      raw *= std::exp(rng.uniform(-2.3, 2.3));  // |p| from 0.1 to 10: off the constraint
    }
    const C theta = to_s<S>(raw);
    const C c = P::canonical(theta);
    INFO("theta = " << str(theta) << ", canonical = " << str(c));
    REQUIRE(finite(c));
    CHECK(max_abs(to_ld(P::rotation(c)) - attitude<P, S>(theta)) <= kTwo * eps<S>());
    if constexpr (!P::has_constraint) {
      // On the chart every coordinate vector is an attitude: R itself is unchanged.
      CHECK(max_abs(to_ld(P::rotation(c)) - to_ld(P::rotation(theta))) <= kTwo * eps<S>());
    } else {
      CHECK(std::fabs(static_cast<LD>(detail::value(P::constraint(c)))) <= kEval * eps<S>());
    }
    // The canonical representative is canonical: a second application changes nothing.
    CHECK(max_abs(to_ld(P::canonical(c)) - to_ld(c)) <=
          kEval * eps<S>() * std::max(LD(1), norm(c)));
    // ... and never nearer to a singularity (the point of the MRP shadow set and of wrapping the
    // rotation vector).
    const LD d_before = static_cast<LD>(detail::value(P::singularity_distance(theta)));
    const LD d_after = static_cast<LD>(detail::value(P::singularity_distance(c)));
    if (std::isfinite(static_cast<double>(d_before))) {
      CHECK(d_after >= d_before - 4 * eps<S>() * 2 * kPi);
    }
  }
}

// ------------------------------------------------------------------------------------------------
// Cross-parameterization agreement
// ------------------------------------------------------------------------------------------------

TEMPLATE_LIST_TEST_CASE("properties: every chart describes the same physical motion",
                        "[orientation][properties]", TUMBLE_CASES) {
  using P = typename TestType::First;
  using S = typename TestType::Second;
  using C = Coords<P, S>;
  INFO(P::name << " in " << scalar_name<S>());
  // The same physical states (R, omega, alpha) for every P and S: the seed is fixed.
  test::Random rng(61);
  for (int i = 0; i < kRandomStates; ++i) {
    const Eigen::Quaterniond q = rng.quaternion();
    const Vector3<double> omega = rng.vector();
    const Vector3<double> alpha = rng.vector();
    const Matrix3<S> r = to_s<S>(q.toRotationMatrix());
    const C theta = P::from_rotation(r);
    const LD cond = cond_G<P>(to_ld(theta));
    INFO("q = " << str(q.coeffs()) << ", theta = " << str(theta) << ", cond(G) = " << double(cond));
    REQUIRE(std::isfinite(static_cast<double>(cond)));
    // The same R ...
    CHECK(max_abs(to_ld(P::rotation(theta)) - to_ld(r)) <= kTwo * eps<S>());
    // ... the same quaternion up to sign ...
    const Eigen::Matrix<LD, 4, 1> qp = to_ld(P::to_quaternion(theta).coeffs());
    const Eigen::Matrix<LD, 4, 1> qr = q.coeffs().template cast<LD>();
    CHECK(std::min(max_abs(qp - qr), max_abs(qp + qr)) <= kTwo * eps<S>());
    // ... the same omega, read off R^T Rdot with Rdot by AD of P::rotation (not through G) ...
    const C td = P::thetadot(theta, to_s<S>(omega));
    const Matrix3<LD> w_ad = rt_rdot_ad<P>(to_ld(theta), to_ld(td));
    const Vector3<LD> omega_back(w_ad(2, 1), w_ad(0, 2), w_ad(1, 0));
    CHECK(max_abs(omega_back - omega.cast<LD>()) <=
          kEval * (eps<S>() + kEpsD) * cond * omega.norm());
    // ... and thetaddot maps back to the same alpha: the AD derivative of G(theta(t)) thetadot(t).
    const C tdd = P::thetaddot(theta, td, to_s<S>(alpha));
    const Vector3<LD> alpha_back = omega_dot_ad<P>(to_ld(theta), to_ld(td), to_ld(tdd));
    const LD scale = cond * (alpha.norm() + gdot_ad<P>(to_ld(theta), to_ld(td)).norm() * norm(td));
    CHECK(max_abs(alpha_back - alpha.cast<LD>()) <= kEval * (eps<S>() + kEpsD) * scale);
  }
}

// ------------------------------------------------------------------------------------------------
// AD derivatives of every function against differences
// ------------------------------------------------------------------------------------------------

/// Compares the AD derivative of y = f(x(t)) along one direction with long double differences of
/// the same function. Scale: |dy/dt| + |y| / (8 h0) (the size of the derivative and of the
/// function over the differences' length) + `extra` (for a quantity computed with cancellation,
/// the size of its terms' derivatives), times `amplify` (cond(G)^2 for the inverse map and
/// thetaddot, whose derivatives contain G^-1 twice). Functions with branch cuts or kinks
/// (`may_jump`) skip a state whose differences straddle one, which their error bound shows.
template <class YAd, class FLd>
bool check_ad(const char* what, const YAd& y_ad, FLd&& f_ld, LD h0, LD extra, LD amplify,
              bool may_jump) {
  const auto d_ad = test::ad_derivatives(y_ad).template cast<LD>().eval();
  const auto y = test::ad_values(y_ad).template cast<LD>().eval();
  const auto fd = test::richardson_derivative(f_ld, h0);
  const LD scale = fd.value.norm() + y.norm() / (8 * h0) + extra;
  if (may_jump && fd.error > kEval * kEpsD * amplify * scale) {
    return false;  // the differences are not sharp here: they straddle a jump or a kink
  }
  INFO(what << ": AD " << str(d_ad) << ", differences " << str(fd.value) << " (error bound "
            << double(fd.error) << "), scale " << double(scale));
  CHECK(finite(d_ad));
  CHECK(max_abs(d_ad - fd.value) <= kEval * kEpsD * amplify * scale + fd.error);
  return true;
}

/// Runs f() (true: passed) in a child process where the platform has fork(), so that an
/// assertion inside Eigen (debug builds) becomes this check's failure instead of ending the whole
/// test run. The child prints its own diagnostics to stderr.
template <class F> std::string run_isolated(F&& f) {
#if TUMBLE_TEST_HAVE_FORK
  std::fflush(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    const bool ok = f();
    std::fflush(nullptr);
    std::_Exit(ok ? 0 : 1);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  if (WIFEXITED(status)) {
    return WEXITSTATUS(status) == 0 ? "passed" : "wrong values (see stderr)";
  }
  return "killed by signal " + std::to_string(WTERMSIG(status)) +
         " (an assertion in Eigen: see stderr)";
#else
  return f() ? "passed" : "wrong values (see stderr)";
#endif
}

template <class M> Eigen::Matrix<typename M::Scalar, M::SizeAtCompileTime, 1> flat(const M& m) {
  return Eigen::Map<const Eigen::Matrix<typename M::Scalar, M::SizeAtCompileTime, 1>>(m.data());
}

TEMPLATE_LIST_TEST_CASE("properties: AD derivatives of every function match differences",
                        "[orientation][properties]", TUMBLE_TEST_PARAMETERIZATIONS) {
  using P = TestType;
  using CL = Coords<P, LD>;
  using CA = Coords<P, AD>;
  using Scalar1 = Eigen::Matrix<LD, 1, 1>;
  using Scalar1AD = Eigen::Matrix<AD, 1, 1>;
  INFO(P::name);
  test::Random rng(71);
  std::vector<Coords<P, double>> states;
  for (const auto& s : random_states<P>(72)) {
    // Moderately conditioned states: conditioning near the singularities is the near-singular
    // case's subject; here the subject is that derivatives flow through every branch.
    if (cond_G<P>(s.theta.template cast<LD>()) <= 20) {
      states.push_back(s.theta);
    }
  }
  for (const auto& z : near_zero_states<P>()) {
    if (cond_G<P>(z.template cast<LD>()) <= 20) {
      states.push_back(z);  // exactly zero and tiny: the small-angle branches
    }
  }
  int skipped = 0;
  int jumpy = 0;
  for (const auto& theta : states) {
    const Coords<P, double> u = random_rate<P>(rng, theta);
    const Coords<P, double> td = random_rate<P>(rng, theta);
    const Vector3<double> w = rng.vector();
    const Vector3<double> a = rng.vector();
    const CA x = test::ad_seed(theta, u);  // theta + t u
    // The other arguments are constants, with zero derivative vectors of the same size (mixing
    // in empty ones is the subject of the next test case).
    const CA td_c = test::ad_constant(td);
    const Vector3<AD> w_c = test::ad_constant(w);
    const Vector3<AD> a_c = test::ad_constant(a);
    const CL th = theta.template cast<LD>();
    const CL ul = u.template cast<LD>();
    const CL tdl = td.template cast<LD>();
    const Vector3<LD> wl = w.cast<LD>();
    const Vector3<LD> al = a.cast<LD>();
    const LD cond = cond_G<P>(th);
    // The differences' length: the chart's, and near a singularity a fraction of the distance to
    // it (in coordinates: the attitude moves at most sigma_max(G) |u| per unit t), so that no
    // step reaches the singularity or the kink of singularity_distance there.
    const LD dist = static_cast<LD>(P::singularity_distance(theta));
    const LD length = std::min(chart_length<P>(th), dist / (2 * singular_values<P>(th)(0)));
    const LD h0 = length / (8 * ul.norm());
    const auto at = [&](LD h) { return CL(th + h * ul); };
    INFO("theta = " << str(theta) << ", direction = " << str(u));

    check_ad(
        "rotation", flat(P::rotation(x)), [&](LD h) { return flat(P::rotation(at(h))); }, h0, 0, 1,
        false);
    check_ad(
        "G", flat(GMatrix<P, AD>(P::G(x))), [&](LD h) { return flat(GMatrix<P, LD>(P::G(at(h)))); },
        h0, 0, 1, false);
    check_ad(
        "Gdot_thetadot", P::Gdot_thetadot(x, td_c),
        [&](LD h) { return P::Gdot_thetadot(at(h), tdl); }, h0, 0, 1, false);
    check_ad(
        "thetadot", P::thetadot(x, w_c), [&](LD h) { return P::thetadot(at(h), wl); }, h0, 0,
        cond * cond, false);
    check_ad(
        "thetaddot", P::thetaddot(x, td_c, a_c), [&](LD h) { return P::thetaddot(at(h), tdl, al); },
        h0, 0, cond * cond, false);
    check_ad(
        "to_quaternion", Vector4<AD>(P::to_quaternion(x).coeffs()),
        [&](LD h) { return Vector4<LD>(P::to_quaternion(at(h)).coeffs()); }, h0, 0, 1, false);
    if constexpr (P::has_constraint) {
      // |p|^2 - 1 cancels: the scale of its derivative is that of its terms, 2 |p| |u|.
      check_ad(
          "constraint", Scalar1AD(P::constraint(x)),
          [&](LD h) { return Scalar1(P::constraint(at(h))); }, h0, 2 * th.norm() * ul.norm(), 1,
          false);
    }
    // Branch cuts: the MRP shadow switch at |s| = 1, the rotation vector's wrap at pi, the
    // principal ranges of the angles returned by from_rotation / from_quaternion.
    // (singularity_distance: the next test case.)
    jumpy += 3;
    skipped += !check_ad(
        "canonical", P::canonical(x), [&](LD h) { return P::canonical(at(h)); }, h0, 0, 1, true);
    // A path of attitudes: q(t) = normalize(q0 + t v) with q0 the quaternion of theta; the
    // attitude moves at most 2 |v| per unit t.
    const Eigen::Vector4d q0 = P::to_quaternion(theta).coeffs().normalized();
    const Eigen::Vector4d v(rng.normal(), rng.normal(), rng.normal(), rng.normal());
    const LD hq = std::min(LD(1), dist / 4) / (8 * v.norm());
    const auto q_ld = [&](LD h) {
      const Eigen::Matrix<LD, 4, 1> c = (q0.cast<LD>() + h * v.cast<LD>()).normalized();
      return Eigen::Quaternion<LD>(c);
    };
    Eigen::Matrix<AD, 4, 1> qa = test::ad_seed(q0, v);
    qa /= sqrt(qa.squaredNorm());
    const Eigen::Quaternion<AD> q_ad(qa);
    skipped += !check_ad(
        "from_quaternion", P::from_quaternion(q_ad),
        [&](LD h) { return P::from_quaternion(q_ld(h)); }, hq, 0, cond, true);
    skipped += !check_ad(
        "from_rotation", P::from_rotation(Matrix3<AD>(q_ad.toRotationMatrix())),
        [&](LD h) { return P::from_rotation(Matrix3<LD>(q_ld(h).toRotationMatrix())); }, hq, 0,
        cond, true);
  }
  INFO(skipped << " of " << jumpy << " branch-cut comparisons skipped");
  CHECK(skipped * 10 <= jumpy);  // a jump near a random state is rare
}

/// singularity_distance through AD: its derivative along a direction against long double
/// differences, away from its kinks (where the nearest singular attitude changes, e.g. t2 = 0 for
/// Tait-Bryan angles; a state whose differences straddle one is skipped, as their error bound
/// shows). Run in a child process (run_isolated): Eigen asserts in debug builds when AD scalars
/// with empty and non-empty derivative vectors meet inside one expression.
TEMPLATE_LIST_TEST_CASE("properties: AD derivative of singularity_distance matches differences",
                        "[orientation][properties]", TUMBLE_TEST_PARAMETERIZATIONS) {
  using P = TestType;
  using CL = Coords<P, LD>;
  INFO(P::name);
  if constexpr (kind_of<P>() != Kind::kEulerParameters) {  // +infinity, constant
    const auto states = random_states<P>(73);
    const std::string result = run_isolated([&] {
      test::Random rng(74);
      int bad = 0;
      int skipped = 0;
      for (const auto& s : states) {
        const Coords<P, double> u = random_rate<P>(rng, s.theta);
        const CL th = s.theta.template cast<LD>();
        const CL ul = u.template cast<LD>();
        const LD dist = static_cast<LD>(P::singularity_distance(s.theta));
        const LD length = std::min(chart_length<P>(th), dist / (2 * singular_values<P>(th)(0)));
        const LD h0 = length / (8 * ul.norm());
        const AD d = P::singularity_distance(Coords<P, AD>(test::ad_seed(s.theta, u)));
        const auto fd = test::richardson_derivative(
            [&](LD h) { return LD(P::singularity_distance(CL(th + h * ul))); }, h0);
        const LD scale = std::fabs(fd.value) + dist / (8 * h0);
        if (fd.error > kEval * kEpsD * scale) {
          ++skipped;
          continue;
        }
        const LD err = std::fabs(static_cast<LD>(test::ad_derivative(d)) - fd.value);
        if (!(err <= kEval * kEpsD * scale + fd.error)) {
          ++bad;
          std::fprintf(stderr, "%s: singularity_distance AD derivative %.17g, differences %.17Lg\n",
                       std::string(P::name).c_str(), test::ad_derivative(d), fd.value);
        }
      }
      return bad == 0 && skipped * 5 <= static_cast<int>(states.size());
    });
    CHECK(result == "passed");
  }
}

// ------------------------------------------------------------------------------------------------
// The 50-digit references
// ------------------------------------------------------------------------------------------------

/// Relative errors of one parameterization against the 50-digit references, in scalar S.
struct ReferenceErrors {
  int states = 0;
  LD rotation = 0;          // |R - R_ref|_max (|R| = 1)
  LD g = 0;                 // |G - G_ref|_max / |G_ref|_max
  LD gdot = 0;              // |Gdot td - ref| / |ref| (2-norms), where the product does not vanish
  LD gdot_scaled = 0;       // |Gdot td - ref| / (|Gdot_ref|_F |td|)
  LD inverse = 0;           // |thetadot(omega) - ref| / |ref|
  LD inverse_per_cond = 0;  // the same divided by cond(G)
  LD thetaddot = 0;         // |thetaddot - ref| / |ref|
  LD thetaddot_per_cond = 0;
};

template <class P, class S> ReferenceErrors reference_errors() {
  using C = Coords<P, S>;
  ReferenceErrors e;
  for (const auto& st : test::reference::states) {
    if (st.parameterization != P::name) {
      continue;
    }
    ++e.states;
    C theta;
    C td;
    for (int i = 0; i < P::size; ++i) {
      theta(i) = S(st.theta[i]);
      td(i) = S(st.thetadot[i]);
    }
    const Vector3<S> w(S(st.omega[0]), S(st.omega[1]), S(st.omega[2]));
    const Vector3<S> a(S(st.alpha[0]), S(st.alpha[1]), S(st.alpha[2]));
    const Eigen::Map<const Eigen::Matrix<LD, 3, 3, Eigen::RowMajor>> r_ref(st.R);
    const Eigen::Map<const Eigen::Matrix<LD, 3, P::size, Eigen::RowMajor>> g_ref(st.G);
    const Eigen::Map<const Eigen::Matrix<LD, 3, P::size, Eigen::RowMajor>> gdot_ref(st.Gdot);
    const Eigen::Map<const Vector3<LD>> gdt_ref(st.Gdot_thetadot);
    const Eigen::Map<const Eigen::Matrix<LD, P::size, 1>> inv_ref(st.thetadot_of_omega);
    const Eigen::Map<const Eigen::Matrix<LD, P::size, 1>> tdd_ref(st.thetaddot);
    const Eigen::JacobiSVD<GMatrix<P, LD>> svd{GMatrix<P, LD>(g_ref)};
    const LD cond = svd.singularValues()(0) / svd.singularValues()(2);

    e.rotation = std::max(e.rotation, max_abs(to_ld(P::rotation(theta)) - r_ref));
    e.g = std::max(e.g, max_abs(to_ld(P::G(theta)) - g_ref) / g_ref.cwiseAbs().maxCoeff());
    const LD gdt_err = (to_ld(P::Gdot_thetadot(theta, td)) - gdt_ref).norm();
    const LD gdt_scale = gdot_ref.norm() * to_ld(td).norm();
    e.gdot_scaled = std::max(e.gdot_scaled, gdt_err / gdt_scale);
    if (gdt_ref.norm() > 1e-3L * gdt_scale) {
      e.gdot = std::max(e.gdot, gdt_err / gdt_ref.norm());
    }
    const LD inv = (to_ld(P::thetadot(theta, w)) - inv_ref).norm() / inv_ref.norm();
    e.inverse = std::max(e.inverse, inv);
    e.inverse_per_cond = std::max(e.inverse_per_cond, inv / cond);
    const LD tdd = (to_ld(P::thetaddot(theta, td, a)) - tdd_ref).norm() / tdd_ref.norm();
    e.thetaddot = std::max(e.thetaddot, tdd);
    e.thetaddot_per_cond = std::max(e.thetaddot_per_cond, tdd / cond);
  }
  return e;
}

TEMPLATE_LIST_TEST_CASE("properties: 50-digit reference values (mpmath, from the definitions)",
                        "[orientation][properties]", TUMBLE_TEST_PARAMETERIZATIONS) {
  using P = TestType;
  INFO(P::name);
  const ReferenceErrors e = reference_errors<P, double>();
  INFO("max rel. errors: R " << double(e.rotation) << ", G " << double(e.g) << ", Gdot thetadot "
                             << double(e.gdot) << " (" << double(e.gdot_scaled)
                             << " of |Gdot||td|), inverse map " << double(e.inverse) << " ("
                             << double(e.inverse_per_cond) << " cond), thetaddot "
                             << double(e.thetaddot) << " (" << double(e.thetaddot_per_cond)
                             << " cond)");
  REQUIRE(e.states >= 4);  // a new parameterization needs references: re-run make_reference.py
  // Targets (the brief): R and G to a small multiple of eps, Gdot thetadot to 1e-13.
  CHECK(e.rotation <= 8 * kEpsD);
  CHECK(e.g <= 8 * kEpsD);
  CHECK(e.gdot <= 1e-13L);
  CHECK(e.gdot_scaled <= 1e-13L);
  CHECK(e.inverse_per_cond <= 8 * kEpsD);
  CHECK(e.thetaddot_per_cond <= 1e-13L);
}

// ------------------------------------------------------------------------------------------------
// The error table (hidden; run `test_orientation "[report]"`)
// ------------------------------------------------------------------------------------------------

template <class P> void report_row() {
  const ReferenceErrors d = reference_errors<P, double>();
  const ReferenceErrors l = reference_errors<P, long double>();
  Worst w;
  for (const auto& s : random_states<P>(81)) {
    check_all_identities<P, double>(s.theta, s.thetadot, s.omega, s.alpha, true, w);
  }
  std::printf("| %-27.*s | %8.1e | %8.1e | %8.1e | %8.1e | %8.1e | %8.1e | %8.1e | %5.1f | %5.1f | "
              "%5.1f | %5.1f |\n",
              static_cast<int>(P::name.size()), P::name.data(), double(d.rotation), double(d.g),
              double(d.gdot_scaled), double(d.inverse), double(d.thetaddot),
              double(std::max({l.rotation, l.g})), double(l.gdot_scaled), double(w.kinematics),
              double(w.gdot), double(w.inverse), double(w.thetaddot));
}

#if TUMBLE_TEST_PRIMARY_SLICE
TEST_CASE("properties: error table per parameterization", "[.][report][orientation][properties]") {
  std::printf(
      "\nWorst errors per parameterization.\n"
      "50-digit references (mpmath, %d states): relative errors of the double results (R: max "
      "abs; G: max abs / max |G|; Gdot td: 2-norm / (|Gdot|_F |td|); inverse map and thetaddot: "
      "2-norm relative), and of long double (R and G, Gdot td).\n"
      "Random states (50 per chart, double, plus their finite-omega rates): worst error in units "
      "of eps * scale against AD (kinematics, Gdot td) and of eps * cond(G) * scale (inverse map "
      "residual, thetaddot residual).\n\n",
      static_cast<int>(std::size(test::reference::states)));
  std::printf("| %-27s | %8s | %8s | %8s | %8s | %8s | %8s | %8s | %5s | %5s | %5s | %5s |\n",
              "parameterization", "R", "G", "Gdot td", "inverse", "thetaddt", "R,G ld", "Gdtd ld",
              "kin", "Gdot", "inv", "tdd");
  std::printf("|-%s-|-%s-|-%s-|-%s-|-%s-|-%s-|-%s-|-%s-|-%s-|-%s-|-%s-|-%s-|\n",
              std::string(27, '-').c_str(), "--------", "--------", "--------", "--------",
              "--------", "--------", "--------", "-----", "-----", "-----", "-----");
  std::apply([](auto... p) { (report_row<decltype(p)>(), ...); }, test::AllParameterizations{});
  std::printf("\n");
  SUCCEED();
}
#endif

// ------------------------------------------------------------------------------------------------
// AD arguments that mix constants and variables
// ------------------------------------------------------------------------------------------------

/// An AD scalar made from a plain number (the natural way to pass a constant) has an EMPTY
/// derivative vector. Eigen's AutoDiff resizes it to its partner's in a binary operation of two
/// plain AD scalars, but not inside compound expressions, where the sizes then disagree (an
/// assertion in debug builds; dropped or garbage derivatives otherwise). Every function must give
/// the same values and derivatives as with constants that carry zero derivative vectors.
/// Run in a child process (run_isolated), since where it fails in a debug build Eigen asserts.
template <class YA, class YB>
bool same_ad(const std::string& where, const char* what, const YA& a, const YB& b) {
  const auto da = test::ad_derivatives(a).template cast<LD>().eval();
  const auto db = test::ad_derivatives(b).template cast<LD>().eval();
  const bool ok = max_abs(test::ad_values(a) - test::ad_values(b)) == 0 &&
                  max_abs(da - db) <= kEval * kEpsD * (db.norm() + 1);
  if (!ok) {
    std::fprintf(stderr,
                 "%s: %s: derivatives with empty constants %s, with zero-derivative "
                 "constants %s\n",
                 where.c_str(), what, str(da).c_str(), str(db).c_str());
  }
  return ok;
}

TEMPLATE_LIST_TEST_CASE("properties: AD arguments mixing constants (empty derivative vectors) "
                        "and variables",
                        "[orientation][properties]", TUMBLE_TEST_PARAMETERIZATIONS) {
  using P = TestType;
  using CA = Coords<P, AD>;
  INFO(P::name);
  const auto states = random_states<P>(91, 6);
  const std::string result = run_isolated([&] {
    test::Random rng(92);
    bool ok = true;
    for (const auto& s : states) {
      const Coords<P, double> u = random_rate<P>(rng, s.theta);
      const CA x = test::ad_seed(s.theta, u);
      const CA x_zero = test::ad_constant(s.theta);
      const CA x_empty = s.theta.template cast<AD>();
      const CA td = test::ad_seed(s.thetadot, u);
      const CA td_zero = test::ad_constant(s.thetadot);
      const CA td_empty = s.thetadot.template cast<AD>();
      const Vector3<AD> w = test::ad_seed(s.omega, s.alpha);
      const Vector3<AD> w_zero = test::ad_constant(s.omega);
      const Vector3<AD> w_empty = s.omega.template cast<AD>();
      const std::string where = std::string(P::name) + ", theta = " + str(s.theta);
      ok &= same_ad(where, "Gdot_thetadot(variable, constant)", P::Gdot_thetadot(x, td_empty),
                    P::Gdot_thetadot(x, td_zero));
      ok &= same_ad(where, "Gdot_thetadot(constant, variable)", P::Gdot_thetadot(x_empty, td),
                    P::Gdot_thetadot(x_zero, td));
      ok &= same_ad(where, "thetadot(variable, constant)", P::thetadot(x, w_empty),
                    P::thetadot(x, w_zero));
      ok &= same_ad(where, "thetadot(constant, variable)", P::thetadot(x_empty, w),
                    P::thetadot(x_zero, w));
      ok &= same_ad(where, "thetaddot(variable, constant, constant)",
                    P::thetaddot(x, td_empty, w_empty), P::thetaddot(x, td_zero, w_zero));
      ok &= same_ad(where, "thetaddot(constant, variable, constant)",
                    P::thetaddot(x_empty, td, w_empty), P::thetaddot(x_zero, td, w_zero));
      ok &= same_ad(where, "thetaddot(constant, constant, variable)",
                    P::thetaddot(x_empty, td_empty, w), P::thetaddot(x_zero, td_zero, w));
    }
    return ok;
  });
  CHECK(result == "passed");
}

}  // namespace
