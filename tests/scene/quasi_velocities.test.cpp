// Tests of the quasi-velocity state form (StateForm::quasi_velocities, scene/state.hpp): per body
// y = [r_oc; theta; v; omega] and y' = [v; G^{-1} omega; a_c; alpha] (scene/rhs.hpp,
// RigidBody::quasi_rates). Each against an independent expectation:
//  - the right-hand side against the generalized form [q; qdot] of the same physical state:
//    a_c = rddot_oc and alpha = G thetaddot + Gdot thetadot (reference chapter, Eq. 1.10) from
//    the generalized qddot, thetadot = the generalized state's own thetadot, for Euler parameters,
//    an Euler-angle sequence (in a chart with a base), MRP and the rotation vector, bodies framed
//    at and off their centroid, with gravity and spring-dampers between bodies;
//  - the exact Jacobian (jacobian.hpp, Jet AD) against Richardson-extrapolated central
//    differences of the right-hand side, on and off the quaternion constraint, with and without
//    its drift correction;
//  - the block preconditioner against a dense solve with the block diagonal of that Jacobian;
//  - the layout: sizes, offsets, bandwidth, observables read back the initial state;
//  - chart switches leave v and omega untouched, and a non-finite omega is reported.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>
#include <string>
#include <type_traits>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/LU>

#include "support/catch.hpp"
#include "support/random.hpp"
#include "tumble/core/errors.hpp"
#include "tumble/tumble.hpp"

namespace {

using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;
using tumble::Bodies;
using tumble::Loads;
using tumble::MassProperties;
using tumble::ReferencePoint;
using tumble::RigidBody;
using tumble::Scene;
using tumble::SceneState;
using tumble::SceneWorkspace;
using tumble::StateForm;

using EPOff = RigidBody<tumble::EulerParameters, ReferencePoint::offset>;
using ZYX = RigidBody<tumble::EulerZYX>;
using MRPOff = RigidBody<tumble::ModifiedRodriguesParameters, ReferencePoint::offset>;
using RV = RigidBody<tumble::RotationVector>;

template <StateForm F>
using MixedScene = Scene<Bodies<EPOff, ZYX, MRPOff, RV>,
                         Loads<tumble::UniformGravity, tumble::SpringDamperBetween>, F>;

}  // namespace

// Every member of the quasi-form scene and its preconditioner compiles, used or not.
template class tumble::Scene<Bodies<EPOff, ZYX, MRPOff, RV>,
                             Loads<tumble::UniformGravity, tumble::SpringDamperBetween>,
                             StateForm::quasi_velocities>;
template class tumble::BlockPreconditioner<MixedScene<StateForm::quasi_velocities>>;

namespace {

MassProperties<double> offset_mass(const Vector3d& centroid) {
  Matrix3d i;
  i << 1.0, 0.1, -0.05, 0.1, 2.0, 0.2, -0.05, 0.2, 2.5;
  return MassProperties<double>::about_centroid(1.5, i, centroid);
}
MassProperties<double> centroid_mass() {
  return MassProperties<double>::about_centroid(2.0, Vector3d(1.0, 2.0, 3.0).asDiagonal());
}

/// The same physical scene in form F: four bodies with random states (the Euler-angle body 20
/// deg from gimbal lock, so its chart is centered with a base), gravity on all, two
/// spring-dampers between bodies. Handles are returned through the ids (0..3, in order).
template <StateForm F> MixedScene<F> make_scene(unsigned seed) {
  tumble::test::Random rnd(seed);
  MixedScene<F> s;
  const auto state = [&](const Matrix3d& r) {
    return tumble::InitialState{.position = rnd.vector(),
                                .rotation = r,
                                .velocity = rnd.vector(),
                                .omega = rnd.vector(2.0)};
  };
  const auto a = s.add(EPOff(offset_mass(Vector3d(0.3, -0.2, 0.1))), state(rnd.rotation()));
  const Matrix3d near_lock = Eigen::AngleAxisd(0.4, Vector3d::UnitZ()).toRotationMatrix() *
                             Eigen::AngleAxisd(70.0 * std::numbers::pi / 180, Vector3d::UnitY()) *
                             Eigen::AngleAxisd(-0.3, Vector3d::UnitX());
  const auto b = s.add(ZYX(centroid_mass()), state(near_lock));
  const auto c = s.add(MRPOff(offset_mass(Vector3d(-0.1, 0.25, 0.2))), state(rnd.rotation()));
  const auto d = s.add(RV(centroid_mass()), state(rnd.rotation()));
  const tumble::UniformGravity g(Vector3d(0.0, 0.0, -9.81));
  s.add_load(a, g);
  s.add_load(b, g);
  s.add_load(c, g);
  s.add_load(d, g);
  s.add_load(a, b,
             tumble::SpringDamperBetween(Vector3d(0.1, 0.2, 0.0), Vector3d(0.0, -0.1, 0.3),
                                         {.stiffness = 40.0, .damping = 0.5, .rest_length = 0.5}));
  s.add_load(c, d,
             tumble::SpringDamperBetween(Vector3d(-0.2, 0.0, 0.1), Vector3d(0.3, 0.1, 0.0),
                                         {.stiffness = 25.0, .damping = 0.8, .rest_length = 0.0}));
  return s;
}

template <class Scn>
VectorXd rhs_of(const Scn& scene, SceneWorkspace<Scn>& ws, const VectorXd& y, const SceneState& s) {
  VectorXd yd(scene.size());
  tumble::rhs(scene, ws, 0.3, y, std::span<const Matrix3d>(s.base), yd);
  return yd;
}

/// The largest |a - b| / (1 + |b|) entrywise.
double rel_diff(const Eigen::Ref<const VectorXd>& a, const Eigen::Ref<const VectorXd>& b) {
  return ((a - b).array().abs() / (1.0 + b.array().abs())).maxCoeff();
}

}  // namespace

TEST_CASE("quasi-velocity state: layout, initial state and observables", "[scene][quasi]") {
  const auto gs = make_scene<StateForm::generalized>(7);
  const auto qs = make_scene<StateForm::quasi_velocities>(7);
  STATIC_REQUIRE(MixedScene<StateForm::quasi_velocities>::form == StateForm::quasi_velocities);
  // [r; theta; v; omega]: nq + 6 per body (EP 13, three-parameter sets 12), against 2 nq.
  CHECK(qs.size() == 13 + 12 + 12 + 12);
  CHECK(gs.size() == 14 + 12 + 12 + 12);
  const tumble::BodyId<EPOff> a{0, 0};
  const tumble::BodyId<ZYX> b{1, 0};
  const tumble::BodyId<MRPOff> c{2, 0};
  const tumble::BodyId<RV> d{3, 0};
  CHECK(qs.offset(a) == 0);
  CHECK(qs.offset(b) == 13);
  CHECK(qs.offset(c) == 25);
  CHECK(qs.offset(d) == 37);
  CHECK(qs.entry(c).rates == 25 + 6);
  // The coupling (a, b) spans body a's first entry to body b's last: 24.
  CHECK(qs.half_bandwidth() == 24);
  const SceneState& q0 = qs.initial_state();
  const SceneState& g0 = gs.initial_state();
  CHECK_FALSE(q0.base[1].isIdentity(1e-3));  // the Euler-angle body starts in a centered chart
  tumble::test::Random rnd(7);  // the draws of make_scene, in order: R, then r, v, omega
  rnd.rotation();
  const Vector3d pos = rnd.vector();
  const Vector3d vel = rnd.vector(), om = rnd.vector(2.0);
  CHECK(q0.y.segment<3>(0) == pos);
  CHECK(q0.y.segment<3>(7) == vel);
  CHECK(q0.y.segment<3>(10) == om);  // omega is stored as given
  CHECK(tumble::omega(qs, a, q0) == om);
  CHECK(tumble::velocity(qs, a, q0) == vel);
  // Every observable agrees with the generalized form of the same state.
  CHECK((tumble::rotation(qs, b, q0) - tumble::rotation(gs, b, g0)).norm() < 1e-15);
  CHECK((tumble::omega(qs, d, q0) - tumble::omega(gs, d, g0)).norm() < 1e-14);
  CHECK(std::abs(tumble::energy(qs, q0) - tumble::energy(gs, g0)) < 1e-13 * tumble::energy(gs, g0));
  CHECK((tumble::angular_momentum(qs, q0) - tumble::angular_momentum(gs, g0)).norm() <
        1e-13 * tumble::angular_momentum(gs, g0).norm());
  CHECK((tumble::linear_momentum(qs, q0) - tumble::linear_momentum(gs, g0)).norm() < 1e-13);
  CHECK(tumble::constraint_drift(qs, q0) < 4e-16);
  // set_velocity writes v and omega as such.
  SceneState s = q0;
  tumble::set_velocity(qs, c, s, Vector3d(1, 2, 3), Vector3d(-1, 0.5, 4));
  CHECK(tumble::velocity(qs, c, s) == Vector3d(1, 2, 3));
  CHECK(tumble::omega(qs, c, s) == Vector3d(-1, 0.5, 4));
}

// The generalized right-hand side is Eq. (1.32) solved for qddot (checked against M, f_v and Q in
// tests/body); from it, alpha = G thetaddot + Gdot thetadot (Eq. 1.10) and a_c = rddot_oc.
TEST_CASE("quasi-velocity right-hand side agrees with the generalized one", "[scene][quasi]") {
  for (unsigned seed : {1u, 2u, 3u, 4u, 5u}) {
    INFO("seed " << seed);
    const auto gs = make_scene<StateForm::generalized>(seed);
    const auto qs = make_scene<StateForm::quasi_velocities>(seed);
    SceneWorkspace<MixedScene<StateForm::generalized>> gw(gs);
    SceneWorkspace<MixedScene<StateForm::quasi_velocities>> qw(qs);
    const SceneState& g0 = gs.initial_state();
    const SceneState& q0 = qs.initial_state();
    const VectorXd gd = rhs_of(gs, gw, g0.y, g0);
    const VectorXd qd = rhs_of(qs, qw, q0.y, q0);
    double worst = 0;
    const auto check_body = [&](const auto& ge, const auto& qe) {
      using Body = std::remove_cvref_t<decltype(ge.body)>;
      using P = typename Body::Param;
      constexpr int n = Body::n_theta;
      const typename Body::Theta th = g0.y.template segment<n>(ge.offset + 3);
      const typename Body::Theta thd = g0.y.template segment<n>(ge.rates + 3);
      const typename Body::Theta thdd = gd.template segment<n>(ge.rates + 3);
      const Vector3d alpha = P::G(th) * thdd + P::Gdot_thetadot(th, thd);
      const Vector3d acc = gd.template segment<3>(ge.rates);
      INFO("body " << ge.id << " (" << P::name << ")");
      CHECK(q0.y.template segment<n>(qe.offset + 3) == th);  // the same chart
      const double e_r =
          rel_diff(qd.template segment<3>(qe.offset), gd.template segment<3>(ge.offset));
      const double e_th = rel_diff(qd.template segment<n>(qe.offset + 3), thd);
      const double e_a = rel_diff(qd.template segment<3>(qe.rates), acc);
      const double e_w = rel_diff(qd.template segment<3>(qe.rates + 3), alpha);
      CHECK(e_r == 0.0);
      CHECK(e_th < 1e-15);
      CHECK(e_a < 1e-13);
      CHECK(e_w < 1e-13);
      worst = std::max({worst, e_th, e_a, e_w});
    };
    check_body(gs.entry(tumble::BodyId<EPOff>{0, 0}), qs.entry(tumble::BodyId<EPOff>{0, 0}));
    check_body(gs.entry(tumble::BodyId<ZYX>{1, 0}), qs.entry(tumble::BodyId<ZYX>{1, 0}));
    check_body(gs.entry(tumble::BodyId<MRPOff>{2, 0}), qs.entry(tumble::BodyId<MRPOff>{2, 0}));
    check_body(gs.entry(tumble::BodyId<RV>{3, 0}), qs.entry(tumble::BodyId<RV>{3, 0}));
    INFO("largest relative difference " << worst);
    CHECK(worst < 1e-13);
  }
}

// Central differences D(h) at h and h/2, one Richardson step (error O(h^4)), per column.
TEST_CASE("quasi-velocity exact Jacobian against finite differences", "[scene][quasi]") {
  using Q = MixedScene<StateForm::quasi_velocities>;
  for (const bool stabilize : {false, true}) {
    for (const double p_scale : {1.0, 1.01}) {  // on the unit sphere, and off it
      INFO("stabilize " << stabilize << ", |p| = " << p_scale);
      const Q qs = make_scene<StateForm::quasi_velocities>(11);
      SceneWorkspace<Q> ws(qs);
      ws.stabilize_constraints = stabilize;
      SceneState s = qs.initial_state();
      s.y.segment<4>(3) *= p_scale;
      const int n = qs.size();
      MatrixXd jac = MatrixXd::Zero(n, n);
      tumble::jacobian(qs, ws, 0.3, s, jac);
      MatrixXd fd(n, n);
      for (int j = 0; j < n; ++j) {
        const double h = 1e-3 * (1.0 + std::abs(s.y(j)));
        const auto diff = [&](double step) {
          VectorXd yp = s.y, ym = s.y;
          yp(j) += step;
          ym(j) -= step;
          return VectorXd((rhs_of(qs, ws, yp, s) - rhs_of(qs, ws, ym, s)) / (2 * step));
        };
        const VectorXd d1 = diff(h), d2 = diff(h / 2);
        fd.col(j) = (4 * d2 - d1) / 3;
      }
      const double scale = std::max(1.0, fd.cwiseAbs().maxCoeff());
      const double err = (jac - fd).cwiseAbs().maxCoeff() / scale;
      INFO("max |J - J_fd| / max|J| = " << err << ", max|J| = " << scale);
      CHECK(err < 1e-8);
      // The rows of rdot = v are [0 I 0] exactly.
      CHECK(jac.block(0, 0, 3, n).cwiseAbs().sum() == 3.0);
      CHECK(jac.block<3, 3>(0, 7) == Eigen::Matrix3d::Identity());

      // Block preconditioner: P^{-1} r against a dense solve with the block diagonal of J.
      tumble::BlockPreconditioner<Q> pre(qs);
      const double gamma = 0.05;
      pre.setup(qs, ws, 0.3, s.y, std::span<const Matrix3d>(s.base), false, gamma);
      MatrixXd jd = MatrixXd::Zero(n, n);
      int o = 0;
      for (const int m : {13, 12, 12, 12}) {
        jd.block(o, o, m, m) = jac.block(o, o, m, m);
        o += m;
      }
      const VectorXd r = VectorXd::LinSpaced(n, -1.0, 2.0);
      VectorXd z(n);
      pre.solve(r, z);
      const VectorXd z_ref = (MatrixXd::Identity(n, n) - gamma * jd).partialPivLu().solve(r);
      CHECK((z - z_ref).cwiseAbs().maxCoeff() < 1e-12 * (1.0 + z_ref.cwiseAbs().maxCoeff()));
    }
  }
}

// The drift correction of Euler parameters (body_terms.hpp): pdot += -(g/2)(|p|^2 - 1) p with
// g = |omega|, so that d(|p|^2)/dt = -g |p|^2 (|p|^2 - 1).
TEST_CASE("quasi-velocity Euler parameters: the drift correction", "[scene][quasi]") {
  using Q = MixedScene<StateForm::quasi_velocities>;
  const Q qs = make_scene<StateForm::quasi_velocities>(5);
  SceneWorkspace<Q> ws(qs);
  SceneState s = qs.initial_state();
  s.y.segment<4>(3) *= 1.01;
  ws.stabilize_constraints = false;
  const VectorXd plain = rhs_of(qs, ws, s.y, s);
  ws.stabilize_constraints = true;
  const VectorXd stab = rhs_of(qs, ws, s.y, s);
  const Eigen::Vector4d p = s.y.segment<4>(3);
  const double g = s.y.segment<3>(10).norm();
  const Eigen::Vector4d expected = -0.5 * g * (p.squaredNorm() - 1.0) * p;
  CHECK((stab.segment<4>(3) - plain.segment<4>(3) - expected).norm() < 1e-15);
  // Without it pdot is tangent to the sphere through p; with it |p|^2 decays at the rate g |p|^2.
  CHECK(std::abs(p.dot(plain.segment<4>(3))) < 1e-15);
  const double dpp = 2 * p.dot(stab.segment<4>(3));
  CHECK(std::abs(dpp + g * p.squaredNorm() * (p.squaredNorm() - 1.0)) < 1e-14);
  // Everything else is unchanged.
  CHECK(stab.segment(7, stab.size() - 7) == plain.segment(7, plain.size() - 7));
}

TEST_CASE("quasi-velocity chart switches change theta and the base only", "[scene][quasi]") {
  using Q = MixedScene<StateForm::quasi_velocities>;
  const Q qs = make_scene<StateForm::quasi_velocities>(3);
  SceneState s = qs.initial_state();
  const SceneState before = s;
  const int which[] = {1, 1, 1};  // the ZYX, MRP and RV bodies
  const int n = tumble::leave_charts(qs, s.y, std::span<Matrix3d>(s.base), which, [](int) {});
  CHECK(n == 3);
  qs.for_each_entry([&](const auto& e) {
    INFO("body " << e.id);
    // v and omega: the same bits; r too.
    CHECK(s.y.template segment<6>(e.rates) == before.y.template segment<6>(e.rates));
    CHECK(s.y.template segment<3>(e.offset) == before.y.template segment<3>(e.offset));
  });
  const tumble::BodyId<ZYX> b{1, 0};
  const tumble::BodyId<MRPOff> c{2, 0};
  const tumble::BodyId<RV> d{3, 0};
  // The attitude is unchanged (to rounding of the new base); the rates too, so omega is.
  using tumble::test::rotation_angle_between;
  CHECK(rotation_angle_between(tumble::rotation(qs, b, s), tumble::rotation(qs, b, before)) <
        1e-15);
  CHECK(rotation_angle_between(tumble::rotation(qs, c, s), tumble::rotation(qs, c, before)) <
        1e-15);
  CHECK(rotation_angle_between(tumble::rotation(qs, d, s), tumble::rotation(qs, d, before)) <
        1e-15);
  CHECK(tumble::omega(qs, b, s) == tumble::omega(qs, b, before));
}

TEST_CASE("quasi-velocity right-hand side reports a non-finite omega", "[scene][quasi]") {
  using Q = MixedScene<StateForm::quasi_velocities>;
  const Q qs = make_scene<StateForm::quasi_velocities>(3);
  SceneWorkspace<Q> ws(qs);
  SceneState s = qs.initial_state();
  s.y(25 + 6 + 4) = std::nan("");  // omega_y of the MRP body
  VectorXd yd(qs.size());
  CHECK_THROWS_AS(tumble::rhs(qs, ws, 0.0, s, yd), tumble::NonFiniteError);
  try {
    tumble::rhs(qs, ws, 0.0, s, yd);
  } catch (const tumble::NonFiniteError& e) {
    // The spring-damper on the body reads its omega: the load is what turns non-finite first.
    INFO(e.what());
    CHECK(std::string(e.what()).find("quasi_rates") != std::string::npos);
  }
}
