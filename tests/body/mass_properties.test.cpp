// Tests of tumble::MassProperties (include/tumble/body/mass_properties.hpp): the parallel axis
// theorem both ways (reference chapter Eq. 1.22 with I_c = I_g + m S(r_g)^T S(r_g)), against a
// solid box in closed form and against point-mass sums; the validation of every input, with the
// message of each rejection.

#include "tumble/body/mass_properties.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "support/body_fixtures.hpp"
#include "support/catch.hpp"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using tumble::MassProperties;
using tumble::test::rel_error;
using MP = MassProperties<double>;

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

/// A solid box with sides a, b, c: I_g = m/12 diag(b^2 + c^2, a^2 + c^2, a^2 + b^2).
Matrix3d box_inertia(double m, double a, double b, double c) {
  return Vector3d(m / 12 * (b * b + c * c), m / 12 * (a * a + c * c), m / 12 * (a * a + b * b))
      .asDiagonal();
}

}  // namespace

TEST_CASE("solid box about a corner and a face centre: parallel axis theorem in closed form",
          "[body][mass_properties]") {
  const double m = 3.0, a = 0.4, b = 1.2, c = 2.0;
  const Matrix3d ig = box_inertia(m, a, b, c);

  // Reference point at the corner (0, 0, 0) of the box [0, a] x [0, b] x [0, c]: the integrals
  // int (y^2 + z^2) dm = m (b^2 + c^2) / 3 and int x y dm = m a b / 4 give
  const Vector3d corner_rg(a / 2, b / 2, c / 2);
  Matrix3d corner;
  corner << m * (b * b + c * c) / 3, -m * a * b / 4, -m * a * c / 4,  //
      -m * a * b / 4, m * (a * a + c * c) / 3, -m * b * c / 4,        //
      -m * a * c / 4, -m * b * c / 4, m * (a * a + b * b) / 3;

  // Reference point at the centre of the face x = 0: only x is shifted, by a/2.
  const Vector3d face_rg(a / 2, 0, 0);
  const Matrix3d face =
      Vector3d(m * (b * b + c * c) / 12, m * (a * a / 3 + c * c / 12), m * (a * a / 3 + b * b / 12))
          .asDiagonal();

  for (const auto& [rg, ic] : {std::pair{corner_rg, corner}, std::pair{face_rg, face}}) {
    const MP from_g = MP::about_centroid(m, ig, rg);
    const MP from_c = MP::about_reference(m, ic, rg);
    CHECK(rel_error(from_g.inertia_reference(), ic) < 8 * kEps);
    CHECK(rel_error(from_c.inertia_centroid(), ig) < 8 * kEps);
    CHECK(rel_error(from_c.inertia_reference(), ic) < 8 * kEps);
    CHECK(from_g.mass() == m);
    CHECK(rel_error(from_g.first_moment(), Vector3d(m * rg)) < kEps);
    CHECK(from_g.centroid() == rg);
    CHECK(from_c.centroid() == rg);
  }
}

TEST_CASE("about_reference takes the centroid's position, not the first moment",
          "[body][mass_properties]") {
  // A thin uniform rod of mass m and length L along the body z axis, framed at its end c: about
  // c the transverse moment is m L^2 / 3, about its centroid (at L/2 from c) m L^2 / 12.
  const double m = 2.5, len = 0.8, thin = 1e-3;  // thin: the axial moment, small but positive
  const Matrix3d ic = Vector3d(m * len * len / 3, m * len * len / 3, thin).asDiagonal();
  const Matrix3d ig = Vector3d(m * len * len / 12, m * len * len / 12, thin).asDiagonal();
  const Vector3d rg(0, 0, len / 2);  // the centroid's position (m), body components
  const MP rod = MP::about_reference(m, ic, rg);
  CHECK(rel_error(rod.inertia_centroid(), ig) < 8 * kEps);
  CHECK(rel_error(rod.inertia_reference(), ic) < 8 * kEps);
  CHECK(rel_error(rod.first_moment(), Vector3d(0, 0, m * len / 2)) < kEps);
  CHECK(rel_error(Matrix3d(rod.inertia_reference_inverse() * ic), Matrix3d::Identity()) < 8 * kEps);
  // The first moment m r_g passed where r_g is meant is another body: here its inertia about
  // the centroid would be m L^2/3 - m (m L/2)^2 < 0, which is rejected.
  REQUIRE_THROWS_AS(MP::about_reference(m, ic, Vector3d(m * rg)), std::invalid_argument);
}

TEST_CASE("the point-mass model has the body's mass, first moment and inertia",
          "[body][mass_properties]") {
  // The fixture that the mass-matrix and momentum suites rely on (Eqs. 1.18, 1.19 as sums).
  tumble::test::Random rng(11);
  for (int i = 0; i < 50; ++i) {
    const auto body = tumble::test::random_body(rng, i % 2 == 1);
    REQUIRE(body.cloud.size() == 6);
    CHECK(std::abs(tumble::test::cloud_mass(body.cloud) - body.mass) < 4 * kEps * body.mass);
    CHECK((tumble::test::cloud_first_moment(body.cloud) - body.mass * body.centroid)
              .cwiseAbs()
              .maxCoeff() < 16 * kEps * body.mass);
    CHECK(rel_error(tumble::test::cloud_inertia(body.cloud, body.centroid), body.inertia_centroid) <
          64 * kEps);
  }
}

TEST_CASE("about_centroid and about_reference agree on random bodies (parallel axis both ways)",
          "[body][mass_properties]") {
  tumble::test::Random rng(12);
  double worst = 0;
  for (int i = 0; i < 100; ++i) {
    const auto body = tumble::test::random_body(rng, true);
    // Independent expectations: the inertia of the six point masses about c and about g.
    const Matrix3d ic = tumble::test::cloud_inertia(body.cloud, Vector3d::Zero());
    const Matrix3d ig = tumble::test::cloud_inertia(body.cloud, body.centroid);
    const MP from_g = MP::about_centroid(body.mass, body.inertia_centroid, body.centroid);
    const MP from_c = MP::about_reference(body.mass, ic, body.centroid);
    const double e = std::max(
        {rel_error(from_g.inertia_reference(), ic), rel_error(from_c.inertia_centroid(), ig),
         rel_error(from_c.inertia_reference(), ic), rel_error(from_g.inertia_centroid(), ig)});
    worst = std::max(worst, e);
    // The parallel-axis subtraction I_c - m S(r_g)^T S(r_g) cancels when |m r_g^2| >> |I_g|:
    // the bound scales with |I_c| / |I_g|.
    const double amplification = ic.cwiseAbs().maxCoeff() / ig.cwiseAbs().maxCoeff();
    CHECK(e < 64 * kEps * amplification);
    CHECK(from_c.inertia_centroid() == from_c.inertia_centroid().transpose());
    CHECK(rel_error(Matrix3d(from_g.inertia_centroid_inverse() * from_g.inertia_centroid()),
                    Matrix3d::Identity()) < 64 * kEps * amplification);
  }
  tumble::test::ErrorReport::instance().record("MassProperties parallel axis", worst);
}

TEST_CASE("principal moments are the eigenvalues of I_g in ascending order",
          "[body][mass_properties]") {
  tumble::test::Random rng(13);
  const Matrix3d axes = rng.rotation();
  const Vector3d moments(2.0, 0.5, 1.75);  // 0.5 + 1.75 >= 2: a valid body
  const MP mp = MP::about_centroid(1.5, axes * moments.asDiagonal() * axes.transpose());
  const Vector3d expected(0.5, 1.75, 2.0);
  CHECK(rel_error(mp.principal_moments(), expected) < 16 * kEps);
}

TEST_CASE("limiting bodies are accepted: plane lamina, symmetric to rounding",
          "[body][mass_properties]") {
  // A plane lamina has I3 = I1 + I2 exactly (the equality case of the triangle inequality).
  const Matrix3d lamina = Vector3d(1.0, 2.0, 3.0).asDiagonal();
  REQUIRE_NOTHROW(MP::about_centroid(1.0, lamina));

  // An inertia that is symmetric only to rounding is accepted and symmetrized.
  Matrix3d near;
  near << 2.0, 0.1, 0.0,  //
      0.1 * (1 + kEps), 2.5, 0.2, 0.0, 0.2, 3.0;
  const MP mp = MP::about_centroid(1.0, near);
  CHECK(mp.inertia_centroid() == mp.inertia_centroid().transpose());
  CHECK(rel_error(mp.inertia_centroid(), near) < 2 * kEps);
}

TEST_CASE("invalid masses are rejected with a message", "[body][mass_properties]") {
  const Matrix3d i = Matrix3d::Identity();
  const Vector3d r(0.1, 0.2, 0.3);
  for (const double m : {0.0, -0.0, -1.0, kNaN, kInf, -kInf}) {
    INFO("mass " << m);
    REQUIRE_THROWS_AS(MP::about_centroid(m, i), std::invalid_argument);
    REQUIRE_THROWS_WITH(MP::about_centroid(m, i), TUMBLE_CONTAINS("mass must be positive"));
    REQUIRE_THROWS_WITH(MP::about_reference(m, i, r), TUMBLE_CONTAINS("mass must be positive"));
  }
  REQUIRE_THROWS_WITH(MP::about_centroid(-1.0, i), TUMBLE_CONTAINS("got -1"));
}

TEST_CASE("invalid inertia tensors are rejected with a message", "[body][mass_properties]") {
  Matrix3d asym = Vector3d(2.0, 2.5, 3.0).asDiagonal();
  asym(0, 1) = 0.1;  // I_01 = 0.1 but I_10 = 0
  REQUIRE_THROWS_AS(MP::about_centroid(1.0, asym), std::invalid_argument);
  REQUIRE_THROWS_WITH(MP::about_centroid(1.0, asym), TUMBLE_CONTAINS("not symmetric"));

  const Matrix3d indefinite = Vector3d(1.0, 1.0, -0.5).asDiagonal();
  REQUIRE_THROWS_WITH(MP::about_centroid(1.0, indefinite),
                      TUMBLE_CONTAINS("not positive definite"));
  REQUIRE_THROWS_WITH(MP::about_centroid(1.0, Matrix3d::Zero()),
                      TUMBLE_CONTAINS("not positive definite"));
  // Positive definite in the eigenvalues but not as an inertia: 1 + 1 < 3.
  const Matrix3d triangle = Vector3d(1.0, 1.0, 3.0).asDiagonal();
  REQUIRE_THROWS_WITH(MP::about_centroid(1.0, triangle), TUMBLE_CONTAINS("triangle inequality"));
  // The same violation hidden by a rotation of the axes.
  tumble::test::Random rng(14);
  const Matrix3d q = rng.rotation();
  const Matrix3d rotated = q * triangle * q.transpose();
  REQUIRE_THROWS_WITH(MP::about_centroid(1.0, Matrix3d(0.5 * (rotated + rotated.transpose()))),
                      TUMBLE_CONTAINS("triangle inequality"));

  for (const double bad : {kNaN, kInf, -kInf}) {
    INFO("entry " << bad);
    Matrix3d i = Matrix3d::Identity();
    i(1, 1) = bad;
    REQUIRE_THROWS_AS(MP::about_centroid(1.0, i), std::invalid_argument);
    REQUIRE_THROWS_WITH(MP::about_centroid(1.0, i),
                        TUMBLE_CONTAINS("inertia about the centroid has a non-finite entry"));
    REQUIRE_THROWS_WITH(
        MP::about_reference(1.0, i, Vector3d::Zero()),
        TUMBLE_CONTAINS("inertia about the reference point has a non-finite entry"));
  }

  // About the reference point, the inertia must exceed the parallel-axis term: here I_c = I
  // with m |r_g|^2 = 4 leaves an I_g with negative moments.
  REQUIRE_THROWS_WITH(MP::about_reference(1.0, Matrix3d::Identity(), Vector3d(2.0, 0.0, 0.0)),
                      TUMBLE_CONTAINS("not positive definite"));
}

TEST_CASE("a non-finite centroid is rejected with a message", "[body][mass_properties]") {
  for (const double bad : {kNaN, kInf}) {
    const Vector3d r(0.0, bad, 0.0);
    REQUIRE_THROWS_AS(MP::about_centroid(1.0, Matrix3d::Identity(), r), std::invalid_argument);
    REQUIRE_THROWS_WITH(MP::about_centroid(1.0, Matrix3d::Identity(), r),
                        TUMBLE_CONTAINS("centroid has a non-finite entry"));
    REQUIRE_THROWS_WITH(MP::about_reference(1.0, Matrix3d::Identity(), r),
                        TUMBLE_CONTAINS("centroid has a non-finite entry"));
  }
}

TEST_CASE("MassProperties in float and AD agree with double", "[body][mass_properties]") {
  tumble::test::Random rng(15);
  const auto body = tumble::test::random_body(rng, true);
  const MP d = tumble::test::mass_properties(body, true);
  const auto f = tumble::test::mass_properties<float>(body, true);
  const auto ad = tumble::test::mass_properties<tumble::test::AD>(body, true);
  const double feps = std::numeric_limits<float>::epsilon();
  const double amplification =
      d.inertia_reference().cwiseAbs().maxCoeff() / d.inertia_centroid().cwiseAbs().maxCoeff();
  CHECK(rel_error(f.inertia_centroid().cast<double>(), d.inertia_centroid()) <
        64 * feps * amplification);
  CHECK(rel_error(f.inertia_reference().cast<double>(), d.inertia_reference()) < 64 * feps);
  Matrix3d ad_ig;
  for (int i = 0; i < 9; ++i) {
    ad_ig(i) = ad.inertia_centroid()(i).value();
  }
  CHECK(rel_error(ad_ig, d.inertia_centroid()) < 4 * kEps);
  REQUIRE_THROWS_WITH(MassProperties<float>::about_centroid(0.0f, Eigen::Matrix3f::Identity()),
                      TUMBLE_CONTAINS("mass must be positive"));
}

template class tumble::MassProperties<float>;
template class tumble::MassProperties<long double>;
template class tumble::MassProperties<tumble::test::AD>;
