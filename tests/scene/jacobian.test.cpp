// Tests of tumble::jacobian (include/tumble/scene/jacobian.hpp): the Jacobian df/dy of the scene's
// right-hand side, formed block by block with automatic differentiation (Jet<N>, core/jet.hpp),
// and of the block preconditioner built on it (scene/preconditioner.hpp). The reference is
// independent of it: central differences of tumble::rhs itself,
// extrapolated by Richardson (tests/support/finite_difference.hpp), one column per coordinate,
// with their own error estimate. Checked for every parameterization in mixed scenes that have
// every load type (one-body loads, spring-dampers between bodies, a user force and a user coupling
// written for any scalar), with and without the Baumgarte term of Euler parameters, off the
// constraint manifold and in charts with a base. Then: the band storage against the dense one,
// which scenes are differentiable (a user load written for double is not), the errors, the
// absence of heap allocations, and BDF integrations with the exact Jacobian against CVODE's
// difference quotients (same trajectory; no right-hand sides spent on the Jacobian).

// Must precede every Eigen include (see integrate/alloc_counter.hpp).
#define EIGEN_RUNTIME_NO_MALLOC

#include "tumble/scene/jacobian.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/LU>

#include "integrate/alloc_counter.hpp"
#include "support/catch.hpp"
#include "support/finite_difference.hpp"
#include "support/parameterizations.hpp"
#include "support/random.hpp"
#include "tumble/body/rigid_body.hpp"
#include "tumble/core/band_matrix.hpp"
#include "tumble/core/errors.hpp"
#include "tumble/force/coupling.hpp"
#include "tumble/force/gravity.hpp"
#include "tumble/force/point_force.hpp"
#include "tumble/force/spring_damper.hpp"
#include "tumble/force/user_force.hpp"
#include "tumble/integrate/scene_integrator.hpp"
#include "tumble/scene/observables.hpp"
#include "tumble/scene/preconditioner.hpp"
#include "tumble/scene/rhs.hpp"
#include "tumble/scene/scene.hpp"

namespace {

using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;
using tumble::Bodies;
using tumble::InitialState;
using tumble::Loads;
using tumble::MassProperties;
using tumble::ReferencePoint;
using tumble::RigidBody;
using tumble::Scene;

/// A user force for any scalar: a smooth nonlinear drag -c sqrt(1 + |v|^2) v, a time-dependent
/// push sin(t) e_x, and a body-fixed force a x omega at the body point r (so it reads R).
struct Swirl {
  template <class S, ReferencePoint Ref>
  tumble::Wrench<S> operator()(const S& t, const tumble::BodyKinematics<S, Ref>& k) const {
    using std::sin;
    using std::sqrt;
    tumble::Wrench<S> w;
    w.force = -S(0.4) * sqrt(S(1) + k.velocity.squaredNorm()) * k.velocity +
              tumble::Vector3<S>(sin(t), S(0), S(0));
    const tumble::Vector3<S> a(S(0.3), S(-0.2), S(0.5));
    w.add_body_force(k.rotation, tumble::Vector3<S>(S(0.1), S(0.2), S(-0.1)), a.cross(k.omega));
    return w;
  }
};

/// A user coupling for any scalar: a torsional damper, moment c (omega_b - omega_a) in a's axes
/// on a, and the opposite on b.
struct Torsion {
  template <class S>
  void operator()(const S& /*t*/, const tumble::KinematicsView<S>& a,
                  const tumble::KinematicsView<S>& b, tumble::Wrench<S>& wa,
                  tumble::Wrench<S>& wb) const {
    const tumble::Matrix3<S> rab = a.rotation.transpose() * b.rotation;
    const tumble::Vector3<S> m = S(0.7) * (rab * b.omega - a.omega);
    wa.add_moment(m);
    wb.add_moment(tumble::Vector3<S>(-(rab.transpose() * m)));
  }
};

using AllLoads =
    Loads<tumble::UniformGravity, tumble::PointForce, tumble::BodyMoment, tumble::SpringDamper,
          tumble::UserForce<Swirl>, tumble::SpringDamperBetween, tumble::UserCoupling<Torsion>>;

/// A third body type distinct from RigidBody<P, centroid>.
template <class P>
using Other = RigidBody<std::conditional_t<std::is_same_v<P, tumble::RotationVector>,
                                           tumble::EulerParameters, tumble::RotationVector>>;

template <class P>
using MixedScene =
    Scene<Bodies<RigidBody<P, ReferencePoint::offset>, RigidBody<P>, Other<P>>, AllLoads>;

MassProperties<double> random_mass(tumble::test::Random& rng, bool offset) {
  const Vector3d moments(rng.uniform(1, 2), rng.uniform(1, 2), rng.uniform(1, 2));  // I1 + I2 >= I3
  const Matrix3d r = Eigen::Matrix3d(rng.quaternion());
  return MassProperties<double>::about_centroid(rng.uniform(0.5, 3),
                                                r * moments.asDiagonal() * r.transpose(),
                                                offset ? rng.vector(0.3) : Vector3d::Zero());
}

InitialState random_state(tumble::test::Random& rng) {
  InitialState s;
  s.position = rng.vector(1.0);
  s.rotation = Matrix3d(rng.quaternion());
  s.velocity = rng.vector(1.0);
  s.omega = rng.vector(1.5);
  return s;
}

/// Five bodies of three types, every load type, two bodies of one type, one body without loads.
template <class P> void build(MixedScene<P>& scene, tumble::test::Random& rng) {
  using Off = RigidBody<P, ReferencePoint::offset>;
  using Cen = RigidBody<P>;
  const auto a = scene.add(Off(random_mass(rng, true)), random_state(rng));
  const auto b = scene.add(Cen(random_mass(rng, false)), random_state(rng));
  const auto c = scene.add(Other<P>(random_mass(rng, false)), random_state(rng));
  const auto d = scene.add(Off(random_mass(rng, true)), random_state(rng));
  scene.add(Cen(random_mass(rng, false)), random_state(rng));  // no loads at all
  const tumble::UniformGravity gravity(Vector3d(0, 0, -9.81));
  scene.add_load(a, gravity);
  scene.add_load(b, gravity);
  scene.add_load(a, tumble::PointForce(rng.vector(0.3), rng.vector(2.0), tumble::Components::body));
  scene.add_load(b, tumble::PointForce(Vector3d::Zero(), rng.vector(2.0)));
  scene.add_load(c, tumble::BodyMoment(rng.vector(1.0)));
  scene.add_load(a, tumble::SpringDamper(rng.vector(0.3), rng.vector(3.0),
                                         {.stiffness = 40, .damping = 1.5, .rest_length = 0.4}));
  scene.add_load(d, tumble::make_user_force(Swirl{}));
  scene.add_load(c, tumble::make_user_force(Swirl{}));
  scene.add_load(
      a, b,
      tumble::SpringDamperBetween(rng.vector(0.3), rng.vector(0.3),
                                  {.stiffness = 25, .damping = 0.8, .rest_length = 0.5}));
  scene.add_load(b, c,
                 tumble::SpringDamperBetween(rng.vector(0.3), Vector3d::Zero(),
                                             {.stiffness = 10, .damping = 0.3}));
  scene.add_load(a, d, tumble::UserCoupling<Torsion>(Torsion{}));
}

/// Column j of df/dy at y by Richardson-extrapolated central differences of tumble::rhs, with a
/// bound on its error: the extrapolation's own estimate (tests/support/finite_difference.hpp,
/// which assumes f in long double) plus the rounding of f in double, 3 eps |f| / h_min (the
/// weights of the extrapolation sum to less than 3).
template <class SceneT>
std::pair<VectorXd, double> fd_column(const SceneT& scene, tumble::SceneWorkspace<SceneT>& ws,
                                      double t, const tumble::SceneState& st, int j) {
  double f_scale = 0;
  const auto f = [&](long double h) {
    VectorXd yh = st.y;
    yh(j) += static_cast<double>(h);
    VectorXd out(yh.size());
    tumble::rhs(scene, ws, t, yh, std::span<const Matrix3d>(st.base), out);
    f_scale = std::max(f_scale, out.cwiseAbs().maxCoeff());
    return Eigen::Matrix<long double, Eigen::Dynamic, 1>(out.cast<long double>());
  };
  // Every coordinate and rate varies on a scale of order 1 here (rad, m, rad/s, m/s): h0 = 1/32,
  // five levels, h_min = 1/512.
  const auto fd = tumble::test::richardson_derivative(f, 1.0L / 32, 5);
  const double rounding = 3 * std::numeric_limits<double>::epsilon() * f_scale * 512;
  return {fd.value.template cast<double>(), static_cast<double>(fd.error) + rounding};
}

}  // namespace

TEMPLATE_LIST_TEST_CASE("jacobian equals extrapolated central differences of rhs",
                        "[scene][jacobian]", tumble::test::AllParameterizations) {
  using P = TestType;
  tumble::test::Random rng(7301);
  for (int trial = 0; trial < 3; ++trial) {
    MixedScene<P> scene;
    build(scene, rng);
    const bool stabilize = trial != 1;
    tumble::SceneWorkspace ws(scene);
    ws.stabilize_constraints = stabilize;
    tumble::SceneState st = scene.initial_state();
    VectorXd& y = st.y;
    if (trial == 2) {
      // Off the manifold of the Euler parameters (and anywhere else): the Baumgarte term and
      // the unconstrained parts of the formulas are differentiated where they matter.
      y += 0.02 * VectorXd::NullaryExpr(y.size(), [&] { return rng.uniform(-1, 1); });
    }
    const int n = scene.size();
    const double t = 0.37;
    MatrixXd jac = MatrixXd::Zero(n, n);
    tumble::jacobian(scene, ws, t, st, jac);
    double worst = 0;
    for (int j = 0; j < n; ++j) {
      const auto [ref, fd_error] = fd_column(scene, ws, t, st, j);
      const double scale = std::max(1.0, ref.cwiseAbs().maxCoeff());
      const double err = (jac.col(j) - ref).cwiseAbs().maxCoeff();
      INFO("trial " << trial << " (Baumgarte " << stabilize << "), column " << j << " of " << n
                    << ": |AD - FD| = " << err << ", FD error bound " << fd_error << ", scale "
                    << scale);
      // Within the differences' error bound, plus the rounding of the AD evaluation (a hundred
      // eps of the column's scale: sums of products of order-1 terms over the loads).
      CHECK(err <= fd_error + 100 * std::numeric_limits<double>::epsilon() * scale);
      worst = std::max(worst, err / scale);
    }
    CHECK(jac.allFinite());
    INFO("worst |AD - FD| / scale " << worst);
    CHECK(worst < 1e-8);
  }
}

TEST_CASE("jacobian: the band storage holds the dense Jacobian's band", "[scene][jacobian]") {
  using P = tumble::EulerZXZ;
  tumble::test::Random rng(99);
  MixedScene<P> scene;
  build(scene, rng);
  const tumble::SceneState& st = scene.initial_state();
  tumble::SceneWorkspace ws(scene);
  const int n = scene.size();
  MatrixXd dense = MatrixXd::Zero(n, n);
  tumble::jacobian(scene, ws, 0.0, st, dense);
  const int full = scene.half_bandwidth();
  for (const int bw : {full, full / 2, 3}) {
    INFO("half-bandwidth " << bw << " (the scene's: " << full << ")");
    // SUNDIALS' layout: stored upper bandwidth mu + ml for the LU's fill-in.
    const int smu = 2 * bw, ldim = smu + bw + 1;
    std::vector<double> storage(static_cast<std::size_t>(ldim) * n, 0.0);
    const tumble::BandMatrixMap band(storage.data(), n, ldim, smu, bw, bw);
    tumble::jacobian(scene, ws, 0.0, st, band);
    double in_band_diff = 0, outside = 0;
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        if (band.in_band(i, j)) {
          in_band_diff = std::max(in_band_diff, std::abs(band.coeffRef(i, j) - dense(i, j)));
        } else {
          outside = std::max(outside, std::abs(dense(i, j)));
        }
      }
    }
    CHECK(in_band_diff == 0.0);  // the same sums in the same order
    if (bw == full) {
      CHECK(outside == 0.0);  // the scene's half-bandwidth holds every nonzero
    } else {
      CHECK(outside > 0.0);  // a narrower band drops entries (as banded difference quotients do)
    }
    // The fill-in rows above the band are left alone (zero).
    double fill = 0;
    for (int j = 0; j < n; ++j) {
      for (int r = 0; r < smu - bw; ++r) {
        fill = std::max(fill, std::abs(storage[static_cast<std::size_t>(j) * ldim + r]));
      }
    }
    CHECK(fill == 0.0);
  }
}

namespace {
/// A user force written for double only: the scene cannot differentiate it.
struct DoubleOnly {
  tumble::Wrench<double> operator()(double /*t*/, const tumble::KinematicsView<double>& k) const {
    tumble::Wrench<double> w;
    w.force = -k.velocity;
    return w;
  }
};
using RV = RigidBody<tumble::RotationVector>;
using Differentiable = Scene<Bodies<RV>, Loads<tumble::UniformGravity, tumble::UserForce<Swirl>>>;
using NotDifferentiable = Scene<Bodies<RV>, Loads<tumble::UserForce<DoubleOnly, false>>>;
}  // namespace

static_assert(Differentiable::differentiable);
static_assert(!NotDifferentiable::differentiable);
static_assert(Scene<Bodies<RV>>::differentiable);  // no loads
static_assert(tumble::CvodeHasJacobian<tumble::detail::SceneSystem<Differentiable>>);
static_assert(tumble::CvodeHasBandJacobian<tumble::detail::SceneSystem<Differentiable>>);
static_assert(!tumble::CvodeHasJacobian<tumble::detail::SceneSystem<NotDifferentiable>>);
static_assert(!tumble::CvodeHasBandJacobian<tumble::detail::SceneSystem<NotDifferentiable>>);

TEST_CASE("jacobian: a singular attitude throws NonFiniteError, omega = 0 is finite",
          "[scene][jacobian]") {
  using ZXZ = RigidBody<tumble::EulerZXZ>;
  using EP = RigidBody<tumble::EulerParameters>;
  Scene<Bodies<ZXZ, EP>, Loads<tumble::UniformGravity>> scene;
  const auto a =
      scene.add(ZXZ(MassProperties<double>::about_centroid(1.0, Vector3d(1, 2, 3).asDiagonal())),
                {.omega = Vector3d(0.3, 0.2, 0.1)});
  const auto b = scene.add(EP(
      MassProperties<double>::about_centroid(1.0, Vector3d(1, 2, 3).asDiagonal())));  // omega = 0
  scene.add_load(b, tumble::UniformGravity(Vector3d(0, 0, -9.81)));
  const int n = scene.size();
  tumble::SceneState st = scene.initial_state();
  VectorXd& y = st.y;
  MatrixXd jac = MatrixXd::Zero(n, n);
  // omega = 0 with the Baumgarte term: |omega| is not differentiable there; the Jacobian takes
  // its one-sided derivative and stays finite, and its other entries are the differences'.
  tumble::SceneWorkspace ws(scene);
  ws.stabilize_constraints = true;
  tumble::jacobian(scene, ws, 0.0, st, jac);
  CHECK(jac.allFinite());
  const int ob = scene.offset(b);
  for (int j = ob; j < ob + 7; ++j) {  // the columns of q_b (the rates enter through |omega|)
    const auto [ref, fd_error] = fd_column(scene, ws, 0.0, st, j);
    CHECK((jac.col(j) - ref).cwiseAbs().maxCoeff() <=
          fd_error + 100 * std::numeric_limits<double>::epsilon() * ref.cwiseAbs().maxCoeff());
  }
  // Gimbal lock of the ZXZ body (theta2 = 0 exactly, written past the scene's chart switching):
  // G is singular, the accelerations are not finite, and the Jacobian reports it as rhs() does.
  y(scene.offset(a) + 4) = 0.0;
  jac.setZero();
  CHECK_THROWS_AS(tumble::jacobian(scene, ws, 0.0, st, jac), tumble::NonFiniteError);
  VectorXd f(n);
  CHECK_THROWS_AS(tumble::rhs(scene, ws, 0.0, st, f), tumble::NonFiniteError);
}

TEST_CASE("jacobian allocates nothing", "[scene][jacobian]") {
  tumble::test::Random rng(5);
  MixedScene<tumble::EulerXYZ> scene;
  build(scene, rng);
  const tumble::SceneState& st = scene.initial_state();
  tumble::SceneWorkspace ws(scene);
  const int n = scene.size();
  MatrixXd dense = MatrixXd::Zero(n, n);
  const int bw = scene.half_bandwidth();
  std::vector<double> storage(static_cast<std::size_t>(3 * bw + 1) * n, 0.0);
  const tumble::BandMatrixMap band(storage.data(), n, 3 * bw + 1, 2 * bw, bw, bw);
  tumble::jacobian(scene, ws, 0.0, st, dense);
  tumble::test::AllocationCounter counter;
  tumble::jacobian(scene, ws, 0.0, st, dense);
  tumble::jacobian(scene, ws, 0.0, st, band);
  CHECK(counter.stop() == 0);
}

TEST_CASE("BlockPreconditioner solves (I - gamma J_D) z = r with J_D the block diagonal of J",
          "[scene][jacobian][preconditioner]") {
  tumble::test::Random rng(17);
  using SceneT = MixedScene<tumble::ModifiedRodriguesParameters>;
  SceneT scene;
  build(scene, rng);
  tumble::SceneWorkspace ws(scene);
  ws.stabilize_constraints = false;
  tumble::BlockPreconditioner<SceneT> pre(scene);
  const tumble::SceneState& st = scene.initial_state();
  const VectorXd& y = st.y;
  const std::span<const Matrix3d> base(st.base);
  const int n = scene.size();
  MatrixXd jac = MatrixXd::Zero(n, n);
  tumble::jacobian(scene, ws, 0.2, st, jac);
  // The block diagonal of the dense Jacobian, one block [q; qdot] per body.
  MatrixXd jd = MatrixXd::Zero(n, n);
  scene.for_each_entry([&](const auto& e) {
    const int m = 2 * std::remove_cvref_t<decltype(e.body)>::nq;
    jd.block(e.offset, e.offset, m, m) = jac.block(e.offset, e.offset, m, m);
  });
  CHECK((jac - jd).cwiseAbs().maxCoeff() > 0);  // the couplings leave off-diagonal blocks
  const VectorXd r = VectorXd::NullaryExpr(n, [&] { return rng.uniform(-1, 1); });
  for (const double gamma : {1e-4, 1e-2, 0.3}) {
    INFO("gamma " << gamma);
    CHECK(pre.setup(scene, ws, 0.2, y, base, false, gamma));  // J_D computed
    VectorXd z(n);
    pre.solve(r, z);
    const MatrixXd p = MatrixXd::Identity(n, n) - gamma * jd;
    const VectorXd expected = p.partialPivLu().solve(r);
    CHECK((z - expected).cwiseAbs().maxCoeff() < 1e-13 * (1 + expected.cwiseAbs().maxCoeff()));
    // With jacobian_ok the saved blocks are reused: the same result, and no recomputation.
    CHECK_FALSE(pre.setup(scene, ws, 0.2, y, base, true, gamma));
    VectorXd z2(n);
    pre.solve(r, z2);
    CHECK(z2 == z);
  }
  VectorXd z(n);
  tumble::test::AllocationCounter counter;
  pre.setup(scene, ws, 0.2, y, base, false, 0.01);
  pre.solve(r, z);
  CHECK(counter.stop() == 0);
}

// ---- in the integrator
// ---------------------------------------------------------------------------

namespace {

/// A heavy top held at its pivot by a stiff spring-damper (k/m = 1e6 s^-2), on top of a second
/// top hanging from it by a spring: stiff, coupled, with every parameterization kind.
struct StiffRun {
  VectorXd y;
  tumble::SceneStatistics stats;
};

template <class P>
StiffRun stiff_tops(tumble::CvodeLinearSolver solver, bool exact_jacobian, double tol = 1e-8,
                    tumble::CvodePreconditioning side = tumble::CvodePreconditioning::left) {
  using Top = RigidBody<P, ReferencePoint::offset>;
  using Hanging = RigidBody<tumble::RotationVector, ReferencePoint::offset>;
  Scene<Bodies<Top, Hanging>,
        Loads<tumble::UniformGravity, tumble::SpringDamper, tumble::SpringDamperBetween>>
      scene;
  const auto mp = MassProperties<double>::about_centroid(1.0, Vector3d(0.4, 0.4, 0.2).asDiagonal(),
                                                         Vector3d(0, 0, 0.5));
  const auto a =
      scene.add(Top(mp), {.rotation = Matrix3d(Eigen::AngleAxisd(0.3, Vector3d(1, 0, 0))),
                          .omega = Vector3d(0, 0, 30)});
  const auto b =
      scene.add(Hanging(mp), {.position = Vector3d(0.3, 0, -1.0), .omega = Vector3d(1, -2, 0.5)});
  const tumble::UniformGravity g(Vector3d(0, 0, -9.81));
  scene.add_load(a, g);
  scene.add_load(b, g);
  scene.add_load(a, tumble::SpringDamper(Vector3d::Zero(), Vector3d::Zero(),
                                         {.stiffness = 1e6, .damping = 2e3}));
  scene.add_load(a, b,
                 tumble::SpringDamperBetween(Vector3d(0, 0, 0.2), Vector3d(0, 0, 0.5),
                                             {.stiffness = 200, .damping = 1, .rest_length = 0.3}));
  tumble::SceneIntegratorOptions o;
  o.cvode.method = tumble::CvodeMethod::bdf;
  o.cvode.rtol = tol;
  o.cvode.atol = tol;
  o.cvode.linear_solver = solver;
  o.cvode.use_system_jacobian = exact_jacobian;
  o.cvode.preconditioning = side;
  tumble::SceneIntegrator integrator(scene, 0.0, o);
  StiffRun r;
  const tumble::SceneState& s = integrator.advance(2.0);
  r.stats = integrator.statistics();
  // Compare physical states, not coordinates: the chart bases of the two runs may differ.
  r.y.resize(2 * 3 + 2 * 9 + 2 * 3 + 2 * 3);
  r.y << tumble::position(scene, a, s), tumble::position(scene, b, s),
      tumble::rotation(scene, a, s).reshaped(), tumble::rotation(scene, b, s).reshaped(),
      tumble::velocity(scene, a, s), tumble::velocity(scene, b, s), tumble::omega(scene, a, s),
      tumble::omega(scene, b, s);
  return r;
}

}  // namespace

TEMPLATE_TEST_CASE("BDF with the exact Jacobian: the difference-quotient run's trajectory, no "
                   "right-hand sides spent on J",
                   "[scene][jacobian][integrate]", tumble::EulerParameters, tumble::EulerZYX,
                   tumble::ModifiedRodriguesParameters) {
  using P = TestType;
  for (const auto solver : {tumble::CvodeLinearSolver::dense, tumble::CvodeLinearSolver::band}) {
    INFO((solver == tumble::CvodeLinearSolver::dense ? "dense" : "band"));
    const StiffRun exact = stiff_tops<P>(solver, true);
    const StiffRun dq = stiff_tops<P>(solver, false);
    INFO("exact: " << exact.stats.steps << " steps, " << exact.stats.rhs_evals << " rhs, "
                   << exact.stats.jacobian_evals << " J, " << exact.stats.linear_rhs_evals
                   << " rhs for J; difference quotients: " << dq.stats.steps << " steps, "
                   << dq.stats.rhs_evals << " rhs, " << dq.stats.jacobian_evals << " J, "
                   << dq.stats.linear_rhs_evals << " rhs for J");
    CHECK(exact.stats.jacobian_evals > 0);
    CHECK(exact.stats.linear_rhs_evals == 0);
    CHECK(dq.stats.linear_rhs_evals > 0);
    // Both runs against a reference at rtol = atol = 1e-12: the exact Newton matrix gives the
    // accuracy the difference quotients give.
    const StiffRun ref = stiff_tops<P>(solver, true, 1e-12);
    const double err_exact = (exact.y - ref.y).cwiseAbs().maxCoeff();
    const double err_dq = (dq.y - ref.y).cwiseAbs().maxCoeff();
    INFO("error against rtol 1e-12: exact " << err_exact << ", difference quotients " << err_dq);
    CHECK(err_exact < 2 * err_dq + 1e-7);
    CHECK(err_exact < 1e-4);
  }
}

TEMPLATE_TEST_CASE("GMRES with the block preconditioner: fewer iterations, the same accuracy",
                   "[scene][jacobian][preconditioner][integrate]", tumble::EulerParameters,
                   tumble::EulerZYX) {
  using P = TestType;
  const auto gmres = tumble::CvodeLinearSolver::gmres;
  const StiffRun ref = stiff_tops<P>(tumble::CvodeLinearSolver::dense, true, 1e-12);
  const StiffRun none = stiff_tops<P>(gmres, true, 1e-8, tumble::CvodePreconditioning::none);
  const StiffRun left = stiff_tops<P>(gmres, true, 1e-8, tumble::CvodePreconditioning::left);
  const StiffRun right = stiff_tops<P>(gmres, true, 1e-8, tumble::CvodePreconditioning::right);
  for (const StiffRun* run : {&none, &left, &right}) {
    INFO((run == &none   ? "none"
          : run == &left ? "left"
                         : "right")
         << ": " << run->stats.steps << " steps, " << run->stats.linear_iterations
         << " GMRES iterations, " << run->stats.preconditioner_setups << " setups, "
         << run->stats.nonlinear_convergence_failures << " convergence failures; error "
         << (run->y - ref.y).cwiseAbs().maxCoeff());
    CHECK((run->y - ref.y).cwiseAbs().maxCoeff() < 1e-4);
  }
  CHECK(none.stats.preconditioner_setups == 0);
  for (const StiffRun* run : {&left, &right}) {
    CHECK(run->stats.preconditioner_setups > 0);
    CHECK(run->stats.preconditioner_solves > 0);
    // The spring's stiffness sits in the top's own block: preconditioned, GMRES needs fewer
    // iterations in all and per step (measured: 1179 and 1210 against 5315 for Euler
    // parameters, 1951 and 2293 against 4270 for ZYX).
    CHECK(run->stats.linear_iterations < none.stats.linear_iterations);
    CHECK(double(run->stats.linear_iterations) / double(run->stats.steps) <
          double(none.stats.linear_iterations) / double(none.stats.steps));
  }
}
