// Chains: the banded solve that keeps a chain's cost linear in its length, against statics (a
// chain hanging at rest carries the weight of the links below each joint) and against the dense
// pivoted solve of the same system (a second method) on a moving spatial chain.

#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Geometry>

#include "support/catch.hpp"
#include "support/random.hpp"
#include "tumble/tumble.hpp"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using Eigen::VectorXd;
using namespace tumble;

using Link = RigidBody<EulerParameters>;

Link link(double m, double l) {
  const double s = 0.03;
  return Link(MassProperties<>::about_centroid(
      m, Vector3d(m * (l * l + s * s) / 12, m * (l * l + s * s) / 12, m * s * s / 6).asDiagonal()));
}

}  // namespace

TEST_CASE("chain: a hanging chain at rest carries the weight below each joint", "[joint]") {
  constexpr int n = 200;
  const double l = 0.1, g = 9.81;
  using SceneT = Mechanism<Bodies<Link>, Joints<Spherical>, Loads<UniformGravity>>;
  SceneT scene;
  std::vector<BodyId<Link>> links;
  std::vector<JointId<Spherical>> joints;
  std::vector<double> mass;
  const Vector3d top(0, 0, 0.5 * l);
  for (int k = 0; k < n; ++k) {
    mass.push_back(1.0 + 0.01 * k);
    links.push_back(scene.add(link(mass.back(), l), {.position = Vector3d(0, 0, -(k + 0.5) * l)}));
    scene.add_load(links.back(), UniformGravity(Vector3d(0, 0, -g)));
    joints.push_back(k == 0 ? scene.add_joint(links[0], ground, Spherical(top, Vector3d::Zero()))
                            : scene.add_joint(links[k], links[k - 1], Spherical(top, -top)));
  }
  SceneWorkspace<SceneT> ws(scene);
  REQUIRE(ws.joints().bandwidth >= 0);  // the banded solve
  CHECK(ws.joints().bandwidth < 6);
  VectorXd f(scene.size());
  rhs(scene, ws, 0.0, scene.initial_state(), f);
  INFO("largest rate at rest: " << f.cwiseAbs().maxCoeff());
  // Nothing moves, to rounding: the top joint carries n weights, and its rounding reaches the
  // n links below: about n^2 eps g.
  CHECK(f.cwiseAbs().maxCoeff() <= n * n * std::numeric_limits<double>::epsilon() * g);
  double below = 0.0;
  for (int k = n - 1; k >= 0; --k) {
    below += mass[static_cast<std::size_t>(k)] * g;
    const JointReaction r = joint_reaction(scene, scene.initial_state(), 0.0, joints[k]);
    INFO("joint " << k << ": " << r.on_a.force.transpose() << " against " << below);
    CHECK((r.on_a.force - Vector3d(0, 0, below)).norm() <= 1e-12 * below);
  }
}

TEST_CASE("chain: the banded and the dense pivoted solve agree on a moving spatial chain",
          "[joint]") {
  constexpr int n = 40;
  const double l = 0.2;
  using SceneT = Mechanism<Bodies<Link>, Joints<Revolute, Universal>, Loads<UniformGravity>>;
  SceneT scene;
  tumble::test::Random rng(7);
  std::vector<BodyId<Link>> links;
  const Vector3d top(0, 0, 0.5 * l);
  for (int k = 0; k < n; ++k) {
    // A straight chain down z, every link spinning about its own axis and swinging: the joints'
    // axes are random, so the motion is spatial; the state is assembled below.
    links.push_back(
        scene.add(link(1.0 + 0.1 * (k % 3), l), {.position = Vector3d(0, 0, -(k + 0.5) * l),
                                                 .velocity = rng.vector(0.3),
                                                 .omega = rng.vector(1.0)}));
    scene.add_load(links.back(), UniformGravity(Vector3d(0, 0, -9.81)));
    const Vector3d axis = rng.vector().normalized();
    if (k == 0) {
      scene.add_joint(links[0], ground, Revolute(top, axis, Vector3d::Zero(), axis));
    } else if (k % 2 == 0) {
      scene.add_joint(links[k], links[k - 1], Revolute(top, axis, -top, axis));
    } else {
      const Vector3d other = axis.cross(Vector3d::UnitZ()).normalized();
      scene.add_joint(links[k], links[k - 1], Universal(top, axis, -top, other));
    }
  }
  SceneState s = scene.initial_state();
  const AssemblyReport rep = assemble(scene, s);
  CHECK(rep.after.position <= 1e-12);
  SceneWorkspace<SceneT> banded(scene), dense(scene);
  REQUIRE(banded.joints().bandwidth >= 0);
  dense.joints().use_dense();
  VectorXd fb(scene.size()), fd(scene.size());
  rhs(scene, banded, 0.3, s, fb);
  rhs(scene, dense, 0.3, s, fd);
  INFO("largest rate " << fd.cwiseAbs().maxCoeff() << ", difference "
                       << (fb - fd).cwiseAbs().maxCoeff());
  CHECK((fb - fd).cwiseAbs().maxCoeff() <= 1e-10 * fd.cwiseAbs().maxCoeff());
  CHECK(banded.joints().rank == scene.constraint_count());
  CHECK((banded.joints().lambda - dense.joints().lambda).cwiseAbs().maxCoeff() <=
        1e-9 * dense.joints().lambda.cwiseAbs().maxCoeff());
}

TEST_CASE("chain: the solve's storage follows the joints' topology", "[joint]") {
  // Three hinged links (15 rows, rows of the joints that share a link within 9 of each other):
  // an open chain takes the banded solve, the same links with a fourth joint that closes a loop
  // through the ground take the dense one (docs/mechanisms.md: which rows of a loop come out
  // redundant is the dense factorization's choice). Both give the dense solve's rates on the chain.
  const double l = 0.3;
  using SceneT = Mechanism<Bodies<Link>, Joints<Revolute, Spherical>, Loads<UniformGravity>>;
  const auto build = [&](bool closed) {
    SceneT scene;
    std::vector<BodyId<Link>> links;
    const Vector3d top(0, 0, 0.5 * l), axis = Vector3d(1, 0.2, 0).normalized();
    for (int k = 0; k < 3; ++k) {
      links.push_back(scene.add(link(1.0 + 0.2 * k, l), {.position = Vector3d(0, 0, -(k + 0.5) * l),
                                                         .omega = Vector3d(0.3 * k, 0, 0)}));
      scene.add_load(links.back(), UniformGravity(Vector3d(0, 0, -9.81)));
      if (k == 0) {
        scene.add_joint(links[0], ground, Revolute(top, axis, Vector3d::Zero(), axis));
      } else {
        scene.add_joint(links[k], links[k - 1], Revolute(top, axis, -top, axis));
      }
    }
    if (closed) {  // the last link's bottom held where it hangs
      scene.add_joint(links[2], ground, Spherical(-top, Vector3d(0, 0, -3 * l)));
    }
    return scene;
  };
  const SceneT open = build(false), closed = build(true);
  SceneWorkspace<SceneT> banded(open), dense(open), loop(closed);
  CHECK(open.constraint_count() == 15);
  CHECK(banded.joints().bandwidth == 9);
  CHECK(loop.joints().bandwidth == -1);
  dense.joints().use_dense();
  VectorXd fb(open.size()), fd(open.size());
  rhs(open, banded, 0.0, open.initial_state(), fb);
  rhs(open, dense, 0.0, open.initial_state(), fd);
  INFO("largest rate " << fd.cwiseAbs().maxCoeff() << ", difference "
                       << (fb - fd).cwiseAbs().maxCoeff());
  CHECK((fb - fd).cwiseAbs().maxCoeff() <= 1e-13 * fd.cwiseAbs().maxCoeff());
  CHECK((banded.joints().lambda - dense.joints().lambda).cwiseAbs().maxCoeff() <=
        1e-12 * dense.joints().lambda.cwiseAbs().maxCoeff());
}
