// A closed loop: the planar four-bar linkage built of spatial revolute joints (over-constrained by
// Gruebler's count: 3 x 6 - 4 x 5 = -2, mobile in fact, rank 17 of 20 rows). Assembled from a
// rough placement against the closed form of its position (two circles' intersection) and of its
// velocities (the derivative of that closed form), then run through the front door with the
// energy conserved and the loop closed to rounding. Bad input: a loop that cannot close, a state
// off the constraints, a joint on one body.

#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "support/catch.hpp"
#include "tumble/integrate.hpp"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using namespace tumble;

using Link = RigidBody<EulerParameters>;
using FourBar = Mechanism<Bodies<Link>, Joints<Revolute>, Loads<UniformGravity>>;

/// The rotation taking body x to the direction of (dx, 0, dz) by a rotation about y.
Matrix3d along(double dx, double dz) {
  return Eigen::AngleAxisd(std::atan2(-dz, dx), Vector3d::UnitY()).toRotationMatrix();
}

/// A link of length l along body x, 4 cm square section, its centroid in the middle.
Link link(double m, double l) {
  const double s = 0.04;
  return Link(MassProperties<>::about_centroid(
      m, Vector3d(m * s * s / 6, m * (l * l + s * s) / 12, m * (l * l + s * s) / 12).asDiagonal()));
}

/// The four-bar O_A (origin) - B - C - O_D (d, 0, 0) in the x-z plane, crank a = |AB| at angle phi
/// from x (towards z), coupler b = |BC|, rocker c = |DC|, closed in the upper branch.
struct Geometry {
  double a = 0.3, b = 1.0, c = 0.8, d = 0.9;
  [[nodiscard]] Vector3d point_b(double phi) const {
    return {a * std::cos(phi), 0, a * std::sin(phi)};
  }
  /// C: the intersection of the circles (B, b) and (D, c) with the larger z.
  [[nodiscard]] Vector3d point_c(double phi) const {
    const Vector3d pb = point_b(phi), pd(d, 0, 0);
    const Vector3d e = pd - pb;
    const double l = e.norm();
    const double x = (b * b - c * c + l * l) / (2 * l);
    const double h = std::sqrt(b * b - x * x);
    const Vector3d u = e / l, n(-u(2), 0, u(0));  // n: u turned by +90 deg in the x-z plane
    const Vector3d p1 = pb + x * u + h * n, p2 = pb + x * u - h * n;
    return p1(2) > p2(2) ? p1 : p2;
  }
};

struct Loop {
  Geometry geo;
  FourBar scene;
  std::vector<BodyId<Link>> links;
  std::vector<JointId<Revolute>> joints;

  /// The links placed exactly at crank angle phi (error = 0), or roughly (error > 0: positions
  /// off by up to `error` m, angles by up to 3 error rad).
  Loop(double phi, double error) {
    const double m1 = 1.0, m2 = 2.0, m3 = 1.5;
    const Vector3d pa(0, 0, 0), pb = geo.point_b(phi), pd(geo.d, 0, 0);
    const Vector3d pc = geo.point_c(phi);
    const auto place = [&](const Vector3d& p, const Vector3d& q, double m, double l, double k) {
      const Vector3d dir = q - p;
      return scene.add(
          link(m, l),
          {.position = 0.5 * (p + q) + Vector3d(error * k, 0, -error * k),
           .rotation = along(dir(0), dir(2)) *
                       Eigen::AngleAxisd(3 * error * k, Vector3d::UnitY()).toRotationMatrix()});
    };
    links.push_back(place(pa, pb, m1, geo.a, 0.0));  // the crank, exact
    links.push_back(place(pb, pc, m2, geo.b, 1.0));
    links.push_back(place(pd, pc, m3, geo.c, -1.0));
    const Vector3d y = Vector3d::UnitY();
    const auto end = [](double l, double sign) { return Vector3d(sign * 0.5 * l, 0, 0); };
    joints.push_back(scene.add_joint(links[0], ground, Revolute(end(geo.a, -1), y, pa, y)));
    joints.push_back(
        scene.add_joint(links[0], links[1], Revolute(end(geo.a, 1), y, end(geo.b, -1), y)));
    joints.push_back(
        scene.add_joint(links[1], links[2], Revolute(end(geo.b, 1), y, end(geo.c, 1), y)));
    joints.push_back(scene.add_joint(links[2], ground, Revolute(end(geo.c, -1), y, pd, y)));
    scene.add_load(links[0], UniformGravity(Vector3d(0, 0, -9.81)));
    scene.add_load(links[1], UniformGravity(Vector3d(0, 0, -9.81)));
    scene.add_load(links[2], UniformGravity(Vector3d(0, 0, -9.81)));
  }
  /// The rocker's end C from the state: its point (+c/2 along its x).
  [[nodiscard]] Vector3d c_of(const SceneStateView& s) const {
    return position(scene, links[2], s) +
           rotation(scene, links[2], s) * Vector3d(0.5 * geo.c, 0, 0);
  }
};

}  // namespace

TEST_CASE("four-bar: assembled from a rough placement onto the closed form", "[joint]") {
  const double phi = std::numbers::pi / 3;
  Loop loop(phi, 0.03);
  SceneState s = loop.scene.initial_state();
  // The crank turns at 2 rad/s about y (body y = inertial y); the others start at rest (wrong).
  set_velocity(
      loop.scene, loop.links[0], s,
      Vector3d(-2.0 * 0.5 * loop.geo.a * std::sin(phi), 0, 2.0 * 0.5 * loop.geo.a * std::cos(phi)),
      Vector3d(0, -2.0, 0));
  const Eigen::Matrix<double, 13, 1> crank_before = s.y.head<13>();
  const AssemblyReport rep = assemble(loop.scene, s, {.keep = {loop.links[0].id}});
  INFO("before: |C| = " << rep.before.position << ", after " << rep.iterations
                        << " iterations: |C| = " << rep.after.position
                        << ", |J nu| = " << rep.after.velocity);
  CHECK(rep.before.position > 1e-3);
  CHECK(rep.after.position <= 1e-12);
  CHECK(rep.after.velocity <= 1e-12);
  CHECK(rep.after.rank == 17);  // 20 rows, 3 of them dependent: the planar loop in 3D
  CHECK(Eigen::Matrix<double, 13, 1>(s.y.head<13>()) == crank_before);  // kept: not moved at all
  const Vector3d c_exact = loop.geo.point_c(phi);
  CHECK((loop.c_of(s) - c_exact).norm() <= 1e-11);
  // The velocity of C from the closed form: dC/dphi phidot by central differences (phidot = 2,
  // the crank's rate about -y is +2 about the x-z angle), against the rocker's point velocity.
  const double h = 1e-5;
  const Vector3d vc_exact = 2.0 * (loop.geo.point_c(phi + h) - loop.geo.point_c(phi - h)) / (2 * h);
  const Vector3d wr = rotation(loop.scene, loop.links[2], s) * omega(loop.scene, loop.links[2], s);
  const Vector3d vc = velocity(loop.scene, loop.links[2], s) +
                      wr.cross(loop.c_of(s) - position(loop.scene, loop.links[2], s));
  INFO("v_C " << vc.transpose() << ", closed form " << vc_exact.transpose());
  CHECK((vc - vc_exact).norm() <= 1e-8);
}

TEST_CASE("four-bar: the front door runs the loop with energy and closure kept", "[joint]") {
  Loop loop(std::numbers::pi / 3, 0.0);
  SceneState s = loop.scene.initial_state();
  assemble(loop.scene, s);
  const double e0 = energy(loop.scene, s);
  double de = 0.0, drift = 0.0;
  std::vector<double> times;
  for (int k = 0; k <= 200; ++k) {
    times.push_back(0.05 * k);
  }
  const AutoStatistics st =
      integrate(loop.scene, 0.0, s, times,
                [&](double, const SceneState& x) {
                  de = std::max(de, std::abs(energy(loop.scene, x) - e0));
                  drift = std::max(drift, constraint_residual(loop.scene, x).position);
                },
                {.rtol = 1e-11, .atol = 1e-11});
  INFO("energy change " << de << " J of " << e0 << ", drift " << drift << " m, " << st.steps
                        << " steps, method " << name(st.choices.front().method));
  CHECK(st.choices.front().method != AutoMethod::bdf);  // not stiff: the explicit path
  CHECK(drift <= 1e-12);
  CHECK(de <= 1e-8 * std::abs(e0));
}

TEST_CASE("mechanism: bad input is refused with the joint named", "[joint]") {
  SECTION("a loop that cannot close") {
    // Links of 0.3, 0.2 and 0.2 m between pivots 0.9 m apart: a + b + c < d, no closure.
    FourBar scene;
    const Vector3d y = Vector3d::UnitY();
    const auto l0 = scene.add(link(1, 0.3), {.position = Vector3d(0.15, 0, 0)});
    const auto l1 = scene.add(link(1, 0.2), {.position = Vector3d(0.4, 0, 0)});
    const auto l2 = scene.add(link(1, 0.2), {.position = Vector3d(0.7, 0, 0)});
    scene.add_joint(l0, ground, Revolute(Vector3d(-0.15, 0, 0), y, Vector3d::Zero(), y));
    scene.add_joint(l0, l1, Revolute(Vector3d(0.15, 0, 0), y, Vector3d(-0.1, 0, 0), y));
    scene.add_joint(l1, l2, Revolute(Vector3d(0.1, 0, 0), y, Vector3d(0.1, 0, 0), y));
    scene.add_joint(l2, ground, Revolute(Vector3d(-0.1, 0, 0), y, Vector3d(0.9, 0, 0), y));
    SceneState s = scene.initial_state();
    const Eigen::VectorXd y0 = s.y;
    CHECK_THROWS_WITH(assemble(scene, s),
                      TUMBLE_CONTAINS("cannot be met") && TUMBLE_CONTAINS("(Revolute, body"));
    CHECK(s.y == y0);  // left as it was
    CHECK_THROWS_WITH(
        OdeintIntegrator<FourBar>(scene, 0.0),
        TUMBLE_CONTAINS("off the joints' constraints") && TUMBLE_CONTAINS("tumble::assemble"));
    CHECK_THROWS_WITH(SceneIntegrator<FourBar>(scene, 0.0),
                      TUMBLE_CONTAINS("off the joints' constraints"));
  }
  SECTION("a joint on one body, a foreign handle, Adams") {
    Loop loop(1.0, 0.0);
    const Vector3d y = Vector3d::UnitY();
    CHECK_THROWS_WITH(loop.scene.add_joint(loop.links[1], loop.links[1],
                                           Revolute(Vector3d::Zero(), y, Vector3d::Zero(), y)),
                      TUMBLE_CONTAINS("two different bodies"));
    CHECK_THROWS_WITH(loop.scene.add_joint(BodyId<Link>{7, 7}, ground,
                                           Revolute(Vector3d::Zero(), y, Vector3d::Zero(), y)),
                      TUMBLE_CONTAINS("does not refer to a body of this scene"));
    CHECK_THROWS_WITH(
        std::as_const(loop.scene).joint(JointId<Revolute>{7, 7}),
        TUMBLE_CONTAINS("the joint handle 7 does not refer to a joint of this scene"));
    SceneIntegratorOptions opt;
    opt.method = CvodeMethod::adams;
    CHECK_THROWS_WITH(SceneIntegrator<FourBar>(loop.scene, 0.0, opt),
                      TUMBLE_CONTAINS("needs method = CvodeMethod::bdf"));
  }
}
