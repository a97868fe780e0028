// Bodies held at a fixed point (ReferencePoint::fixed_point) in a scene, in both state forms,
// beside a free body and coupled to it: the layout of the state (nothing translational), the
// right-hand side against the body's own equations, the exact Jacobian against extrapolated
// central differences of the right-hand side (tests/scene/mixed_scene.hpp), the block
// preconditioner against a dense solve, chart switching, projection and the observables.

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <stdexcept>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/LU>

#include "scene/mixed_scene.hpp"
#include "support/catch.hpp"
#include "support/random.hpp"
#include "tumble/body/rigid_body.hpp"
#include "tumble/force/coupling.hpp"
#include "tumble/force/gravity.hpp"
#include "tumble/force/spring_damper.hpp"
#include "tumble/scene/accelerations.hpp"
#include "tumble/scene/charts.hpp"
#include "tumble/scene/jacobian.hpp"
#include "tumble/scene/observables.hpp"
#include "tumble/scene/preconditioner.hpp"
#include "tumble/scene/projection.hpp"
#include "tumble/scene/rhs.hpp"
#include "tumble/scene/scene.hpp"

namespace {

using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;
using tumble::EulerParameters;
using tumble::ReferencePoint;
using tumble::RotationVector;
using tumble::StateForm;

using FixedEP = tumble::RigidBody<EulerParameters, ReferencePoint::fixed_point>;
using FixedRV = tumble::RigidBody<RotationVector, ReferencePoint::fixed_point>;
// Two scene types per form, each with one body type, to keep this translation unit small (the
// Jet Jacobian of a coupling is compiled for every pair of body types): fixed three-parameter
// bodies coupled by springs (couplings, charts), and a fixed Euler-parameter body (its
// constraint). Couplings between free bodies: tests/scene/jacobian.test.cpp.
template <StateForm F>
using CoupledScene =
    tumble::Scene<tumble::Bodies<FixedRV>,
                  tumble::Loads<tumble::UniformGravity, tumble::SpringDamperBetween>, F>;
template <StateForm F>
using TopScene = tumble::Scene<tumble::Bodies<FixedEP>, tumble::Loads<tumble::UniformGravity>, F>;

constexpr double kEps = std::numeric_limits<double>::epsilon();

tumble::MassProperties<double> body_mass(tumble::test::Random& rng) {
  const Vector3d moments(rng.uniform(0.5, 1.0), rng.uniform(0.5, 1.0), rng.uniform(0.5, 1.0));
  return tumble::MassProperties<double>::about_centroid(rng.uniform(1.0, 3.0), moments.asDiagonal(),
                                                        rng.vector(0.3));
}

/// A rotation by at most 1.5 rad, well inside the rotation vector's chart (re-centered at pi),
/// where its inverse map is well conditioned: the differences of the right-hand side then measure
/// the Jacobian, not the rounding that the chart amplifies near its edge (at 2.6 rad a column's
/// differences varied by 1e-11 with their step, beyond their own error estimate).
Matrix3d moderate_rotation(tumble::test::Random& rng) {
  return Eigen::AngleAxisd(rng.uniform(0.0, 1.5), rng.vector(1.0).normalized()).toRotationMatrix();
}

/// Three fixed rotation-vector bodies joined by springs, and beside them, in a scene of its own,
/// a fixed Euler-parameter body.
template <StateForm F> struct Built {
  CoupledScene<F> scene;
  tumble::BodyId<FixedRV> a, b, c;
  Vector3d pivot_a, pivot_b;
  TopScene<F> top;
  tumble::BodyId<FixedEP> e;
};

template <StateForm F> void build(Built<F>& s, tumble::test::Random& rng) {
  s.pivot_a = rng.vector(1.0);
  s.pivot_b = rng.vector(1.0);
  const Vector3d pivot_c = rng.vector(1.0);
  s.a = s.scene.add(FixedRV(body_mass(rng), s.pivot_a),
                    {s.pivot_a, moderate_rotation(rng), Vector3d::Zero(), rng.vector(1.0)});
  s.b = s.scene.add(FixedRV(body_mass(rng), s.pivot_b),
                    {s.pivot_b, moderate_rotation(rng), Vector3d::Zero(), rng.vector(1.0)});
  s.c = s.scene.add(FixedRV(body_mass(rng), pivot_c),
                    {pivot_c, moderate_rotation(rng), Vector3d::Zero(), rng.vector(1.0)});
  const tumble::UniformGravity g(Vector3d(0, 0, -9.81));
  s.scene.add_load(s.a, g);
  s.scene.add_load(s.b, g);
  s.scene.add_load(s.c, g);
  s.scene.add_load(s.a, s.c,
                   tumble::SpringDamperBetween(rng.vector(0.5), rng.vector(0.5), {30.0, 0.7, 0.2}));
  s.scene.add_load(s.b, s.c,
                   tumble::SpringDamperBetween(rng.vector(0.5), rng.vector(0.5), {10.0, 0.2, 0.0}));
  const Vector3d pivot_e = rng.vector(1.0);
  s.e = s.top.add(FixedEP(body_mass(rng), pivot_e),
                  {pivot_e, rng.rotation(), Vector3d::Zero(), rng.vector(1.0)});
  s.top.add_load(s.e, g);
}

}  // namespace

TEMPLATE_TEST_CASE_SIG("a fixed body's block holds its attitude and rates only",
                       "[scene][fixed_point]", ((StateForm F), F), StateForm::generalized,
                       StateForm::quasi_velocities) {
  tumble::test::Random rng(4401);
  Built<F> s;
  build(s, rng);
  constexpr bool quasi = F == StateForm::quasi_velocities;
  CHECK(s.scene.size() == 3 * 6);
  CHECK(s.top.size() == (quasi ? 7 : 8));
  const tumble::SceneState& y = s.scene.initial_state();
  // Observables: the pivot, at rest; the attitude and omega as given.
  CHECK(tumble::position(s.scene, s.a, y) == s.pivot_a);
  CHECK(tumble::velocity(s.scene, s.b, y).isZero(0));
  CHECK(tumble::position(s.scene, s.b, y) == s.pivot_b);
  // The centroid moves on a sphere about the pivot: its velocity is R (omega x r_g).
  const auto& body = s.scene.body(s.a);
  const Vector3d rg = body.mass_properties().centroid();
  const Matrix3d r = tumble::rotation(s.scene, s.a, y);
  const Vector3d w = tumble::omega(s.scene, s.a, y);
  CHECK((tumble::centroid_position(s.scene, s.a, y) - (s.pivot_a + r * rg)).norm() < 10 * kEps);
  // Kinetic energy: each body's 1/2 omega . I_c omega about its pivot.
  double t_expected = 0;
  for (const auto id : {s.a, s.b, s.c}) {
    const Vector3d wi = tumble::omega(s.scene, id, y);
    t_expected += 0.5 * wi.dot(s.scene.body(id).mass_properties().inertia_reference() * wi);
  }
  CHECK(std::abs(tumble::kinetic_energy(s.scene, y) - t_expected) < 100 * kEps * t_expected);

  // A fixed body starts at its pivot, at rest, and keeps no velocity.
  TopScene<F> other;
  const tumble::InitialState moved{Vector3d(1, 0, 0), Matrix3d::Identity(), Vector3d::Zero(),
                                   Vector3d::Zero()};
  REQUIRE_THROWS_AS(other.add(FixedEP(body_mass(rng)), moved), std::invalid_argument);
  const tumble::InitialState moving{Vector3d::Zero(), Matrix3d::Identity(), Vector3d(0, 1, 0),
                                    Vector3d::Zero()};
  REQUIRE_THROWS_AS(other.add(FixedEP(body_mass(rng)), moving), std::invalid_argument);
  tumble::SceneState copy = y;
  REQUIRE_THROWS_AS(tumble::set_velocity(s.scene, s.a, copy, Vector3d(1, 0, 0), w),
                    std::invalid_argument);
  tumble::set_velocity(s.scene, s.a, copy, Vector3d::Zero(), Vector3d(0.1, 0.2, 0.3));
  CHECK((tumble::omega(s.scene, s.a, copy) - Vector3d(0.1, 0.2, 0.3)).norm() < 10 * kEps);
  // A held body's own form sets omega alone: the same state as with v = 0, the attitude kept.
  tumble::SceneState held = y;
  tumble::set_velocity(s.scene, s.a, held, Vector3d(0.1, 0.2, 0.3));
  CHECK(held.y == copy.y);
  CHECK(tumble::rotation(s.scene, s.a, held) == tumble::rotation(s.scene, s.a, y));
}

namespace {
// reaction_force and angular_acceleration evaluate the loads: the time they are evaluated at is
// a required argument (a forgotten one would silently mean t = 0 for time-dependent loads).
template <class S, class B>
concept AccelerationsWithoutTime = requires(const S& scene, tumble::BodyId<B> b,
                                            const tumble::SceneState& y) {
  tumble::reaction_force(scene, b, y);
}
|| requires(const S& scene, tumble::BodyId<B> b, const tumble::SceneState& y) {
  tumble::angular_acceleration(scene, b, y);
};
template <class S, class B>
concept AccelerationsWithTime = requires(const S& scene, tumble::BodyId<B> b,
                                         const tumble::SceneState& y) {
  tumble::reaction_force(scene, b, y, 0.0);
  tumble::angular_acceleration(scene, b, y, 0.0);
};
static_assert(AccelerationsWithTime<TopScene<StateForm::quasi_velocities>, FixedEP>);
static_assert(!AccelerationsWithoutTime<TopScene<StateForm::quasi_velocities>, FixedEP>);
}  // namespace

TEMPLATE_TEST_CASE_SIG("rhs of a fixed body: the body's own rates, nothing translational",
                       "[scene][fixed_point]", ((StateForm F), F), StateForm::generalized,
                       StateForm::quasi_velocities) {
  tumble::test::Random rng(4402);
  Built<F> s;
  build(s, rng);
  tumble::SceneWorkspace ws(s.scene);
  ws.stabilize_constraints = false;
  const tumble::SceneState& y = s.scene.initial_state();
  VectorXd ydot(s.scene.size());
  tumble::rhs(s.scene, ws, 0.0, y, ydot);
  // The rate of omega (quasi form) or of thetadot (generalized) from the scene's alpha: alpha =
  // G thetaddot + Gdot thetadot, the same alpha tumble::angular_acceleration reports.
  const auto& e = std::as_const(s.scene).entry(s.b);
  const Vector3d alpha = tumble::angular_acceleration(s.scene, s.b, y, 0.0);
  if constexpr (F == StateForm::quasi_velocities) {
    CHECK((ydot.segment<3>(e.rates) - alpha).norm() < 100 * kEps * (1 + alpha.norm()));
  } else {
    const Vector3d th = y.y.segment<3>(e.offset), thd = y.y.segment<3>(e.rates);
    const Vector3d a = FixedRV::angular_acceleration(th, thd, ydot.segment<3>(e.rates).eval());
    CHECK((a - alpha).norm() < 1e3 * kEps * (1 + alpha.norm()));
    CHECK((ydot.segment<3>(e.offset) - thd).norm() == 0);
  }
}

TEMPLATE_TEST_CASE_SIG("jacobian of a scene with fixed bodies equals differences of rhs",
                       "[scene][fixed_point]", ((StateForm F), F), StateForm::generalized,
                       StateForm::quasi_velocities) {
  tumble::test::Random rng(4403);
  for (int trial = 0; trial < 2; ++trial) {
    Built<F> s;
    build(s, rng);
    tumble::SceneWorkspace ws(s.scene);
    ws.stabilize_constraints = trial == 0;
    tumble::SceneState st = s.scene.initial_state();
    const int n = s.scene.size();
    MatrixXd jac = MatrixXd::Zero(n, n);
    tumble::jacobian(s.scene, ws, 0.2, st, jac);
    for (int j = 0; j < n; ++j) {
      const auto [ref, fd_error] = tumble::test::mixed::fd_column(s.scene, ws, 0.2, st, j);
      const double scale = std::max(1.0, ref.cwiseAbs().maxCoeff());
      const double err = (jac.col(j) - ref).cwiseAbs().maxCoeff();
      INFO("column " << j << " of " << n << ": |AD - FD| = " << err << ", bound " << fd_error);
      CHECK(err <= fd_error + 100 * kEps * scale);
    }
    // The block preconditioner: its block of a fixed body is that body's diagonal block of J.
    tumble::BlockPreconditioner<CoupledScene<F>> pre(s.scene);
    const double gamma = 0.01;
    pre.setup(s.scene, ws, 0.2, st.y, std::span<const Matrix3d>(st.base), false, gamma);
    const VectorXd r = VectorXd::NullaryExpr(n, [&] { return rng.uniform(-1, 1); });
    VectorXd z(n);
    pre.solve(r, z);
    const auto& e = std::as_const(s.scene).entry(s.b);
    constexpr int m = std::remove_cvref_t<decltype(e)>::block_size;
    const MatrixXd block = MatrixXd::Identity(m, m) - gamma * jac.block(e.offset, e.offset, m, m);
    const VectorXd expected = block.lu().solve(r.segment(e.offset, m));
    CHECK((z.segment(e.offset, m) - expected).cwiseAbs().maxCoeff() < 1e-12);
  }
}

TEMPLATE_TEST_CASE_SIG("charts and projection of fixed bodies keep the attitude and omega",
                       "[scene][fixed_point]", ((StateForm F), F), StateForm::generalized,
                       StateForm::quasi_velocities) {
  tumble::test::Random rng(4404);
  Built<F> s;
  build(s, rng);
  tumble::SceneState st = s.scene.initial_state();
  const Matrix3d r_before = tumble::rotation(s.scene, s.b, st);
  const Vector3d w_before = tumble::omega(s.scene, s.b, st);
  // Leave the chart of the second rotation-vector body: same attitude and omega.
  const int which[3] = {0, 1, 0};
  REQUIRE(s.scene.chart_bodies().size() == 3);
  CHECK(tumble::leave_charts(s.scene, st.y, std::span<Matrix3d>(st.base), which, [](int) {}) == 1);
  CHECK((tumble::rotation(s.scene, s.b, st) - r_before).cwiseAbs().maxCoeff() < 1e-14);
  CHECK((tumble::omega(s.scene, s.b, st) - w_before).cwiseAbs().maxCoeff() < 1e-13);
  CHECK(tumble::position(s.scene, s.b, st) == s.pivot_b);
  // The Euler parameters of the fixed body, pushed off |p| = 1, are projected back; its omega
  // is unchanged.
  tumble::SceneState sp = s.top.initial_state();
  const auto& ee = std::as_const(s.top).entry(s.e);
  const Matrix3d r_e = tumble::rotation(s.top, s.e, sp);
  const Vector3d w_e = tumble::omega(s.top, s.e, sp);
  sp.y.segment<4>(ee.offset) *= 1.01;
  CHECK(tumble::constraint_drift(s.top, sp) > 1e-3);
  VectorXd corr(sp.y.size()), none;
  tumble::project(s.top, sp.y, corr, none);
  sp.y += corr;
  CHECK(tumble::constraint_drift(s.top, sp) < 10 * kEps);
  CHECK((tumble::rotation(s.top, s.e, sp) - r_e).cwiseAbs().maxCoeff() < 10 * kEps);
  CHECK((tumble::omega(s.top, s.e, sp) - w_e).norm() < 100 * kEps * (1 + w_e.norm()));
}
