// Tests of tumble::jacobian (include/tumble/scene/jacobian.hpp): the Jacobian df/dy of the scene's
// right-hand side, formed block by block with automatic differentiation (Jet<N>, core/jet.hpp),
// for every parameterization. The reference is
// independent of it: central differences of tumble::rhs itself,
// extrapolated by Richardson (tests/support/finite_difference.hpp), one column per coordinate,
// with their own error estimate. Checked for every parameterization in mixed scenes that have
// every load type (one-body loads, spring-dampers between bodies, a user force and a user coupling
// written for any scalar), with and without the Baumgarte term of Euler parameters, off the
// constraint manifold and in charts with a base (mixed_scene.hpp). Compiled in slices of the
// parameterization list (tests/CMakeLists.txt). The band storage, differentiability, errors,
// allocations and the preconditioner: jacobian_storage.test.cpp; BDF integrations with the exact
// Jacobian and the preconditioner: tests/integrate/exact_jacobian.test.cpp.

#include "tumble/scene/jacobian.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "scene/mixed_scene.hpp"
#include "support/catch.hpp"
#include "support/finite_difference.hpp"
#include "support/parameterizations.hpp"
#include "support/random.hpp"
#include "tumble/body/rigid_body.hpp"
#include "tumble/scene/rhs.hpp"
#include "tumble/scene/scene.hpp"

namespace {

using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;
using tumble::test::mixed::build;
using tumble::test::mixed::MixedScene;

using tumble::test::mixed::fd_column;

}  // namespace

TEMPLATE_LIST_TEST_CASE("jacobian equals extrapolated central differences of rhs",
                        "[scene][jacobian]", TUMBLE_TEST_PARAMETERIZATIONS) {
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
