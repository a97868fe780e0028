// Bad input to the core: every case must throw the documented exception with a message
// that says what is wrong and where (docs/conventions.md, "Errors"), never crash or return NaN.
// Mass properties (include/tumble/body/mass_properties.hpp), bodies (rigid_body.hpp), the
// orientation parameterizations' canonical forms and conversions, and the force elements.

#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>

#include <Eigen/Core>

#include "support/catch.hpp"
#include "tumble/tumble.hpp"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using Eigen::Vector4d;
using tumble::MassProperties;
using tumble::NonFiniteError;
using tumble::ReferencePoint;
using tumble::RigidBody;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

/// The message of the exception of type E that f throws ("" and a failed check otherwise).
template <class E> std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  } catch (const std::exception& e) {
    FAIL_CHECK("threw the wrong exception type: " << e.what());
    return "";
  }
  FAIL_CHECK("did not throw");
  return "";
}

bool has(const std::string& message, const std::string& part) {
  return message.find(part) != std::string::npos;
}

const Matrix3d kInertia = Vector3d(1.0, 2.0, 2.5).asDiagonal();

}  // namespace

// ---- mass -------------------------------------------------------------------------------------

TEST_CASE("bad input: a mass that is not positive and finite", "[body][bad_input]") {
  for (const double m : {0.0, -1.0, -0.0, kNaN, kInf, -kInf}) {
    INFO("mass " << m);
    const std::string msg = message_of<std::invalid_argument>(
        [&] { (void)MassProperties<>::about_centroid(m, kInertia); });
    CHECK(has(msg, "tumble::MassProperties"));
    CHECK(has(msg, "mass must be positive and finite"));
  }
  // The same check guards the inertia given about the reference point.
  const std::string msg = message_of<std::invalid_argument>(
      [&] { (void)MassProperties<>::about_reference(-2.0, kInertia, Vector3d(0.1, 0, 0)); });
  CHECK(has(msg, "mass must be positive and finite, got -2"));
}

// ---- inertia ----------------------------------------------------------------------------------

TEST_CASE("bad input: an inertia tensor that is not symmetric", "[body][bad_input]") {
  Matrix3d i = kInertia;
  i(0, 1) = 0.1;  // I_01 != I_10
  const std::string msg =
      message_of<std::invalid_argument>([&] { (void)MassProperties<>::about_centroid(1.0, i); });
  CHECK(has(msg, "not symmetric"));
  CHECK(has(msg, "0.1"));
}

TEST_CASE("bad input: an inertia tensor that is not positive definite", "[body][bad_input]") {
  for (const Vector3d& d : {Vector3d(0, 1, 1), Vector3d(-1, 2, 2), Vector3d(0, 0, 0)}) {
    INFO("diag " << d.transpose());
    const std::string msg = message_of<std::invalid_argument>(
        [&] { (void)MassProperties<>::about_centroid(1.0, d.asDiagonal()); });
    CHECK(has(msg, "not positive definite"));
    CHECK(has(msg, "principal moments"));
  }
}

TEST_CASE("bad input: principal moments violating the triangle inequality", "[body][bad_input]") {
  const std::string msg = message_of<std::invalid_argument>(
      [&] { (void)MassProperties<>::about_centroid(1.0, Vector3d(1, 1, 3).asDiagonal()); });
  CHECK(has(msg, "triangle inequality"));
  CHECK(has(msg, "1 + 1 < 3"));
}

TEST_CASE("bad input: a non-finite inertia or centroid", "[body][bad_input]") {
  Matrix3d i = kInertia;
  i(2, 2) = kNaN;
  CHECK(has(
      message_of<std::invalid_argument>([&] { (void)MassProperties<>::about_centroid(1.0, i); }),
      "the inertia about the centroid has a non-finite entry"));
  i(2, 2) = kInf;
  CHECK(has(message_of<std::invalid_argument>(
                [&] { (void)MassProperties<>::about_reference(1.0, i, Vector3d::Zero()); }),
            "the inertia about the reference point has a non-finite entry"));
  CHECK(has(message_of<std::invalid_argument>([&] {
              (void)MassProperties<>::about_centroid(1.0, kInertia, Vector3d(0, kNaN, 0));
            }),
            "the centroid has a non-finite entry"));
}

TEST_CASE("bad input: an inertia whose inverse overflows (found by fuzz/body.fuzz.cpp)",
          "[body][bad_input]") {
  // Positive definite and symmetric, but 1 / 1e-310 is not a double: accepting it made the
  // accelerations infinite later.
  const std::string msg = message_of<std::invalid_argument>([&] {
    (void)MassProperties<>::about_centroid(1.0, Vector3d(1e-310, 1e-310, 1e-310).asDiagonal());
  });
  CHECK(has(msg, "its inverse (or the parallel-axis inertia) overflows"));
}

TEST_CASE("bad input: an inertia about the reference point smaller than the parallel-axis term",
          "[body][bad_input]") {
  // I_c = I_g + m (|r|^2 I - r r^T): an I_c below the parallel-axis term of its centroid gives an
  // I_g that is not positive definite.
  const std::string msg = message_of<std::invalid_argument>(
      [&] { (void)MassProperties<>::about_reference(10.0, kInertia, Vector3d(1.0, 0, 0)); });
  CHECK(has(msg, "about the centroid is not positive definite"));
}

TEST_CASE("bad input: a centroidal body whose centroid is off its reference point",
          "[body][bad_input]") {
  const auto mp = MassProperties<>::about_centroid(1.0, kInertia, Vector3d(0.1, 0, 0));
  const std::string msg =
      message_of<std::invalid_argument>([&] { (void)RigidBody<tumble::EulerParameters>(mp); });
  CHECK(has(msg, "ReferencePoint::centroid"));
  CHECK(has(msg, "ReferencePoint::offset"));
  // The offset body accepts it.
  CHECK_NOTHROW(RigidBody<tumble::EulerParameters, ReferencePoint::offset>(mp));
}

// ---- orientation ------------------------------------------------------------------------------

TEST_CASE("bad input: a quaternion of zero or non-finite norm", "[body][bad_input]") {
  using tumble::EulerParameters;
  for (const Vector4d& p :
       {Vector4d(0, 0, 0, 0), Vector4d(kNaN, 0, 0, 0), Vector4d(kInf, 1, 0, 0)}) {
    INFO("p = " << p.transpose());
    const std::string msg =
        message_of<std::domain_error>([&] { (void)EulerParameters::canonical<double>(p); });
    CHECK(has(msg, "EulerParameters"));
    CHECK(has(msg, "zero or non-finite norm"));
  }
  // A non-unit quaternion is normalized, not rejected (documented in docs/conventions.md).
  const Vector4d p = EulerParameters::canonical<double>(Vector4d(2, 0, 0, 0));
  CHECK(p(0) == 1.0);
  // ... also when |p|^2 would underflow or overflow (a fuzz finding): the direction of (1, 2, 2, 4)
  // scaled by 1e-170 or 1e170 is (1, 2, 2, 4) / 5 whatever the scale.
  for (const double scale : {1e-170, 1e170, 1e-300, 1e300}) {
    INFO("scale " << scale);
    const Vector4d u = EulerParameters::canonical<double>(scale * Vector4d(1, 2, 2, 4));
    CHECK((u - Vector4d(0.2, 0.4, 0.4, 0.8)).cwiseAbs().maxCoeff() <= 4e-16);
  }
}

TEST_CASE("bad input: conversions at a set's singular attitude", "[body][bad_input]") {
  // Gibbs vector of a rotation by exactly 180 degrees: infinite, reported.
  const Eigen::Quaterniond half_turn(0.0, 1.0, 0.0, 0.0);
  const std::string msg = message_of<NonFiniteError>(
      [&] { (void)tumble::RodriguesParameters::from_quaternion<double>(half_turn); });
  CHECK(has(msg, "RodriguesParameters"));
  CHECK(has(msg, "180 degrees"));
  // So close to 180 degrees that e / e0 overflows (a fuzz finding): reported, not inf.
  const Eigen::Quaterniond almost_half_turn(1e-320, 1.0, 0.0, 0.0);
  CHECK(has(message_of<NonFiniteError>([&] {
              (void)tumble::RodriguesParameters::from_quaternion<double>(almost_half_turn);
            }),
            "overflows"));
  // The zero quaternion is no attitude for MRP and the rotation vector.
  const Eigen::Quaterniond zero(0.0, 0.0, 0.0, 0.0);
  CHECK(has(message_of<std::domain_error>(
                [&] { (void)tumble::ModifiedRodriguesParameters::from_quaternion<double>(zero); }),
            "zero quaternion"));
  CHECK(has(message_of<std::domain_error>(
                [&] { (void)tumble::RotationVector::from_quaternion<double>(zero); }),
            "zero quaternion"));
  // The MRP shadow of sigma = 0 (the rotation by 360 degrees) is at infinity.
  CHECK(has(message_of<std::domain_error>([&] {
              (void)tumble::ModifiedRodriguesParameters::shadow<double>(Vector3d::Zero());
            }),
            "ModifiedRodriguesParameters"));
}

// ---- accelerations ----------------------------------------------------------------------------

TEST_CASE("bad input: accelerations of a non-finite state or load", "[body][bad_input]") {
  using Body = RigidBody<tumble::EulerZYX>;
  const Body body(MassProperties<>::about_centroid(1.0, kInertia));
  Body::Coords q = Body::Coords::Zero(), qd = Body::Coords::Zero();
  qd(3) = 1.0;
  tumble::Wrench<double> w;
  q(4) = kNaN;
  CHECK(has(message_of<NonFiniteError>([&] { (void)body.accelerations(q, qd, w); }),
            "the state q has a non-finite entry"));
  q(4) = 0.0;
  w.moment(1) = kInf;
  CHECK(has(message_of<NonFiniteError>([&] { (void)body.accelerations(q, qd, w); }),
            "the applied load has a non-finite entry"));
  w.moment(1) = 0.0;
  qd(5) = kNaN;
  CHECK(has(message_of<NonFiniteError>([&] { (void)body.accelerations(q, qd, w); }),
            "the rates qdot have a non-finite entry"));
}

// ---- force elements ---------------------------------------------------------------------------

TEST_CASE("bad input: force elements with non-finite or negative parameters", "[body][bad_input]") {
  CHECK(has(
      message_of<std::invalid_argument>([] { (void)tumble::UniformGravity(Vector3d(0, 0, kNaN)); }),
      "UniformGravity: g has a non-finite entry"));
  CHECK(has(message_of<std::invalid_argument>(
                [] { (void)tumble::PointForce(Vector3d(kInf, 0, 0), Vector3d(0, 0, 1)); }),
            "PointForce: the point or the force is not finite"));
  CHECK(has(message_of<std::invalid_argument>([] {
              (void)tumble::SpringDamper(Vector3d::Zero(), Vector3d::Zero(),
                                         {.stiffness = -1.0, .damping = 0, .rest_length = 0});
            }),
            "tumble::SpringDamper: stiffness, damping and rest length must be finite and >= 0"));
  CHECK(has(message_of<std::invalid_argument>([] {
              (void)tumble::SpringDamperBetween(Vector3d::Zero(), Vector3d::Zero(),
                                                {.stiffness = 1.0, .damping = kNaN});
            }),
            "tumble::SpringDamperBetween"));
  CHECK(has(message_of<std::invalid_argument>([] {
              (void)tumble::SpringDamper(Vector3d(0, kNaN, 0), Vector3d::Zero(),
                                         {.stiffness = 1.0});
            }),
            "the point or the anchor is not finite"));
}

TEST_CASE("bad input: a spring with a rest length whose ends coincide", "[body][bad_input]") {
  using Body = RigidBody<tumble::EulerParameters>;
  const Body body(MassProperties<>::about_centroid(1.0, kInertia));
  Body::Coords q = Body::Coords::Zero(), qd = Body::Coords::Zero();
  q(3) = 1.0;
  // The body point (0.1, 0, 0) sits on the anchor.
  q.head<3>() = Vector3d(-0.1, 0, 0);
  const tumble::SpringDamper spring(Vector3d(0.1, 0, 0), Vector3d::Zero(),
                                    {.stiffness = 10.0, .rest_length = 0.5});
  const std::string msg =
      message_of<NonFiniteError>([&] { (void)tumble::accelerations(body, 0.0, q, qd, spring); });
  CHECK(has(msg, "the two ends coincide"));
  // With L0 = 0 the spring is isotropic and defined there.
  const tumble::SpringDamper iso(Vector3d(0.1, 0, 0), Vector3d::Zero(), {.stiffness = 10.0});
  CHECK(tumble::accelerations(body, 0.0, q, qd, iso).allFinite());
}

TEST_CASE("bad input: a user force that returns NaN", "[body][bad_input]") {
  using Body = RigidBody<tumble::EulerParameters>;
  const Body body(MassProperties<>::about_centroid(1.0, kInertia));
  Body::Coords q = Body::Coords::Zero(), qd = Body::Coords::Zero();
  q(3) = 1.0;
  const auto f = tumble::make_user_force<false>([](double, const auto&) {
    tumble::Wrench<double> w;
    w.force(0) = kNaN;
    return w;
  });
  const std::string msg =
      message_of<NonFiniteError>([&] { (void)tumble::accelerations(body, 0.0, q, qd, f); });
  CHECK(has(msg, "UserForce: the user force returned a non-finite wrench"));
}
