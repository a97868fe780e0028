// The joints' rows against the definition of their derivatives, independently of how they were
// derived: along a motion with constant velocities (r(t) = r + v t, R(t) = R exp(t S(omega)),
// omega in body components), dC/dt = J_a nu_a + J_b nu_b and, since nudot = 0,
// d2C/dt2 = -gamma. Both by fourth-order central differences of C(t), at arbitrary (not
// assembled) configurations, where the identities hold as well; each joint type, between two
// bodies and to the ground.

#include <cmath>

#include <Eigen/Geometry>

#include "support/catch.hpp"
#include "support/random.hpp"
#include "tumble/joint/cylindrical.hpp"
#include "tumble/joint/distance.hpp"
#include "tumble/joint/prismatic.hpp"
#include "tumble/joint/revolute.hpp"
#include "tumble/joint/spherical.hpp"
#include "tumble/joint/universal.hpp"
#include "tumble/joint/weld.hpp"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using tumble::ConstraintRows;
using tumble::JointFrame;
using tumble::KinematicsView;

Matrix3d rotation_of(const Vector3d& phi) {
  const double a = phi.norm();
  return a > 0 ? Eigen::AngleAxisd(a, phi / a).toRotationMatrix() : Matrix3d::Identity();
}

/// The kinematics of a body moving with constant velocities, at time t.
KinematicsView<double> at_time(const KinematicsView<double>& k0, double t) {
  KinematicsView<double> k = k0;
  k.position = k0.position + t * k0.velocity;
  k.rotation = k0.rotation * rotation_of(t * k0.omega);
  return k;
}

KinematicsView<double> random_body(tumble::test::Random& rng) {
  KinematicsView<double> k;
  k.position = rng.vector(0.6);
  k.rotation = rotation_of(rng.vector(1.2));
  k.velocity = rng.vector(0.6);
  k.omega = rng.vector(1.2);
  return k;
}

JointFrame random_frame(tumble::test::Random& rng) {
  JointFrame f;
  f.point = rng.vector(0.3);
  f.axes = rotation_of(rng.vector(1.2));
  return f;
}

template <class J>
void check_rows(const J& joint, const KinematicsView<double>& a0,
                const KinematicsView<double>& b0) {
  constexpr int m = J::size;
  const auto c_at = [&](double t) {
    ConstraintRows<double, m> r;
    joint.evaluate(at_time(a0, t), at_time(b0, t), r);
    return Eigen::Matrix<double, m, 1>(r.c);
  };
  ConstraintRows<double, m> r;
  joint.evaluate(a0, b0, r);
  Eigen::Matrix<double, 6, 1> nua, nub;
  nua << a0.velocity, a0.omega;
  nub << b0.velocity, b0.omega;
  const double h = 2e-3;
  const auto c1 = c_at(h), cm1 = c_at(-h), c2 = c_at(2 * h), cm2 = c_at(-2 * h);
  const Eigen::Matrix<double, m, 1> cd = (8.0 * (c1 - cm1) - (c2 - cm2)) / (12.0 * h);
  const Eigen::Matrix<double, m, 1> cdd =
      (-c2 + 16.0 * c1 - 30.0 * r.c + 16.0 * cm1 - cm2) / (12.0 * h * h);
  const Eigen::Matrix<double, m, 1> jnu = r.ja * nua + r.jb * nub;
  INFO(J::name);
  INFO("dC/dt by differences " << cd.transpose() << "\nJ nu " << jnu.transpose());
  CHECK((cd - jnu).cwiseAbs().maxCoeff() <= 1e-8 * (1.0 + jnu.cwiseAbs().maxCoeff()));
  INFO("d2C/dt2 by differences " << cdd.transpose() << "\n-gamma " << (-r.gamma).transpose());
  CHECK((cdd + r.gamma).cwiseAbs().maxCoeff() <= 1e-6 * (1.0 + r.gamma.cwiseAbs().maxCoeff()));
}

template <class Make> void for_pairs(Make&& make) {
  tumble::test::Random rng(20261126);
  for (int trial = 0; trial < 20; ++trial) {
    const KinematicsView<double> a = random_body(rng), b = random_body(rng);
    const auto joint = make(rng);
    check_rows(joint, a, b);
    check_rows(joint, a, tumble::ground_view<double>());
  }
}

}  // namespace

TEST_CASE("joint rows: dC/dt = J nu and d2C/dt2 = -gamma along a motion", "[joint]") {
  for_pairs([](auto& rng) { return tumble::Spherical(rng.vector(0.3), rng.vector(0.3)); });
  for_pairs([](auto& rng) {
    return tumble::Revolute(rng.vector(0.3), Vector3d(rng.vector().normalized()), rng.vector(0.3),
                            Vector3d(rng.vector().normalized()));
  });
  for_pairs([](auto& rng) {
    return tumble::Universal(rng.vector(0.3), Vector3d(rng.vector().normalized()), rng.vector(0.3),
                             Vector3d(rng.vector().normalized()));
  });
  for_pairs([](auto& rng) {
    return tumble::Cylindrical(rng.vector(0.3), Vector3d(rng.vector().normalized()),
                               rng.vector(0.3), Vector3d(rng.vector().normalized()));
  });
  for_pairs([](auto& rng) { return tumble::Prismatic(random_frame(rng), random_frame(rng)); });
  for_pairs([](auto& rng) { return tumble::Weld(random_frame(rng), random_frame(rng)); });
  for_pairs([](auto& rng) { return tumble::Distance(rng.vector(0.3), rng.vector(0.3), 0.7); });
}

TEST_CASE("joint rows: bad input names the joint and the value", "[joint]") {
  const Vector3d p = Vector3d::Zero();
  CHECK_THROWS_WITH(
      tumble::Revolute(p, Vector3d(0, 0, 2), p, Vector3d::UnitZ()),
      TUMBLE_CONTAINS("Revolute") && TUMBLE_CONTAINS("axis on body a must be a unit vector"));
  CHECK_THROWS_WITH(tumble::Revolute(p, Vector3d::UnitZ(), p, Vector3d::Zero()),
                    TUMBLE_CONTAINS("axis on body b"));
  CHECK_THROWS_WITH(
      tumble::Distance(p, p, 0.0),
      TUMBLE_CONTAINS("Distance") && TUMBLE_CONTAINS("length must be finite and > 0"));
  CHECK_THROWS_WITH(tumble::Spherical(Vector3d(NAN, 0, 0), p),
                    TUMBLE_CONTAINS("point on body a is not finite"));
  JointFrame bad;
  bad.axes(0, 0) = -1.0;  // a reflection
  CHECK_THROWS_WITH(tumble::Weld(bad, JointFrame{}), TUMBLE_CONTAINS("proper rotation"));
}
