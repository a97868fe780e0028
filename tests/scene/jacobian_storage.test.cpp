// Tests of tumble::jacobian (include/tumble/scene/jacobian.hpp) beyond its values (those:
// jacobian.test.cpp): the band storage against the dense one, which scenes are differentiable (a
// user load written for double is not), a singular attitude, no heap allocation, and the block
// preconditioner (scene/preconditioner.hpp) against a dense solve with the block diagonal of J.

// Must precede every Eigen include (see integrate/alloc_counter.hpp).
#define EIGEN_RUNTIME_NO_MALLOC

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>
#include <type_traits>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/LU>

#include "integrate/alloc_counter.hpp"
#include "scene/mixed_scene.hpp"
#include "support/catch.hpp"
#include "support/random.hpp"
#include "tumble/body/rigid_body.hpp"
#include "tumble/core/band_matrix.hpp"
#include "tumble/core/errors.hpp"
#include "tumble/force/gravity.hpp"
#include "tumble/force/user_force.hpp"
#include "tumble/integrate/scene_integrator.hpp"
#include "tumble/orientation/euler_angles.hpp"
#include "tumble/scene/jacobian.hpp"
#include "tumble/scene/preconditioner.hpp"
#include "tumble/scene/rhs.hpp"
#include "tumble/scene/scene.hpp"

namespace {

using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;
using tumble::Bodies;
using tumble::Loads;
using tumble::MassProperties;
using tumble::RigidBody;
using tumble::Scene;
using tumble::test::mixed::build;
using tumble::test::mixed::fd_column;
using tumble::test::mixed::MixedScene;
using tumble::test::mixed::Swirl;

}  // namespace

namespace {
/// The parameterization of the mixed scene here: one scene type for all the tests of this file
/// (each scene type adds its Jacobian, in Jet scalars, to the compile).
using ChartParam = tumble::EulerZXZ;
}  // namespace

TEST_CASE("jacobian: the band storage holds the dense Jacobian's band", "[scene][jacobian]") {
  using P = ChartParam;
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
  MixedScene<ChartParam> scene;
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
  using SceneT = MixedScene<ChartParam>;
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
