// Bricard's mechanism (problem A04 of the IFToMM multibody benchmark library): an over-constrained
// loop, five rods and six hinges, that moves though Gruebler's count says it cannot.
//
// Problem: the orthogonal Bricard linkage. Six unit links run along edges of the unit cube,
// P0 = (0,0,0) -> P1 = (1,0,0) -> P2 = (1,1,0) -> P3 = (1,1,1) -> P4 = (0,1,1) -> P5 = (0,0,1)
// -> P0, each hinged to the next at P_k about the axis perpendicular to both (consecutive axes
// perpendicular, no offsets). The link P5 P0 is the ground; the five others are rods of 1 m and
// 1 kg with a 0.1 m square section (the benchmark's), released at rest under gravity along -y.
// Five bodies have 30 coordinates and six hinges 30 constraints, so Gruebler's count gives no
// motion; the hinges' directions make one of the 30 rows dependent on the others (rank 29), and
// the linkage moves with one degree of freedom for the benchmark's 10 s.
// Checks, printed: the point P3 (the tip of the middle rod) over time, the energy balance (no
// dissipation: constant), the largest constraint residual, and the same P3 from the same linkage
// with the hinge at P5 made a universal joint whose second arm turns with the last rod (29
// independent rows, no redundancy, and the same motion: the hinges' motion is a curve inside the
// one-dimensional motion of the twin). The program exits with status 1 if the twin or the energy
// is missed.
// Units: SI.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include <Eigen/Geometry>

#include "tumble/integrate.hpp"

namespace bricard {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using Rod = tumble::RigidBody<tumble::EulerParameters>;

/// The rotation that turns body x onto the unit vector d, as Eigen's Quaternion::FromTwoVectors
/// gives it (its arithmetic, so the same doubles) but without the SVD it compiles for opposite
/// directions: d = -x is half a turn about z, the rotation that SVD gives.
inline Matrix3d x_onto(const Vector3d& d) {
  if (d.x() == -1.0) {
    return Vector3d(-1, -1, 1).asDiagonal();
  }
  const double s = std::sqrt((1 + d.x()) * 2);
  Eigen::Quaterniond q;
  q.vec() = Vector3d::UnitX().cross(d) * (1 / s);
  q.w() = s * 0.5;
  return q.toRotationMatrix();
}

/// The linkage of the file comment; with Extra = Universal, the twin (the joint at P5 a universal
/// joint: 4 rows, the arm fixed in the rod along inertial y at the start).
template <class... Extra> struct Bricard {
  using SceneT = tumble::Mechanism<tumble::Bodies<Rod>, tumble::Joints<tumble::Revolute, Extra...>,
                                   tumble::Loads<tumble::UniformGravity>>;
  static constexpr std::array<double, 3> kGravity{0.0, -9.81, 0.0};
  SceneT scene;
  std::vector<tumble::BodyId<Rod>> rods;

  Bricard() {
    using tumble::ground;
    const std::array<Vector3d, 6> p{Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(1, 1, 0),
                                    Vector3d(1, 1, 1), Vector3d(0, 1, 1), Vector3d(0, 0, 1)};
    // The hinge at P_k: perpendicular to the two links that meet there.
    const std::array<Vector3d, 6> axis{Vector3d::UnitY(), Vector3d::UnitZ(), Vector3d::UnitX(),
                                       Vector3d::UnitY(), Vector3d::UnitZ(), Vector3d::UnitX()};
    const double m = 1.0, l = 1.0, s = 0.1;
    const Rod rod(tumble::MassProperties<>::about_centroid(
        m,
        Vector3d(m * s * s / 6, m * (l * l + s * s) / 12, m * (l * l + s * s) / 12).asDiagonal()));
    std::vector<Matrix3d> r;  // rod i from P_i to P_i+1, its body x along it
    for (int i = 0; i < 5; ++i) {
      r.push_back(x_onto(p[i + 1] - p[i]));
      rods.push_back(scene.add(rod, {.position = 0.5 * (p[i] + p[i + 1]), .rotation = r.back()}));
      scene.add_load(rods.back(),
                     tumble::UniformGravity(Vector3d(kGravity[0], kGravity[1], kGravity[2])));
    }
    const Vector3d end(0.5 * l, 0, 0);  // a rod's ends, body components
    scene.add_joint(rods[0], ground,
                    tumble::Revolute(-end, r[0].transpose() * axis[0], p[0], axis[0]));
    for (int i = 1; i < 5; ++i) {
      scene.add_joint(
          rods[i - 1], rods[i],
          tumble::Revolute(end, r[i - 1].transpose() * axis[i], -end, r[i].transpose() * axis[i]));
    }
    if constexpr (sizeof...(Extra) > 0) {
      scene.add_joint(rods[4], ground,
                      tumble::Universal(end, r[4].transpose() * Vector3d::UnitY(), p[5], axis[5]));
    } else {
      scene.add_joint(rods[4], ground,
                      tumble::Revolute(end, r[4].transpose() * axis[5], p[5], axis[5]));
    }
  }

  /// P3, the tip of the middle rod, in the state s.
  [[nodiscard]] Vector3d p3(const tumble::SceneState& s) const {
    return tumble::position(scene, rods[2], s) +
           tumble::rotation(scene, rods[2], s) * Vector3d(0.5, 0, 0);
  }
};

}  // namespace bricard

int main() {
  using bricard::Bricard;
  Bricard<> six;
  Bricard<tumble::Universal> twin;
  std::vector<double> times;
  for (int k = 0; k <= 200; ++k) {
    times.push_back(0.05 * k);  // the benchmark's 10 s
  }
  const double tol = 1e-10;
  std::vector<Eigen::Vector3d> twin_p3;
  tumble::integrate(twin.scene, 0.0, times,
                    [&](double, const tumble::SceneState& s) { twin_p3.push_back(twin.p3(s)); },
                    {.rtol = tol, .atol = tol});

  const tumble::SceneState s0 = six.scene.initial_state();
  const tumble::ConstraintResidual r0 = tumble::constraint_residual(six.scene, s0);
  std::printf("%d constraint rows of rank %d; |C| = %.1e m at the start\n",
              six.scene.constraint_count(), r0.rank, r0.position);
  const double e0 = tumble::energy(six.scene, s0);
  double worst_e = 0, worst_c = 0, worst_twin = 0;
  std::size_t k = 0;
  std::printf("%6s %30s %12s %12s\n", "t (s)", "P3 (m)", "E - E0 (J)", "|P3 - twin|");
  const tumble::AutoStatistics st = tumble::integrate(
      six.scene, 0.0, times,
      [&](double t, const tumble::SceneState& s) {
        const Eigen::Vector3d p = six.p3(s);
        const double de = tumble::energy(six.scene, s) - e0;
        const double dt = k < twin_p3.size() ? (p - twin_p3[k]).norm() : INFINITY;
        ++k;
        worst_e = std::max(worst_e, std::abs(de));
        worst_c = std::max(worst_c, tumble::constraint_residual(six.scene, s).position);
        worst_twin = std::max(worst_twin, dt);
        if (k % 10 == 1) {  // every 0.5 s
          std::printf("%6.2f %9.6f %9.6f %9.6f %12.3e %12.3e\n", t, p(0), p(1), p(2), de, dt);
        }
      },
      {.rtol = tol, .atol = tol});
  std::printf("%s, %ld steps; |E - E0| <= %.2e J of %.4f J, |C| <= %.2e m, |P3 - twin| <= %.2e m\n",
              tumble::name(st.choices.front().method), st.steps, worst_e, e0, worst_c, worst_twin);
  return k == times.size() && worst_twin <= 1e-7 && worst_e <= 1e3 * tol * std::abs(e0) ? 0 : 1;
}
