// A body held at a fixed point (RigidBody<P, ReferencePoint::fixed_point>, include/tumble/body/
// rigid_body.hpp) against the chapter's equations evaluated in the test as sums over the
// point-mass model (tests/support/body_fixtures.hpp), for every parameterization:
//   - with rddot_oc = 0 the theta-rows of M qddot = f_v + Q (Eq. 1.32), M and f_v summed over the
//     point masses (Eqs. 1.18, 1.19) and Q over the applied forces (Eqs. 1.28, 1.31), give the
//     body's thetaddot (with p.pddot = -|pdot|^2 for Euler parameters);
//   - the r-rows then give the reaction force: F_R = M_r,theta thetaddot - f_v^r - Q^r;
//   - the body's M and f_v are the theta-blocks of those sums;
//   - the angular acceleration G thetaddot + Gdot thetadot (Eq. 1.10) against a five-point
//     derivative of omega along the motion.

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include <Eigen/Dense>

#include "support/body_fixtures.hpp"
#include "support/catch.hpp"
#include "support/finite_difference.hpp"
#include "support/parameterizations.hpp"
#include "tumble/body/rigid_body.hpp"
#include "tumble/force/loads.hpp"

// Every member of these instantiations must compile, with every compiler users have: Clang 14
// instantiates here even the members constrained to the free bodies (`requires(!fixed)`), GCC
// only those of a fixed one. One of four parameters and one of three; the float and AD bodies
// are in rigid_body_scalar_types.test.cpp.
template class tumble::RigidBody<tumble::EulerParameters, tumble::ReferencePoint::fixed_point>;
#ifdef TUMBLE_TEST_HAVE_MRP
template class tumble::RigidBody<tumble::ModifiedRodriguesParameters,
                                 tumble::ReferencePoint::fixed_point>;
#endif

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using tumble::ReferencePoint;
using tumble::test::rel_error;

constexpr double kEps = std::numeric_limits<double>::epsilon();

template <class P> using Fixed = tumble::RigidBody<P, ReferencePoint::fixed_point, double>;
template <class P> using Theta = typename P::template Coords<double>;

/// The test's solution of the theta-rows: M_tt thetaddot = rhs, and for Euler parameters the
/// constraint row p.pddot = -|pdot|^2 (M_tt is singular along p).
template <class P>
Theta<P> solve_theta_rows(const Eigen::Matrix<double, P::size, P::size>& mtt, const Theta<P>& rhs,
                          const tumble::test::State<P>& s) {
  if constexpr (P::has_constraint) {
    Eigen::Matrix<double, 5, 5> a = Eigen::Matrix<double, 5, 5>::Zero();
    Eigen::Matrix<double, 5, 1> b;
    const Eigen::Vector4d p = s.theta(), pd = s.thetadot();
    a.topLeftCorner<4, 4>() = mtt;
    a.topRightCorner<4, 1>() = p;
    a.bottomLeftCorner<1, 4>() = p.transpose();
    b << rhs, -pd.squaredNorm();
    return a.fullPivLu().solve(b).template head<4>();
  } else {
    return mtt.fullPivLu().solve(rhs);
  }
}

}  // namespace

TEMPLATE_LIST_TEST_CASE("a body held at a fixed point: the theta-rows and r-rows of Eq. (1.32)",
                        "[body][fixed_point]", tumble::test::AllParameterizations) {
  using P = TestType;
  constexpr int n = P::size;
  tumble::test::Random rng(1207);
  double worst_tdd = 0, worst_reaction = 0, worst_m = 0, worst_fv = 0;
  for (int b = 0; b < 4; ++b) {
    const auto model = tumble::test::random_body(rng, true);
    const Vector3d pivot = rng.vector(1.0);
    const Fixed<P> body(tumble::test::mass_properties(model, b % 2 == 1), pivot);
    for (int i = 0; i < 6; ++i) {
      // The free coordinates of the same physical state, with the reference point at rest at the
      // pivot: what the point-mass sums are written in.
      tumble::test::PhysicalState ps = tumble::test::random_physical_state(rng);
      if (!tumble::test::usable<P>(ps)) {
        continue;
      }
      ps.position = pivot;
      ps.velocity.setZero();
      const auto s = tumble::test::make_state<P>(ps);
      const auto loads = tumble::test::random_loads(rng);

      const auto m = tumble::test::cloud_mass_matrix(model, s);
      const auto fv = tumble::test::cloud_centrifugal_coriolis(model, s);
      const auto q =
          tumble::test::generalized_force(s, tumble::test::applied_forces(model, s, loads));
      const Theta<P> rhs = fv.template tail<n>() + q.template tail<n>();
      const Theta<P> tdd_expected =
          solve_theta_rows<P>(m.template bottomRightCorner<n, n>(), rhs, s);
      const Vector3d reaction_expected = m.template topRightCorner<3, n>() * tdd_expected -
                                         fv.template head<3>() - q.template head<3>();

      const Theta<P> th = s.theta(), thd = s.thetadot();
      const auto w = tumble::test::with_elements(
          loads, [&](const auto&... e) { return tumble::total_wrench(body, 0.0, th, thd, e...); });
      const Theta<P> tdd = body.accelerations(th, thd, w);
      const Vector3d reaction = body.reaction_force(s.R, s.omega, w);

      // Scales: thetaddot against the size of the terms of the right-hand side (an entry may
      // cancel), the reaction against m a_g and F.
      const double tdd_scale = std::max(tdd_expected.cwiseAbs().maxCoeff(), 1.0);
      worst_tdd = std::max(worst_tdd, (tdd - tdd_expected).cwiseAbs().maxCoeff() / tdd_scale);
      worst_reaction = std::max(worst_reaction, rel_error(reaction, reaction_expected));
      worst_m =
          std::max(worst_m, rel_error(body.mass_matrix(th), m.template bottomRightCorner<n, n>()));
      worst_fv = std::max(
          worst_fv,
          (body.centrifugal_coriolis(th, thd) - fv.template tail<n>()).cwiseAbs().maxCoeff() /
              tumble::test::cloud_centrifugal_coriolis_scale(model, s).cwiseAbs().maxCoeff());
      // Nothing translational: the fixed body's position is its pivot, its velocity zero.
      const auto k = body.kinematics(th, thd);
      CHECK(k.position == pivot);
      CHECK(k.velocity.isZero(0));
      // The quasi-velocity rates of x = [theta; omega]: [thetadot; alpha], alpha by Eq. (1.10).
      typename Fixed<P>::QuasiCoords x;
      x << th, s.omega;
      const auto xd = body.quasi_rates(x, w);
      const Vector3d alpha = Fixed<P>::angular_acceleration(th, thd, tdd);
      CHECK(rel_error(Theta<P>(xd.template head<n>()), thd) < 1e3 * kEps);
      CHECK(rel_error(Vector3d(xd.template tail<3>()), alpha) < 1e5 * kEps);
      // Kinetic energy about the pivot, 1/2 omega . I_c omega; the centroid on its sphere.
      const Matrix3d ic = body.mass_properties().inertia_reference();
      CHECK(std::abs(body.kinetic_energy(th, thd) - 0.5 * s.omega.dot(ic * s.omega)) <
            1e3 * kEps * s.omega.squaredNorm() * ic.norm());
      CHECK(rel_error(body.centroid_position(th), Vector3d(pivot + s.R * model.centroid)) <
            10 * kEps);
    }
  }
  INFO(P::name << ": thetaddot " << worst_tdd << ", reaction " << worst_reaction << ", M "
               << worst_m << ", f_v " << worst_fv);
  if (std::getenv("TUMBLE_TEST_REPORT") != nullptr) {
    std::printf("fixed body %-27.*s thetaddot %.1e reaction %.1e M %.1e f_v %.1e\n",
                static_cast<int>(P::name.size()), P::name.data(), worst_tdd, worst_reaction,
                worst_m, worst_fv);
  }
  // Conditioned states (kMinSingularityDistance from a singularity), inertia ratios up to 100:
  // the solves lose a digit or two (measured: at most 32 eps for thetaddot, 17 eps for the
  // reaction, 6 eps for M and 3 eps for f_v over the 16 parameterizations).
  CHECK(worst_tdd < 1e3 * kEps);
  CHECK(worst_reaction < 1e3 * kEps);
  CHECK(worst_m < 100 * kEps);
  CHECK(worst_fv < 100 * kEps);
}

TEMPLATE_LIST_TEST_CASE("angular_acceleration is d omega / dt along the motion (Eq. 1.10)",
                        "[body][fixed_point]", tumble::test::AllParameterizations) {
  using P = TestType;
  tumble::test::Random rng(1208);
  const auto model = tumble::test::random_body(rng, true);
  const Fixed<P> body(tumble::test::mass_properties(model));
  for (int i = 0; i < 4; ++i) {
    const auto s = tumble::test::random_state<P>(rng);
    const Theta<P> th = s.theta(), thd = s.thetadot();
    const Theta<P> tdd = body.accelerations(th, thd, tumble::Wrench<double>{});
    // omega(h) = G(theta(h)) thetadot(h) along theta(h) = theta + h thetadot + h^2/2 thetaddot.
    const auto omega_along = [&](long double h) {
      const double hd = static_cast<double>(h);
      const Theta<P> t1 = th + hd * thd + 0.5 * hd * hd * tdd;
      return Eigen::Matrix<long double, 3, 1>(
          Vector3d(P::G(t1) * Theta<P>(thd + hd * tdd)).template cast<long double>());
    };
    const Vector3d fd =
        tumble::test::five_point_derivative(omega_along, 1e-4L).template cast<double>();
    const Vector3d alpha = Fixed<P>::angular_acceleration(th, thd, tdd);
    CHECK(rel_error(alpha, fd) < 1e-8);
    // Torque-free about the pivot: I_c alpha = -omega x I_c omega (the closed form).
    const Matrix3d ic = body.mass_properties().inertia_reference();
    CHECK(rel_error(Vector3d(ic * alpha), Vector3d(-s.omega.cross(ic * s.omega))) < 1e4 * kEps);
  }
}

TEST_CASE("a fixed body rejects a non-finite fixed point", "[body][fixed_point]") {
  const auto mp = tumble::MassProperties<double>::about_centroid(1.0, Matrix3d::Identity());
  const Vector3d bad(0.0, std::numeric_limits<double>::quiet_NaN(), 0.0);
  REQUIRE_THROWS_AS(Fixed<tumble::EulerParameters>(mp, bad), std::invalid_argument);
}
