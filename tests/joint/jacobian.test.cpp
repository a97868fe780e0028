// The exact Jacobian of a mechanism (scene/jacobian.hpp, mechanism_jacobian: forward-mode AD of
// the bodies, loads and joints at fixed multipliers, and the multipliers' derivative through the
// constraint solve) against central differences of tumble::rhs itself, extrapolated by
// Richardson (tests/support/finite_difference.hpp), one column per coordinate. Checked on
// Andrews' mechanism (redundant rows frozen, a spring and a motor; Euler parameters and the
// rotation vector) at a state of its motion, and on a spatial double pendulum with a spring
// between its links (a coupling), a spherical and a universal joint, off the constraints. CVODE's
// BDF with it on Andrews' mechanism, against the difference quotients: andrews_bdf.test.cpp.
// Compiled in three slices (tests/CMakeLists.txt), one parameterization of Andrews' mechanism each,
// the double pendulum in slice 2.

#include "tumble/scene/jacobian.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <tuple>
#include <vector>

#include <Eigen/Geometry>

#include "support/catch.hpp"
#include "support/finite_difference.hpp"
#include "support/parameterizations.hpp"
#include "tumble/integrate.hpp"

// Unused here (the example runs in andrews.test.cpp): its main as a function template, which is
// never instantiated, so its body (the front door on the mechanism) is not compiled.
#define main(...) andrews_jacobian_main(auto...)
#include "../../examples/andrews.cpp"  // NOLINT(bugprone-suspicious-include)
#undef main

namespace {

using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;
using namespace tumble;

/// Column j of df/dy by extrapolated central differences with the first step h0, and its error
/// bound: the extrapolation's, plus the rounding of rhs at the smallest step. That rounding is
/// measured, not assumed: a mechanism's right-hand side goes through the constraint solve, whose
/// rounding grows with its condition, so the noise of f along column j is taken as the largest
/// second difference |f(y + d) - 2 f(y) + f(y - d)| / 2 at steps d far below h0 (where the
/// curvature's part, f'' d^2, is below 1e-16 of f).
template <class SceneT>
std::pair<VectorXd, double> fd_column(const SceneT& scene, SceneWorkspace<SceneT>& ws, double t,
                                      const SceneState& st, int j, double h0) {
  const auto at = [&](double h) {
    VectorXd yh = st.y;
    yh(j) += h;
    VectorXd out(yh.size());
    rhs(scene, ws, t, yh, std::span<const Matrix3d>(st.base), out);
    return out;
  };
  const VectorXd f0 = at(0.0);
  double noise = std::numeric_limits<double>::epsilon() * f0.cwiseAbs().maxCoeff();
  for (int k = 1; k <= 8; ++k) {
    const double d = 1e-8 * h0 * k;
    noise = std::max(noise, 0.5 * (at(d) + at(-d) - 2 * f0).cwiseAbs().maxCoeff());
  }
  const auto f = [&](long double h) {
    return Eigen::Matrix<long double, Eigen::Dynamic, 1>(
        at(static_cast<double>(h)).template cast<long double>());
  };
  constexpr int levels = 5;
  const auto fd = test::richardson_derivative(f, static_cast<long double>(h0), levels);
  const double rounding = 3 * noise / std::ldexp(h0, -(levels - 1));
  return {fd.value.template cast<double>(), static_cast<double>(fd.error) + rounding};
}

/// The largest |AD - FD| over the columns, each against its bound: true if all within.
/// `step(j)` is column j's first step, about an eighth of the length on which f varies along it.
template <class SceneT, class Step>
bool matches_differences(const SceneT& scene, SceneWorkspace<SceneT>& ws, double t,
                         const SceneState& st, Step&& step) {
  const Eigen::Index n = scene.size();
  MatrixXd jac = MatrixXd::Zero(n, n);
  jacobian(scene, ws, t, st, jac);
  bool ok = true;
  for (int j = 0; j < n; ++j) {
    const auto [ref, bound] = fd_column(scene, ws, t, st, j, step(j));
    const double scale = std::max(1.0, ref.cwiseAbs().maxCoeff());
    const double err = (jac.col(j) - ref).cwiseAbs().maxCoeff();
    // Within the differences' bound, plus the rounding of the AD evaluation: a solve of the
    // constraints' size, so a thousand eps of the column's scale.
    if (!(err <= bound + 1e3 * std::numeric_limits<double>::epsilon() * scale)) {
      UNSCOPED_INFO("column " << j << " of " << n << ": |AD - FD| = " << err << ", bound " << bound
                              << ", scale " << scale);
      ok = false;
    }
  }
  return ok;
}

/// Which columns of a scene's y are positions r_oc (metres): the others are attitudes and rates.
template <class SceneT> std::vector<char> position_columns(const SceneT& scene) {
  std::vector<char> p(static_cast<std::size_t>(scene.size()), 0);
  scene.for_each_entry([&](const auto& e) {
    for (int i = 0; i < 3; ++i) {
      p[static_cast<std::size_t>(e.offset + i)] = 1;
    }
  });
  return p;
}

/// Andrews' mechanism in a constraint chart and in a vector chart (its shadow switches).
using JacobianParameterizations = std::tuple<EulerParameters, RotationVector>;
using TUMBLE_TEST_SLICED_NAME(JacobianSlice) = tumble::test::ThisSlice<JacobianParameterizations>;

}  // namespace

#if !defined(TUMBLE_TEST_SLICE) || TUMBLE_TEST_SLICE < 2  // slice 2 has no parameterization
TEMPLATE_LIST_TEST_CASE("mechanism jacobian: Andrews' mechanism in its motion, against differences",
                        "[joint][jacobian]", TUMBLE_TEST_SLICED_NAME(JacobianSlice)) {
  const andrews::Andrews<TestType> m;
  static_assert(andrews::Andrews<TestType>::SceneT::differentiable);
  // A state of the motion, 5 ms after the start: the crank at 1000 rad/s.
  OdeintIntegrator<typename andrews::Andrews<TestType>::SceneT> run(m.scene, 0.0,
                                                                    {.rtol = 1e-10, .atol = 1e-10});
  run.advance(0.005);
  const SceneState st = run.state();
  SceneWorkspace<typename andrews::Andrews<TestType>::SceneT> ws(m.scene);
  CHECK(detail::freeze_redundant_rows(m.scene, ws, st.y, st.base) == 9);
  const std::vector<char> position = position_columns(m.scene);
  // Lengths of a few centimetres; attitudes and rates vary on a scale of 1 (rad, rad/s) or more.
  CHECK(matches_differences(m.scene, ws, 0.005, st, [&](int j) {
    return position[static_cast<std::size_t>(j)] ? 1e-3 : std::max(1.0, std::abs(st.y(j))) / 32;
  }));
}

#endif  // slices 0 and 1

#if TUMBLE_TEST_IN_SLICE(2)
TEST_CASE("mechanism jacobian: a spatial double pendulum with a spring, off its constraints",
          "[joint][jacobian]") {
  using Link = RigidBody<EulerZYX>;
  Mechanism<Bodies<Link>, Joints<Spherical, Universal>, Loads<UniformGravity, SpringDamperBetween>>
      scene;
  static_assert(decltype(scene)::differentiable);
  const Link rod(MassProperties<>::about_centroid(2.0, Vector3d(0.02, 0.17, 0.18).asDiagonal()));
  const auto a =
      scene.add(rod, {.position = Vector3d(0.5, 0, 0),
                      .rotation = Matrix3d(Eigen::AngleAxisd(0.3, Vector3d(1, 2, 3).normalized())),
                      .velocity = Vector3d(0.1, 0.4, -0.2),
                      .omega = Vector3d(0.7, -0.3, 0.9)});
  const auto b = scene.add(rod, {.position = Vector3d(1.4, 0.2, 0.1),
                                 .velocity = Vector3d(-0.3, 0.2, 0.5),
                                 .omega = Vector3d(-0.4, 1.1, 0.2)});
  const Vector3d end(0.5, 0, 0);
  scene.add_joint(a, ground, Spherical(-end, Vector3d::Zero()));
  scene.add_joint(a, b, Universal(end, Vector3d::UnitY(), -end, Vector3d::UnitZ()));
  scene.add_load(a, UniformGravity({0, -9.81, 0}));
  scene.add_load(b, UniformGravity({0, -9.81, 0}));
  scene.add_load(a, b,
                 SpringDamperBetween({0, 0.1, 0}, {0.2, 0, 0}, {.stiffness = 50, .damping = 2}));
  SceneWorkspace<decltype(scene)> ws(scene);
  const SceneState st = scene.initial_state();  // placed roughly: off the joints by centimetres
  CHECK(matches_differences(scene, ws, 0.3, st, [](int) { return 1.0 / 32; }));
}
#endif  // TUMBLE_TEST_IN_SLICE(2)
