// tumble_micro: the cost of the scene's Jacobian df/dy (tumble::jacobian, automatic
// differentiation in Jet<N>, scene/jacobian.hpp) against what BDF's Newton matrix costs without it:
// CVODE's dense difference quotients, one right-hand side per column (cvLsDenseDQJac in the CVODE
// guide, "Difference-quotient Jacobian approximations"), rewritten here in the same loop form.
// The scene is one body with gravity, a point force and a spring-damper to the ground (so that
// every block of J is nonzero). In ns per call:
//   scene_rhs/<P>/<ref>          tumble::rhs: one f(t, y)
//   scene_jacobian/<P>/<ref>     tumble::jacobian into a zeroed dense matrix (exact)
//   scene_jacobian_dq/<P>/<ref>  forward differences: 2 nq right-hand sides and the columns

#include "tumble/scene/jacobian.hpp"

#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <string>

#include "micro/common.hpp"
#include "tumble/scene/rhs.hpp"
#include "tumble/scene/scene.hpp"
#include "tumble/scene/workspace.hpp"

namespace tumble::bench {
namespace {

template <class Body>
using LoadedScene = Scene<Bodies<Body>, Loads<UniformGravity, PointForce, SpringDamper>>;

/// The scene, its workspace and the states of States<Body> as scene vectors y = [q; qdot] (in
/// charts without a base).
template <class Body> struct SceneCase {
  LoadedScene<Body> scene;
  std::array<Eigen::VectorXd, kStates> y;
  ChartBases base{Matrix3<double>::Identity()};
  std::optional<SceneWorkspace<LoadedScene<Body>>> ws;
  SceneCase() {
    const auto id = scene.add(Body(mass_properties<Body::reference>()));
    const LoadSet l;
    scene.add_load(id, l.gravity);
    scene.add_load(id, l.force);
    scene.add_load(id, SpringDamper(load_point(), Vector3<double>(0.5, -0.3, 2.0),
                                    {.stiffness = 1e3, .damping = 5.0, .rest_length = 0.5}));
    ws.emplace(scene);
    static const States<Body> s;
    for (std::size_t i = 0; i < kStates; ++i) {
      y[i].resize(2 * Body::nq);
      y[i] << s.q[i], s.qdot[i];
    }
  }
};

template <class P, ReferencePoint Ref> void register_scene() {
  using Body = RigidBody<P, Ref, double>;
  const std::string suffix = std::string("/") + std::string(P::name) + "/" + ref_name(Ref);
  add("scene_rhs" + suffix, [](benchmark::State& st) {
    constexpr int n = 2 * Body::nq;
    SceneCase<Body> c;
    Eigen::Matrix<double, n, 1> f;
    run_cycling(st, [&](std::size_t i) {
      rhs(c.scene, *c.ws, 0.0, c.y[i], std::span<const Matrix3<double>>(c.base), f);
      return f(n - 1);
    });
  });
  add("scene_jacobian" + suffix, [](benchmark::State& st) {
    constexpr int n = 2 * Body::nq;
    SceneCase<Body> c;
    Eigen::MatrixXd jac(n, n);
    run_cycling(st, [&](std::size_t i) {
      jac.setZero();  // CVODE hands the Jacobian over zeroed
      jacobian(c.scene, *c.ws, 0.0, c.y[i], std::span<const Matrix3<double>>(c.base), jac);
      return jac(n - 1, 0);
    });
  });
  add("scene_jacobian_dq" + suffix, [](benchmark::State& st) {
    constexpr int n = 2 * Body::nq;
    SceneCase<Body> c;
    Eigen::MatrixXd jac(n, n);
    Eigen::VectorXd f0(n), f1(n), yj(n);
    const double srur = std::sqrt(std::numeric_limits<double>::epsilon());
    run_cycling(st, [&](std::size_t i) {
      rhs(c.scene, *c.ws, 0.0, c.y[i], std::span<const Matrix3<double>>(c.base),
          f0);  // CVODE has f(t, y) already; timed for the first column
      yj = c.y[i];
      for (int j = 0; j < n; ++j) {
        const double saved = yj(j);
        const double inc = srur * std::max(std::abs(saved), 1.0);
        yj(j) = saved + inc;
        rhs(c.scene, *c.ws, 0.0, yj, std::span<const Matrix3<double>>(c.base), f1);
        jac.col(j) = (f1 - f0) / inc;
        yj(j) = saved;
      }
      return jac(n - 1, 0);
    });
  });
}

template <class... P> void register_all() {
  (register_scene<P, ReferencePoint::centroid>(), ...);
  (register_scene<P, ReferencePoint::offset>(), ...);
}

}  // namespace

void register_jacobian() {
  register_all<EulerParameters, RodriguesParameters, ModifiedRodriguesParameters, RotationVector,
               EulerZYX, EulerZXZ>();
}

}  // namespace tumble::bench
