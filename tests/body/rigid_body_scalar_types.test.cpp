// Tests of tumble::RigidBody (include/tumble/body/rigid_body.hpp) in other scalar types than
// double: explicit instantiations of float, long double and AD bodies (every member must compile),
// and float and AD against double for one parameterization of each kind. Split from
// rigid_body.test.cpp, which the build compiles in slices of the parameterizations: the AD
// instantiations here are as heavy as half of that file, so they get a translation unit of their
// own instead of weighing down one slice.

#include <algorithm>
#include <limits>
#include <tuple>

#include <Eigen/Dense>

#include "support/body_fixtures.hpp"
#include "support/catch.hpp"
#include "support/parameterizations.hpp"
#include "tumble/body/rigid_body.hpp"
#include "tumble/force/loads.hpp"

using tumble::ReferencePoint;
using tumble::test::AD;

// Every member of these instantiations must compile, with every compiler users have: Clang 14
// instantiates here even the members whose `requires` does not hold for the Ref at hand (CI
// compiles this file with it). The fixed_point bodies are instantiated in fixed_point.test.cpp.
template class tumble::RigidBody<tumble::EulerParameters, ReferencePoint::centroid, float>;
template class tumble::RigidBody<tumble::EulerParameters, ReferencePoint::offset, float>;
template class tumble::RigidBody<tumble::EulerParameters, ReferencePoint::offset, long double>;
template class tumble::RigidBody<tumble::EulerParameters, ReferencePoint::centroid, AD>;
template class tumble::RigidBody<tumble::EulerParameters, ReferencePoint::offset, AD>;
#ifdef TUMBLE_TEST_HAVE_EULER_ANGLES
template class tumble::RigidBody<tumble::EulerZYX, ReferencePoint::offset, float>;
template class tumble::RigidBody<tumble::EulerZXZ, ReferencePoint::offset, AD>;
#endif
#ifdef TUMBLE_TEST_HAVE_RODRIGUES
template class tumble::RigidBody<tumble::RodriguesParameters, ReferencePoint::offset, AD>;
#endif
#ifdef TUMBLE_TEST_HAVE_MRP
template class tumble::RigidBody<tumble::ModifiedRodriguesParameters, ReferencePoint::offset,
                                 float>;
#endif
#ifdef TUMBLE_TEST_HAVE_ROTATION_VECTOR
template class tumble::RigidBody<tumble::RotationVector, ReferencePoint::offset, AD>;
#endif

namespace {

using tumble::test::record_error;
using tumble::test::rel_error;

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr bool offset(ReferencePoint r) { return r == ReferencePoint::offset; }

template <class P, ReferencePoint Ref> using Body = tumble::RigidBody<P, Ref, double>;
template <class P> using Coords = typename tumble::test::State<P>::Coords;

template <class S, class Derived> auto to(const Eigen::MatrixBase<Derived>& x) {
  return x.template cast<S>().eval();
}
template <class Derived> Eigen::MatrixXd values(const Eigen::MatrixBase<Derived>& x) {
  Eigen::MatrixXd v(x.rows(), x.cols());
  for (Eigen::Index j = 0; j < x.cols(); ++j) {
    for (Eigen::Index i = 0; i < x.rows(); ++i) {
      v(i, j) = static_cast<double>(tumble::detail::value(x(i, j)));
    }
  }
  return v;
}

/// The float and AD instantiations of the body: one parameterization of each kind (Euler
/// parameters, a Tait-Bryan and a proper Euler sequence, Gibbs, MRP, rotation vector), not all 16.
/// What this checks is the body's own arithmetic (M, f_v, the accelerations with every load) in
/// another scalar type; that code is one template over P, and the charts' functions themselves
/// run in float and AD for all 16 parameterizations in orientation/properties.test.cpp. The six
/// cover every formula family of the charts (the 12 Euler sequences are one template, EulerAngles
/// <i, j, k>, whose only branch is Tait-Bryan versus proper), at 6/16 of the compile time.
using ScalarTypeRepresentatives = std::tuple<tumble::EulerParameters
#ifdef TUMBLE_TEST_HAVE_EULER_ANGLES
                                             ,
                                             tumble::EulerZYX, tumble::EulerZXZ
#endif
#ifdef TUMBLE_TEST_HAVE_RODRIGUES
                                             ,
                                             tumble::RodriguesParameters
#endif
#ifdef TUMBLE_TEST_HAVE_MRP
                                             ,
                                             tumble::ModifiedRodriguesParameters
#endif
#ifdef TUMBLE_TEST_HAVE_ROTATION_VECTOR
                                             ,
                                             tumble::RotationVector
#endif
                                             >;

template <class P, ReferencePoint Ref> void check_scalar_types() {
  // A well-conditioned body (sides in [0.8, 1.2]), so that float's error is not dominated by
  // the conditioning of I_g.
  tumble::test::Random rng(108);
  const auto model = tumble::test::random_body(rng, offset(Ref), 0.8, 1.2);
  const Body<P, Ref> body_d(tumble::test::mass_properties(model));
  const tumble::RigidBody<P, Ref, float> body_f(tumble::test::mass_properties<float>(model));
  const tumble::RigidBody<P, Ref, AD> body_ad(tumble::test::mass_properties<AD>(model));
  const double feps = std::numeric_limits<float>::epsilon();
  double worst_f = 0, worst_ad = 0;
  for (int i = 0; i < 10; ++i) {
    const auto s = tumble::test::random_state<P>(rng);
    const auto loads = tumble::test::random_loads(rng);
    INFO(P::name << " " << tumble::test::ref_name(Ref) << " state " << i);
    // Round the inputs to float first, so that both compute from the same numbers.
    const Coords<P> q = to<double>(to<float>(s.q));
    const Coords<P> qdot = to<double>(to<float>(s.qdot));
    const auto run = [&](const auto& body, const auto& qs, const auto& qds, const auto& t) {
      return tumble::test::with_elements(
          loads, [&](const auto&... e) { return tumble::accelerations(body, t, qs, qds, e...); });
    };
    const Coords<P> qdd_d = run(body_d, q, qdot, 0.0);

    const double ef =
        std::max({rel_error(values(body_f.mass_matrix(to<float>(q))),
                            Eigen::MatrixXd(body_d.mass_matrix(q))),
                  rel_error(values(body_f.centrifugal_coriolis(to<float>(q), to<float>(qdot))),
                            Eigen::MatrixXd(body_d.centrifugal_coriolis(q, qdot))),
                  rel_error(values(run(body_f, to<float>(q), to<float>(qdot), 0.0f)),
                            Eigen::MatrixXd(qdd_d))});
    // float: the same few hundred roundings as kTol, at float's epsilon.
    CHECK(ef < 256 * feps);
    worst_f = std::max(worst_f, ef);

    const double ead = std::max(
        {rel_error(values(body_ad.mass_matrix(to<AD>(q))), Eigen::MatrixXd(body_d.mass_matrix(q))),
         rel_error(values(body_ad.centrifugal_coriolis(to<AD>(q), to<AD>(qdot))),
                   Eigen::MatrixXd(body_d.centrifugal_coriolis(q, qdot))),
         rel_error(values(run(body_ad, to<AD>(q), to<AD>(qdot), AD(0.0))),
                   Eigen::MatrixXd(qdd_d))});
    // AD values are computed by the same operations as double (up to Eigen's vectorized
    // summation order).
    CHECK(ead < 16 * kEps);
    worst_ad = std::max(worst_ad, ead);
  }
  record_error("float vs double (M, f_v, qddot)", P::name, Ref, worst_f);
  record_error("AD values vs double (M, f_v, qddot)", P::name, Ref, worst_ad);
}

}  // namespace

TEMPLATE_LIST_TEST_CASE("float and AD bodies agree with double to the type's precision",
                        "[body][rigid_body]", ScalarTypeRepresentatives) {
  check_scalar_types<TestType, ReferencePoint::centroid>();
  check_scalar_types<TestType, ReferencePoint::offset>();
}
