// tumble_micro: the cost of the scene's Jacobian df/dy (Scene::jacobian, automatic
// differentiation in Jet<N>, scene/scene.hpp) against what BDF's Newton matrix costs without it:
// CVODE's dense difference quotients, one right-hand side per column (cvLsDenseDQJac in the CVODE
// guide, "Difference-quotient Jacobian approximations"), rewritten here in the same loop form.
// The scene is one body with gravity, a point force and a spring-damper to the ground (so that
// every block of J is nonzero). In ns per call:
//   scene_rhs/<P>/<ref>          Scene::rhs: one f(t, y)
//   scene_jacobian/<P>/<ref>     Scene::jacobian into a zeroed dense matrix (exact)
//   scene_jacobian_dq/<P>/<ref>  forward differences: 2 nq right-hand sides and the columns

#include <cmath>
#include <limits>
#include <string>

#include "micro_common.hpp"
#include "tumble/scene/scene.hpp"

namespace tumble::bench {
namespace {

template <class Body>
using LoadedScene = Scene<Bodies<Body>, Loads<UniformGravity, PointForce, SpringDamper>>;

/// The scene and the states of States<Body> as scene vectors y = [q; qdot].
template <class Body> struct SceneCase {
  LoadedScene<Body> scene;
  std::array<Eigen::VectorXd, kStates> y;
  SceneCase() {
    const auto id = scene.add(Body(mass_properties<Body::reference>()));
    const LoadSet l;
    scene.add_load(id, l.gravity);
    scene.add_load(id, l.force);
    scene.add_load(id, SpringDamper(load_point(), Vector3<double>(0.5, -0.3, 2.0),
                                    {.stiffness = 1e3, .damping = 5.0, .rest_length = 0.5}));
    scene.prepare();
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
      c.scene.rhs(0.0, c.y[i], f);
      return f(n - 1);
    });
  });
  add("scene_jacobian" + suffix, [](benchmark::State& st) {
    constexpr int n = 2 * Body::nq;
    SceneCase<Body> c;
    Eigen::MatrixXd jac(n, n);
    run_cycling(st, [&](std::size_t i) {
      jac.setZero();  // CVODE hands the Jacobian over zeroed
      c.scene.jacobian(0.0, c.y[i], jac);
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
      c.scene.rhs(0.0, c.y[i], f0);  // CVODE has f(t, y) already; timed for the first column
      yj = c.y[i];
      for (int j = 0; j < n; ++j) {
        const double saved = yj(j);
        const double inc = srur * std::max(std::abs(saved), 1.0);
        yj(j) = saved + inc;
        c.scene.rhs(0.0, yj, f1);
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
