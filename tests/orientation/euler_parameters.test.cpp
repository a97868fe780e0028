// Tests of include/tumble/orientation/euler_parameters.hpp that are specific to Euler parameters
// (the unit quaternion p = (e0, e1, e2, e3), scalar first, Hamilton product). The properties
// every parameterization shares (kinematics against differences and AD, round trips, the
// 50-digit references, ...) are in properties.test.cpp.
//
// Expected values come from independent sources: Eigen's quaternion and AngleAxis conversions,
// the Hamilton product written out below, the quaternion kinematic equation
// pdot = 1/2 p (x) (0, omega) for body rates and its time derivative, and the constraint
// |p| = 1 with its derivatives p.pdot = 0, p.pddot = -|pdot|^2. Reference chapter:
// Chapter 1, "Rigid body", Eqs. (1.1), (1.5), (1.10).
//
// Tolerances are k * eps_S: kEval = 32 for one evaluation of a closed form compared with
// another one (each a few roundings per entry, see properties.test.cpp), kTwo = 64 for two
// chained ones (a product of two matrices, a round trip).

#include "tumble/orientation/euler_parameters.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <unsupported/Eigen/AutoDiff>

#include "support/catch.hpp"
#include "support/finite_difference.hpp"
#include "support/numeric.hpp"
#include "support/random.hpp"
#include "tumble/core/math.hpp"
#include "tumble/orientation/concept.hpp"

// Explicit instantiation of every member template for every scalar type the library supports,
// so that members no test calls still compile.
namespace tumble {
#define TUMBLE_INSTANTIATE_EULER_PARAMETERS(S)                                                 \
  template Matrix<S, 3, 4> EulerParameters::L<S>(const Vector4<S>&);                           \
  template Matrix3<S> EulerParameters::rotation<S>(const Vector4<S>&);                         \
  template Matrix<S, 3, 4> EulerParameters::G<S>(const Vector4<S>&);                           \
  template Vector3<S> EulerParameters::Gdot_thetadot<S>(const Vector4<S>&, const Vector4<S>&); \
  template Vector4<S> EulerParameters::thetadot<S>(const Vector4<S>&, const Vector3<S>&);      \
  template Vector4<S> EulerParameters::thetaddot<S>(const Vector4<S>&, const Vector4<S>&,      \
                                                    const Vector3<S>&);                        \
  template Vector4<S> EulerParameters::from_rotation<S>(const Matrix3<S>&);                    \
  template Eigen::Quaternion<S> EulerParameters::to_quaternion<S>(const Vector4<S>&);          \
  template Vector4<S> EulerParameters::from_quaternion<S>(const Eigen::Quaternion<S>&);        \
  template S EulerParameters::singularity_distance<S>(const Vector4<S>&);                      \
  template Vector4<S> EulerParameters::canonical<S>(const Vector4<S>&);                        \
  template S EulerParameters::constraint<S>(const Vector4<S>&);
TUMBLE_INSTANTIATE_EULER_PARAMETERS(float)
TUMBLE_INSTANTIATE_EULER_PARAMETERS(double)
TUMBLE_INSTANTIATE_EULER_PARAMETERS(long double)
TUMBLE_INSTANTIATE_EULER_PARAMETERS(tumble::test::ADScalar)
#undef TUMBLE_INSTANTIATE_EULER_PARAMETERS
}  // namespace tumble

namespace {

using tumble::EulerParameters;
using tumble::Matrix3;
using tumble::Vector3;
using tumble::Vector4;
using AD = tumble::test::ADScalar;
using LD = long double;
using P = EulerParameters;

constexpr LD kEval = 32;
constexpr LD kTwo = 64;

using tumble::test::eps;
template <class S> LD val(const S& x) { return static_cast<LD>(tumble::detail::value(x)); }
template <class D> auto to_ld(const Eigen::MatrixBase<D>& m) {
  return m.unaryExpr([](const typename D::Scalar& x) { return val(x); }).eval();
}
template <class S, class D> auto to_s(const Eigen::MatrixBase<D>& m) {
  using V = decltype(tumble::detail::value(std::declval<S>()));
  return m.unaryExpr([](const typename D::Scalar& x) { return S(static_cast<V>(x)); }).eval();
}
template <class D> LD max_abs(const Eigen::MatrixBase<D>& m) {
  return to_ld(m).cwiseAbs().maxCoeff();
}

/// The Hamilton product a (x) b of scalar-first quaternions, written out:
/// (a0 b0 - a.b, a0 b + b0 a + a x b).
template <class S> Vector4<S> hamilton(const Vector4<S>& a, const Vector4<S>& b) {
  const Vector3<S> av = a.template tail<3>();
  const Vector3<S> bv = b.template tail<3>();
  Vector4<S> c;
  c(0) = a(0) * b(0) - av.dot(bv);
  c.template tail<3>() = a(0) * bv + b(0) * av + av.cross(bv);
  return c;
}
template <class S> Vector4<S> pure(const Vector3<S>& v) {
  return Vector4<S>(S(0), v(0), v(1), v(2));
}

/// A random unit quaternion (e0, e1, e2, e3), normalized in long double so that it is a unit
/// quaternion to the precision of every scalar type it is rounded to.
Vector4<LD> random_unit(tumble::test::Random& rng) {
  const Eigen::Quaterniond q = rng.quaternion();
  return Vector4<LD>(q.w(), q.x(), q.y(), q.z()).normalized();
}

TEST_CASE("EulerParameters: static interface", "[orientation][euler_parameters]") {
  STATIC_REQUIRE(tumble::Orientation<P>);
  STATIC_REQUIRE(P::size == 4);
  STATIC_REQUIRE(P::has_constraint);
  STATIC_REQUIRE(P::gdot_vanishes);
  STATIC_REQUIRE(P::name == "EulerParameters");
  STATIC_REQUIRE(std::is_same_v<P::Coords<float>, Vector4<float>>);
}

TEMPLATE_TEST_CASE("EulerParameters: scalar first, Hamilton: R matches Eigen and composes",
                   "[orientation][euler_parameters]", float, double, long double, AD) {
  using S = TestType;
  tumble::test::Random rng(101);
  for (int i = 0; i < 50; ++i) {
    const Vector4<LD> pd = random_unit(rng);
    const Vector4<S> p = to_s<S>(pd);
    INFO("p = " << pd.transpose());
    // Eigen's w-first constructor, independent matrix formula.
    const Eigen::Quaternion<LD> q(val(p(0)), val(p(1)), val(p(2)), val(p(3)));
    CHECK(max_abs(to_ld(P::rotation(p)) - q.toRotationMatrix()) <= kEval * eps<S>());
    // q and -q are the same attitude.
    CHECK(max_abs(to_ld(P::rotation(Vector4<S>(-p))) - to_ld(P::rotation(p))) <= kEval * eps<S>());
    // Hamilton: R(a (x) b) = R(a) R(b) (rotate by b in the body, then by a).
    const Vector4<S> b = to_s<S>(random_unit(rng));
    CHECK(max_abs(to_ld(P::rotation(hamilton(p, b))) -
                  to_ld(P::rotation(p)) * to_ld(P::rotation(b))) <= kTwo * eps<S>());
  }
}

TEST_CASE("EulerParameters: axis-angle and the coordinate order",
          "[orientation][euler_parameters]") {
  tumble::test::Random rng(102);
  for (int i = 0; i < 50; ++i) {
    const double phi = rng.uniform(-3.1, 3.1);
    const Eigen::Vector3d n = rng.vector().normalized();
    const Eigen::Vector4d p(std::cos(phi / 2), std::sin(phi / 2) * n(0), std::sin(phi / 2) * n(1),
                            std::sin(phi / 2) * n(2));
    CHECK(max_abs(P::rotation(p) - Eigen::AngleAxisd(phi, n).toRotationMatrix()) <=
          kEval * eps<double>());
  }
  // A rotation by 90 degrees about z maps the body x axis to the inertial y axis (r_F = R r_f).
  const double h = std::sqrt(0.5);
  const Eigen::Vector4d pz(h, 0, 0, h);
  CHECK(max_abs(P::rotation(pz) * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()) <=
        kEval * eps<double>());
  // Scalar first: to_quaternion / from_quaternion map (e0, e1, e2, e3) <-> w, x, y, z.
  const Eigen::Vector4d p(0.1, 0.2, 0.3, 0.4);
  const Eigen::Quaterniond q = P::to_quaternion(p);
  CHECK(q.w() == 0.1);
  CHECK(q.x() == 0.2);
  CHECK(q.y() == 0.3);
  CHECK(q.z() == 0.4);
  CHECK(P::from_quaternion(Eigen::Quaterniond(0.1, 0.2, 0.3, 0.4)) == p);
  CHECK(tumble::convert<P, P>(p) == p);
}

TEMPLATE_TEST_CASE("EulerParameters: G = 2 L(p), pdot = 1/2 p (x) (0, omega)",
                   "[orientation][euler_parameters]", float, double, long double, AD) {
  using S = TestType;
  tumble::test::Random rng(103);
  for (int i = 0; i < 50; ++i) {
    const Vector4<S> p = to_s<S>(random_unit(rng));
    const Vector3<S> w = to_s<S>(rng.vector());
    const Vector4<LD> pl = to_ld(p);
    INFO("p = " << pl.transpose() << ", omega = " << to_ld(w).transpose());
    const auto l = to_ld(P::L(p));
    // L L^T = |p|^2 I and L p = 0: G maps the tangent space onto R^3, p to zero.
    CHECK(max_abs(l * l.transpose() - Eigen::Matrix<LD, 3, 3>::Identity()) <= kEval * eps<S>());
    CHECK(max_abs(l * pl) <= kEval * eps<S>());
    CHECK(max_abs(to_ld(P::G(p)) - 2 * l) == 0);
    // The quaternion kinematic equation for body rates, written with the Hamilton product.
    const Vector4<LD> pdot_ref = LD(0.5) * hamilton<LD>(pl, pure<LD>(to_ld(w)));
    const Vector4<S> pdot = P::thetadot(p, w);
    CHECK(max_abs(to_ld(pdot) - pdot_ref) <= kEval * eps<S>());
    CHECK(std::fabs(pl.dot(to_ld(pdot))) <= kEval * eps<S>());  // tangent: p.pdot = 0
    CHECK(max_abs(to_ld(Vector3<S>(P::G(p) * pdot)) - to_ld(w)) <= kEval * eps<S>());
    // omega = G pdot as the hot path writes it out (P::omega, through angular_velocity), against
    // the Hamilton product: omega = 2 vec(conj(p) (x) pdot) for |p| = 1.
    const Vector4<LD> pc(pl(0), -pl(1), -pl(2), -pl(3));
    const Vector3<LD> w_ref = LD(2) * hamilton<LD>(pc, to_ld(pdot)).template tail<3>();
    CHECK(max_abs(to_ld(P::omega(p, pdot)) - w_ref) <= kEval * eps<S>());
    CHECK(max_abs(to_ld(tumble::angular_velocity<P, S>(p, pdot)) - w_ref) <= kEval * eps<S>());
  }
}

TEMPLATE_TEST_CASE("EulerParameters: Gdot pdot vanishes; pddot from the kinematic equation",
                   "[orientation][euler_parameters]", float, double, long double, AD) {
  using S = TestType;
  tumble::test::Random rng(104);
  for (int i = 0; i < 50; ++i) {
    const Vector4<LD> pd = random_unit(rng);
    const Eigen::Vector3d wd = rng.vector();
    const Eigen::Vector3d ad = rng.vector();
    const Vector4<S> p = to_s<S>(pd);
    const Vector3<S> w = to_s<S>(wd);
    const Vector3<S> a = to_s<S>(ad);
    const Vector4<S> pdot = P::thetadot(p, w);
    INFO("p = " << pd.transpose() << ", omega = " << wd.transpose()
                << ", alpha = " << ad.transpose());
    // Gdot pdot = 2 L(pdot) pdot = 0 exactly (the function returns a literal zero) ...
    CHECK(max_abs(P::Gdot_thetadot(p, pdot)) == 0);
    // ... and AD of G along pdot agrees: d/dt G(p + t pdot) pdot = 2 L(pdot) pdot.
    const auto g_ad = P::G(Vector4<AD>(tumble::test::ad_seed(to_ld(p).template cast<double>(),
                                                             to_ld(pdot).template cast<double>())));
    CHECK(max_abs(tumble::test::ad_derivatives(g_ad) * to_ld(pdot).template cast<double>()) <=
          kEval * eps<double>() * to_ld(pdot).squaredNorm());
    // pddot: differentiating pdot = 1/2 p (x) (0, omega) gives
    // pddot = 1/2 pdot (x) (0, omega) + 1/2 p (x) (0, alpha).
    const Vector4<S> pddot = P::thetaddot(p, pdot, a);
    const Vector4<LD> pl = to_ld(p);
    const Vector4<LD> pdl = to_ld(pdot);
    const Vector4<LD> ref = LD(0.5) * hamilton<LD>(pdl, pure<LD>(to_ld(w))) +
                            LD(0.5) * hamilton<LD>(pl, pure<LD>(to_ld(a)));
    const LD scale = to_ld(a).norm() + to_ld(w).squaredNorm();
    CHECK(max_abs(to_ld(pddot) - ref) <= kTwo * eps<S>() * scale);
    // The constraint's second derivative: p.pddot = -|pdot|^2 ...
    CHECK(std::fabs(pl.dot(to_ld(pddot)) + pdl.squaredNorm()) <= kEval * eps<S>() * scale);
    // ... and Eq. (1.10): G pddot + Gdot pdot = alpha.
    CHECK(max_abs(to_ld(Vector3<S>(P::G(p) * pddot)) - to_ld(a)) <= kEval * eps<S>() * scale);
  }
}

TEMPLATE_TEST_CASE("EulerParameters: Shepperd's method in all four branches",
                   "[orientation][euler_parameters]", float, double, long double, AD) {
  using S = TestType;
  // Each rotation makes a different one of e0^2 .. e3^2 the largest: small angles (e0), and
  // angles near pi about axes near x, y, z (e1, e2, e3); then exactly pi about each axis and about
  // a diagonal, where e0 = 0 and the trace branch cannot be used.
  tumble::test::Random rng(105);
  std::vector<Eigen::Vector4d> ps;
  for (int k = 0; k < 4; ++k) {
    for (int i = 0; i < 10; ++i) {
      const double phi = k == 0 ? rng.uniform(-1.5, 1.5) : rng.uniform(2.8, 3.1415);
      Eigen::Vector3d n = 0.2 * rng.vector();
      if (k > 0) {
        n(k - 1) += 1;
      }
      n.normalize();
      ps.emplace_back(std::cos(phi / 2), std::sin(phi / 2) * n(0), std::sin(phi / 2) * n(1),
                      std::sin(phi / 2) * n(2));
    }
  }
  const double h = std::sqrt(0.5);
  for (const Eigen::Vector4d& p :
       {Eigen::Vector4d(0, 1, 0, 0), Eigen::Vector4d(0, 0, 1, 0), Eigen::Vector4d(0, 0, 0, 1),
        Eigen::Vector4d(0, h, h, 0), Eigen::Vector4d(0, 0, -h, h), Eigen::Vector4d(1, 0, 0, 0)}) {
    ps.push_back(p);
  }
  for (const Eigen::Vector4d& pd : ps) {
    INFO("p = " << pd.transpose());
    // The reference is pd normalized in long double: pd itself is unit only to double rounding,
    // which is coarser than the long double instantiation's tolerance.
    const Vector4<LD> pref = pd.cast<LD>().normalized();
    const Eigen::Quaternion<LD> q(pref(0), pref(1), pref(2), pref(3));
    const Matrix3<S> r = to_s<S>(q.toRotationMatrix());
    const Vector4<S> p = P::from_rotation(r);
    const Vector4<LD> pl = to_ld(p);
    CHECK(pl(0) >= 0);
    CHECK(std::fabs(pl.norm() - 1) <= kEval * eps<S>());
    CHECK(std::min(max_abs(pl - pref), max_abs(pl + pref)) <= kEval * eps<S>());
    // AD through the branch: along p(t) = normalize(p + t v), d/dt from_rotation(R(p(t))) is
    // +-pdot (the sign of the branch's result), with pdot the projection of v.
    if constexpr (std::is_same_v<S, AD>) {
      if (pd(0) > 1e-3) {  // off e0 = 0, where the sign convention e0 >= 0 flips
        const Eigen::Vector4d v(0.3, -0.2, 0.5, 0.1);
        Eigen::Matrix<AD, 4, 1> pa = tumble::test::ad_seed(pd, v);
        pa /= sqrt(pa.squaredNorm());
        const Eigen::Quaternion<AD> qa(pa(0), pa(1), pa(2), pa(3));
        const Vector4<AD> back = P::from_rotation(Matrix3<AD>(qa.toRotationMatrix()));
        const Eigen::Vector4d pdot = v - pd.dot(v) * pd;
        CHECK(max_abs(tumble::test::ad_derivatives(back) - pdot) <= kTwo * eps<double>());
      }
    }
  }
}

TEMPLATE_TEST_CASE("EulerParameters: canonical() normalizes; constraint; no singularity",
                   "[orientation][euler_parameters]", float, double, long double, AD) {
  using S = TestType;
  using V = decltype(tumble::detail::value(std::declval<S>()));
  const Vector4<S> p = to_s<S>(Eigen::Vector4d(1, -2, 2, 4));  // |p| = 5
  const Vector4<S> c = P::canonical(p);
  CHECK(max_abs(to_ld(c) - Vector4<LD>(0.2L, -0.4L, 0.4L, 0.8L)) <= kEval * eps<S>());
  CHECK(std::fabs(val(P::constraint(p)) - 24) <= kEval * eps<S>() * 25);
  CHECK(std::fabs(val(P::constraint(c))) <= kEval * eps<S>());
  // A negative e0 is kept: canonical() normalizes and does not change the sign (q and -q are the
  // same attitude, and a sign flip would make integrated coordinates jump).
  const Vector4<S> m = P::canonical(Vector4<S>(-p));
  CHECK(max_abs(to_ld(m) + to_ld(c)) <= kEval * eps<S>());
  // No attitude to recover from zero or non-finite coordinates.
  CHECK_THROWS_AS(P::canonical(Vector4<S>(Vector4<S>::Zero())), std::domain_error);
  CHECK_THROWS_AS(
      P::canonical(Vector4<S>(S(std::numeric_limits<V>::quiet_NaN()), S(0), S(0), S(0))),
      std::domain_error);
  CHECK_THROWS_AS(P::canonical(Vector4<S>(S(std::numeric_limits<V>::infinity()), S(0), S(0), S(0))),
                  std::domain_error);
  // Euler parameters have no singular attitude.
  tumble::test::Random rng(106);
  for (int i = 0; i < 20; ++i) {
    CHECK(std::isinf(static_cast<double>(val(P::singularity_distance(to_s<S>(random_unit(rng)))))));
  }
}

}  // namespace
