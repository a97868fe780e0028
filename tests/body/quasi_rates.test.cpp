// Tests of RigidBody::velocity_rates and RigidBody::quasi_rates (include/tumble/body/
// rigid_body.hpp): the rate of the quasi-velocity state x = [r_oc; theta; v; omega],
// xdot = [v; thetadot(theta, omega); a_c; alpha], checked against the Newton-Euler equations
// written in the test from the physical state and the forces themselves (m a_g = sum F,
// I_g alpha + omega x I_g omega = M_g; a_g = a_c + R (alpha x r_g + omega x (omega x r_g))),
// against omega = G thetadot (Eq. 1.5), against accelerations() (the same (a_c, alpha) through
// Eq. 1.10, bit for bit), velocity_rates_into (the same pair written into given vectors; a
// body held at a fixed point leaves the acceleration alone; with NoWrench, the torque-free
// motion), and for the error a non-finite
// omega raises. For Euler parameters, an Euler-angle sequence, MRP and the rotation vector, at
// and off the centroid.

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <tuple>

#include <Eigen/Dense>

#include "support/body_fixtures.hpp"
#include "support/catch.hpp"
#include "tumble/body/rigid_body.hpp"
#include "tumble/core/errors.hpp"
#include "tumble/force/loads.hpp"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using tumble::ReferencePoint;

constexpr double kTol = 256 * std::numeric_limits<double>::epsilon();

using QuasiParameterizations =
    std::tuple<tumble::EulerParameters, tumble::EulerZXZ, tumble::ModifiedRodriguesParameters,
               tumble::RotationVector>;

template <class P, ReferencePoint Ref> void check_quasi_rates() {
  using Body = tumble::RigidBody<P, Ref>;
  constexpr int n = P::size, nq = Body::nq;
  tumble::test::Random rng(301);
  int used = 0;
  for (int b = 0; b < 3; ++b) {
    const auto model = tumble::test::random_body(rng, Ref == ReferencePoint::offset);
    const Body body(tumble::test::mass_properties(model));
    const Matrix3d& ig = model.inertia_centroid;
    const Vector3d& rg = model.centroid;
    const double lambda_min = Eigen::SelfAdjointEigenSolver<Matrix3d>(ig).eigenvalues()(0);
    for (int i = 0; i < 10; ++i) {
      const auto ps = tumble::test::random_physical_state(rng);
      const auto loads = tumble::test::random_loads(rng);
      if (!tumble::test::usable<P>(ps)) {
        continue;
      }
      ++used;
      INFO(P::name << " " << tumble::test::ref_name(Ref) << " body " << b << " state " << i);
      const auto s = tumble::test::make_state<P>(ps);
      const tumble::Wrench<double> w = tumble::test::with_elements(loads, [&](const auto&... e) {
        return tumble::total_wrench(body, 0.0, s.q, s.qdot, e...);
      });
      typename Body::QuasiCoords x;
      x << s.q, ps.velocity, ps.omega;
      const typename Body::QuasiCoords xd = body.quasi_rates(x, w);

      // rdot = v; thetadot is the inverse of omega = G thetadot (Eq. 1.5).
      CHECK(xd.template head<3>() == ps.velocity);
      const typename Body::Theta thd = xd.template segment<n>(3);
      CHECK((P::G(s.theta()) * thd - ps.omega).norm() < kTol * (1.0 + ps.omega.norm()));

      // Newton-Euler in the test.
      const Vector3d alpha = xd.template tail<3>();
      const Vector3d a_c = xd.template segment<3>(nq);
      const auto applied = tumble::test::applied_forces(model, ps, loads);
      Vector3d force = Vector3d::Zero(), moment_g = applied.moment;
      double f_scale = 0, m_scale = applied.moment.norm();
      for (const auto& [rho, f] : applied.forces) {
        force += f;
        moment_g += (rho - rg).cross(ps.rotation.transpose() * f);
        f_scale += f.norm();
        m_scale += (rho - rg).norm() * f.norm();
      }
      const Vector3d gyro = ps.omega.cross(ig * ps.omega);
      m_scale += gyro.norm();
      const double alpha_scale = m_scale / lambda_min;
      CHECK((ig * alpha + gyro - moment_g).norm() / (lambda_min * alpha_scale) < kTol);
      const Vector3d a_g =
          a_c + ps.rotation * (alpha.cross(rg) + ps.omega.cross(ps.omega.cross(rg)));
      const double ag_scale =
          f_scale / model.mass + alpha_scale * rg.norm() + ps.omega.squaredNorm() * rg.norm();
      CHECK((a_g - force / model.mass).norm() / ag_scale < kTol);

      // velocity_rates is the same pair; accelerations() maps it through Eq. (1.10).
      const tumble::VelocityRates<double> vr = body.velocity_rates(s.theta(), ps.omega, w);
      CHECK((vr.acceleration - a_c).norm() <= kTol * ag_scale);
      CHECK((vr.alpha - alpha).norm() <= kTol * alpha_scale);
      // velocity_rates_into writes the same pair into any writable 3-vectors (here the two halves
      // of one vector, as the scene writes them into y'), from the body's kinematics.
      typename Body::Kinematics k;
      k.mass_properties = &body.mass_properties();
      k.omega = ps.omega;
      k.rotation = ps.rotation;
      Eigen::Matrix<double, 6, 1> into;
      into.fill(std::numeric_limits<double>::quiet_NaN());
      body.velocity_rates_into(k, w, into.head<3>(), into.tail<3>());
      CHECK((into.head<3>() - a_c).norm() <= kTol * ag_scale);
      CHECK((into.tail<3>() - alpha).norm() <= kTol * alpha_scale);
      const typename Body::Coords qdd = body.accelerations(s.q, s.qdot, w);
      // The same computation with the same omega: the body's own omega = G thetadot (written out
      // by P::omega; s.omega is the product with the matrix G, equal to it up to rounding).
      const tumble::VelocityRates<double> vg =
          body.velocity_rates(s.theta(), Body::omega(s.q, s.qdot), w);
      CHECK(qdd.template head<3>() == vg.acceleration);
      const Vector3d alpha_g =
          P::G(s.theta()) * qdd.template tail<n>() + P::Gdot_thetadot(s.theta(), s.thetadot());
      CHECK((alpha_g - vg.alpha).norm() < kTol * alpha_scale);
    }
  }
  CHECK(used >= 20);
}

}  // namespace

TEMPLATE_LIST_TEST_CASE("quasi_rates: the Newton-Euler rates of [r; theta; v; omega]",
                        "[body][quasi]", QuasiParameterizations) {
  check_quasi_rates<TestType, ReferencePoint::centroid>();
  check_quasi_rates<TestType, ReferencePoint::offset>();
}

TEST_CASE("velocity_rates_into: a body held at a fixed point writes alpha only", "[body][quasi]") {
  using Body = tumble::RigidBody<tumble::EulerParameters, ReferencePoint::fixed_point>;
  const Vector3d ig(1.0, 2.0, 3.0);
  const Vector3d r(0.1, -0.2, 0.3);  // the centroid from the fixed point c, body frame
  const Body body(tumble::MassProperties<double>::about_centroid(1.0, ig.asDiagonal(), r),
                  Vector3d(0.5, 0.5, 1.0));
  Body::Kinematics k;
  k.mass_properties = &body.mass_properties();
  k.omega = Vector3d(0.3, 2.0, -0.5);
  tumble::Wrench<double> w;
  w.moment = Vector3d(0.7, -0.1, 0.2);
  Vector3d acceleration = Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  Vector3d alpha = Vector3d::Zero();
  body.velocity_rates_into(k, w, acceleration, alpha);
  CHECK(acceleration.array().isNaN().all());  // a fixed body has no a_c: left as it was
  // Euler's equations about the fixed point c, I_c alpha + omega x I_c omega = M_c, with I_c by
  // the parallel-axis theorem (mass 1) from the centroid's principal inertia.
  const Matrix3d ic =
      Matrix3d(ig.asDiagonal()) + (r.squaredNorm() * Matrix3d::Identity() - r * r.transpose());
  const Vector3d residual = ic * alpha + k.omega.cross(ic * k.omega) - w.moment;
  CHECK(residual.norm() < kTol * (w.moment.norm() + k.omega.squaredNorm() * ic.norm()));
  const tumble::VelocityRates<double> vr = body.velocity_rates(Body::Theta::Zero(), k, w);
  CHECK(vr.alpha == alpha);  // the same computation
  CHECK(vr.acceleration == Vector3d::Zero());
}

namespace {

/// velocity_rates_into with NoWrench (a body nothing loads: the wrench's terms left out) against
/// the same call with a zero Wrench (equal values: a zero's sign aside, which == ignores) and
/// against torque-free Newton-Euler written here: I_g alpha + omega x I_g omega = 0 and a_g = 0,
/// a_g = a_c + R (alpha x r_g + omega x (omega x r_g)); held at c, I_c alpha + omega x I_c omega =
/// 0.
template <ReferencePoint Ref> void check_no_wrench(const Matrix3d& ig, const Vector3d& rg) {
  using Body = tumble::RigidBody<tumble::EulerParameters, Ref>;
  const auto mp = tumble::MassProperties<double>::about_centroid(2.0, ig, rg);
  const Body body = [&] {
    if constexpr (Ref == ReferencePoint::fixed_point) {
      return Body(mp, Vector3d(0.5, 0.5, 1.0));
    } else {
      return Body(mp);
    }
  }();
  typename Body::Kinematics k;
  k.mass_properties = &body.mass_properties();
  k.omega = Vector3d(0.3, 2.0, -0.5);
  k.rotation = Eigen::AngleAxisd(0.7, Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  Vector3d a_free = Vector3d::Zero(), alpha_free, a_zero = Vector3d::Zero(), alpha_zero;
  body.velocity_rates_into(k, tumble::NoWrench{}, a_free, alpha_free);
  body.velocity_rates_into(k, tumble::Wrench<double>{}, a_zero, alpha_zero);
  CHECK(alpha_free == alpha_zero);
  CHECK(a_free == a_zero);
  const Matrix3d i =
      Ref == ReferencePoint::fixed_point ? body.mass_properties().inertia_reference() : ig;
  const double scale = k.omega.squaredNorm() * i.norm();
  CHECK((i * alpha_free + k.omega.cross(i * k.omega)).norm() < kTol * scale);
  if constexpr (Ref != ReferencePoint::fixed_point) {
    const Vector3d a_g =
        a_free + k.rotation * (alpha_free.cross(rg) + k.omega.cross(k.omega.cross(rg)));
    CHECK(a_g.norm() < kTol * (1 + scale) * (1 + rg.norm()));
  }
}

}  // namespace

TEST_CASE("velocity_rates_into: NoWrench, a body nothing loads, is the torque-free motion",
          "[body][quasi]") {
  const Matrix3d principal = Vector3d(1.0, 2.0, 3.0).asDiagonal();
  Matrix3d general;
  general << 2.0, 0.3, -0.2, 0.3, 3.0, 0.1, -0.2, 0.1, 4.0;
  for (const Matrix3d& ig : {principal, general}) {
    INFO("inertia about the centroid\n" << ig);
    check_no_wrench<ReferencePoint::centroid>(ig, Vector3d::Zero());
    check_no_wrench<ReferencePoint::offset>(ig, Vector3d(0.1, -0.2, 0.3));
    check_no_wrench<ReferencePoint::fixed_point>(ig, Vector3d::Zero());
    check_no_wrench<ReferencePoint::fixed_point>(ig, Vector3d(0.1, -0.2, 0.3));
  }
}

TEST_CASE("quasi_rates: a non-finite omega is reported as such", "[body][quasi]") {
  using Body = tumble::RigidBody<tumble::ModifiedRodriguesParameters>;
  const Body body(
      tumble::MassProperties<double>::about_centroid(1.0, Vector3d(1.0, 2.0, 3.0).asDiagonal()));
  Body::QuasiCoords x = Body::QuasiCoords::Zero();
  x(6 + 3 + 1) = std::numeric_limits<double>::quiet_NaN();
  try {
    (void)body.quasi_rates(x, tumble::Wrench<double>{});
    FAIL("no NonFiniteError");
  } catch (const tumble::NonFiniteError& e) {
    const std::string what = e.what();
    INFO(what);
    CHECK(what.find("quasi_rates") != std::string::npos);
    CHECK(what.find("the velocities (v, omega) have a non-finite entry") != std::string::npos);
  }
}
