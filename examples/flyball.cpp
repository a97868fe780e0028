// The stiff flyball governor (problem A05 of the IFToMM multibody benchmark library): a turning
// shaft, a slider on it, two rods with heavy balls, and two very stiff, very damped
// spring-dampers in place of the coupler rods. The dampers make it stiff: BDF is the method.
//
// Problem (M. Gonzalez, D. Dopico, U. Lugris, J. Cuadrado, "A benchmarking system for MBS
// simulation software: problem standardization and performance measurement", Multibody System
// Dynamics 16(2), 2006, 179-190; the data as re-published by the Rehabilitation Engineering
// Group's OpenSim implementation, github.com/RehabEngGroup/MBSbenchmarksInOpenSim): z vertical,
// gravity 9.81 m/s^2 along -z, density 3000 kg/m^3.
//   - the shaft, a 1.0 x 0.01 x 0.01 m prism (0.3 kg), vertical from z = 0 to z = 1, hinged to
//     the ground at its bottom end about z;
//   - the slider, a 0.1 m cube (3 kg), on the shaft by a prismatic joint along its axis (it turns
//     with the shaft); s, the height of its centre, starts at 0.5 m;
//   - two rods, each a 1.0 x 0.01 x 0.01 m prism (0.3 kg) with a 5 kg point mass at its free end,
//     hinged at the other end to the shaft at (+-0.05, 0, 1) about y, pointing outward and down
//     at alpha = 30 degrees below the horizontal. Each rod and its ball are ONE rigid body here
//     (5.3 kg, its centroid 0.9717 m from the hinge, its inertia the prism's plus the point
//     mass's about that centroid);
//   - two spring-dampers, each from a rod's midpoint to the slider's point (+-0.05, 0, 0) (its
//     centre's height), K = 8e5 N/m, C = 4e4 N s/m, rest length 0.5 m (the initial length);
//   - the whole assembly turning rigidly about z at 2 pi rad/s at t = 0, the shaft free after.
// The balls are flung outward, the rods rise and the springs pull the slider up. The benchmark's
// output is s(t); the re-publication ran 10 s in one place and 350 s in another: 10 s here.
// Checks, printed: s(t), the rods' angle below the horizontal, the angular momentum about z (no
// external moment about z: conserved), the rods' mirror symmetry, the energy (the dampers only
// dissipate: it never rises), the largest constraint residual and the initial spring length. The
// program exits with status 1 if one of them is missed. A second model in minimal coordinates
// checks s(t) and the rods' angle: tests/joint/flyball.test.cpp.
// Units: SI.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include <Eigen/Geometry>

#include "tumble/integrate.hpp"

namespace flyball {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using Part = tumble::RigidBody<tumble::EulerParameters>;

constexpr double kG = 9.81;                        // m/s^2
constexpr double kDensity = 3000;                  // kg/m^3
constexpr double kBar = 1.0, kSide = 0.01;         // shaft and rods, m
constexpr double kCube = 0.1;                      // slider, m
constexpr double kBall = 5.0;                      // point mass, kg
constexpr double kOffset = 0.05;                   // the rods' hinges off the axis, m
constexpr double kK = 8e5, kC = 4e4, kRest = 0.5;  // N/m, N s/m, m
constexpr double kS0 = 0.5;                        // m
constexpr double kAlpha = std::numbers::pi / 6;    // rad
constexpr double kSpin = 2 * std::numbers::pi;     // rad/s

constexpr double kBarMass = kDensity * kBar * kSide * kSide;    // 0.3 kg
constexpr double kCubeMass = kDensity * kCube * kCube * kCube;  // 3 kg
constexpr double kRodMass = kBarMass + kBall;                   // 5.3 kg
/// The rod's centroid from its hinge, m.
constexpr double kRodCentroid = (kBarMass * 0.5 * kBar + kBall * kBar) / kRodMass;
/// The rod's moments of inertia about its centroid, along and across it (kg m^2).
constexpr double kRodAxial = kBarMass * 2 * kSide * kSide / 12;
constexpr double kRodTransverse =
    kBarMass * (kBar * kBar + kSide * kSide) / 12 +
    kBarMass * (0.5 * kBar - kRodCentroid) * (0.5 * kBar - kRodCentroid) +
    kBall * (kBar - kRodCentroid) * (kBar - kRodCentroid);

/// The governor of the file comment, with the dampers' constant `damping` (N s/m; 0: undamped).
struct Governor {
  using SceneT =
      tumble::Mechanism<tumble::Bodies<Part>, tumble::Joints<tumble::Revolute, tumble::Prismatic>,
                        tumble::Loads<tumble::UniformGravity, tumble::SpringDamperBetween>>;
  SceneT scene;
  tumble::BodyId<Part> shaft, slider;
  std::array<tumble::BodyId<Part>, 2> rods{};
  /// The rods' sides: rod k is hinged at x = side[k] * 0.05 of the shaft's top.
  static constexpr std::array<double, 2> side{1.0, -1.0};

  explicit Governor(double damping = kC) {
    using tumble::ground;
    const Vector3d z = Vector3d::UnitZ(), y = Vector3d::UnitY();
    const Vector3d spin(0, 0, kSpin);
    // Each body's frame at its centroid; at t = 0 every point turns about z at 2 pi rad/s.
    const auto add = [&](const Part& part, const Vector3d& at, const Matrix3d& r) {
      return scene.add(part, {.position = at,
                              .rotation = r,
                              .velocity = spin.cross(at),
                              .omega = r.transpose() * spin});
    };
    const double l2 = kBar * kBar, a2 = kSide * kSide;
    shaft = add(Part(tumble::MassProperties<>::about_centroid(
                    kBarMass, Vector3d(kBarMass * (l2 + a2) / 12, kBarMass * (l2 + a2) / 12,
                                       kBarMass * 2 * a2 / 12)
                                  .asDiagonal())),
                Vector3d(0, 0, 0.5 * kBar), Matrix3d::Identity());
    const double jc = kCubeMass * 2 * kCube * kCube / 12;
    slider = add(Part(tumble::MassProperties<>::about_centroid(kCubeMass,
                                                               Vector3d(jc, jc, jc).asDiagonal())),
                 Vector3d(0, 0, kS0), Matrix3d::Identity());
    // A rod's body x runs from its hinge to its ball, body y along the hinge's axis.
    const Part rod(tumble::MassProperties<>::about_centroid(
        kRodMass, Vector3d(kRodAxial, kRodTransverse, kRodTransverse).asDiagonal()));
    for (int k = 0; k < 2; ++k) {
      const double sk = side[static_cast<std::size_t>(k)];
      const Vector3d hinge(sk * kOffset, 0, kBar);
      const Vector3d along(sk * std::cos(kAlpha), 0, -std::sin(kAlpha));
      const Matrix3d r =
          Eigen::AngleAxisd(sk > 0 ? kAlpha : std::numbers::pi - kAlpha, y).toRotationMatrix();
      rods[static_cast<std::size_t>(k)] = add(rod, hinge + kRodCentroid * along, r);
    }

    scene.add_joint(shaft, ground,
                    tumble::Revolute(Vector3d(0, 0, -0.5 * kBar), z, Vector3d::Zero(), z));
    scene.add_joint(shaft, slider, tumble::Prismatic(tumble::JointFrame{}, tumble::JointFrame{}));
    const tumble::SpringDamperParameters spring{
        .stiffness = kK, .damping = damping, .rest_length = kRest};
    for (int k = 0; k < 2; ++k) {
      const double sk = side[static_cast<std::size_t>(k)];
      const auto rod_k = rods[static_cast<std::size_t>(k)];
      scene.add_joint(rod_k, shaft,
                      tumble::Revolute(Vector3d(-kRodCentroid, 0, 0), y,
                                       Vector3d(sk * kOffset, 0, 0.5 * kBar), y));
      scene.add_load(rod_k, slider,
                     tumble::SpringDamperBetween(Vector3d(0.5 * kBar - kRodCentroid, 0, 0),
                                                 Vector3d(sk * kOffset, 0, 0), spring));
    }
    for (const auto b : {shaft, slider, rods[0], rods[1]}) {
      scene.add_load(b, tumble::UniformGravity(Vector3d(0, 0, -kG)));
    }
  }

  /// s: the height of the slider's centre (m).
  [[nodiscard]] double s(const tumble::SceneStateView& x) const {
    return tumble::position(scene, slider, x)(2);
  }
  /// Rod k's angle below the horizontal (rad; alpha at t = 0).
  [[nodiscard]] double angle(const tumble::SceneStateView& x, int k) const {
    const Vector3d u =
        tumble::rotation(scene, rods[static_cast<std::size_t>(k)], x) * Vector3d::UnitX();
    return std::atan2(-u(2), std::hypot(u(0), u(1)));
  }
  /// Spring k's length (m).
  [[nodiscard]] double spring_length(const tumble::SceneStateView& x, int k) const {
    const auto rod_k = rods[static_cast<std::size_t>(k)];
    const Vector3d mid =
        tumble::position(scene, rod_k, x) +
        tumble::rotation(scene, rod_k, x) * Vector3d(0.5 * kBar - kRodCentroid, 0, 0);
    const Vector3d end = tumble::position(scene, slider, x) +
                         tumble::rotation(scene, slider, x) *
                             Vector3d(side[static_cast<std::size_t>(k)] * kOffset, 0, 0);
    return (mid - end).norm();
  }
  /// The mirror error: rod 2 against rod 1 turned by pi about z (centroid, its velocity and the
  /// angular velocity, inertial), the largest entry (m, m/s, rad/s); and the slider off the axis
  /// or tilted (m, and 1 - cos of the tilt).
  [[nodiscard]] double asymmetry(const tumble::SceneStateView& x) const {
    const Matrix3d half_turn = Vector3d(-1, -1, 1).asDiagonal();
    const auto r1 = rods[0], r2 = rods[1];
    const Vector3d dp = tumble::position(scene, r2, x) - half_turn * tumble::position(scene, r1, x);
    const Vector3d dv = tumble::velocity(scene, r2, x) - half_turn * tumble::velocity(scene, r1, x);
    const Vector3d dw = tumble::rotation(scene, r2, x) * tumble::omega(scene, r2, x) -
                        half_turn * tumble::rotation(scene, r1, x) * tumble::omega(scene, r1, x);
    const Vector3d c = tumble::position(scene, slider, x);
    const double tilt = 1 - tumble::rotation(scene, slider, x)(2, 2);
    return std::max({dp.cwiseAbs().maxCoeff(), dv.cwiseAbs().maxCoeff(), dw.cwiseAbs().maxCoeff(),
                     std::hypot(c(0), c(1)), tilt});
  }
  /// The angular momentum about z (kg m^2/s).
  [[nodiscard]] double spin_momentum(const tumble::SceneStateView& x) const {
    return tumble::angular_momentum(scene, x)(2);
  }
};

/// The outputs: every 0.05 s over the benchmark's 10 s.
inline std::vector<double> output_times(double end = 10.0, double every = 0.05) {
  std::vector<double> t;
  const int n = static_cast<int>(std::lround(end / every));
  for (int k = 0; k <= n; ++k) {
    t.push_back(every * k);
  }
  return t;
}

}  // namespace flyball

int main() {
  using namespace flyball;
  const Governor g;
  const tumble::SceneState s0 = g.scene.initial_state();
  const tumble::ConstraintResidual r0 = tumble::constraint_residual(g.scene, s0);
  const double l0 = g.spring_length(s0, 0) - kRest;
  std::printf("%d constraint rows of rank %d; |C| = %.1e m at the start; spring length - rest "
              "length = %.1e m\n",
              g.scene.constraint_count(), r0.rank, r0.position, l0);
  const double h0 = g.spin_momentum(s0), e0 = tumble::energy(g.scene, s0);
  const double tol = 1e-10;
  const std::vector<double> times = output_times();
  double worst_h = 0, worst_sym = 0, worst_c = 0, rise = 0, e_prev = e0;
  double s_end = 0, angle_end = 0, s_low = kS0, s_high = kS0;
  std::size_t k = 0;
  std::printf("%6s %12s %14s %12s %12s\n", "t (s)", "s (m)", "angle (deg)", "E - E0 (J)",
              "H_z - H0");
  const tumble::AutoStatistics st = tumble::integrate(
      g.scene, 0.0, times,
      [&](double t, const tumble::SceneState& x) {
        const double e = tumble::energy(g.scene, x);
        worst_h = std::max(worst_h, std::abs(g.spin_momentum(x) - h0));
        worst_sym = std::max(worst_sym, g.asymmetry(x));
        worst_c = std::max(worst_c, tumble::constraint_residual(g.scene, x).position);
        rise = std::max(rise, e - e_prev);
        e_prev = e;
        s_end = g.s(x);
        angle_end = g.angle(x, 0);
        s_low = std::min(s_low, s_end);
        s_high = std::max(s_high, s_end);
        if (k % 20 == 0 || (k < 40 && k % 5 == 0)) {  // every 0.25 s to 2 s, then every 1 s
          std::printf("%6.2f %12.9f %14.9f %12.5e %12.3e\n", t, s_end,
                      angle_end * 180 / std::numbers::pi, e - e0, g.spin_momentum(x) - h0);
        }
        ++k;
      },
      {.rtol = tol, .atol = tol});
  std::printf("%s, %ld steps, %ld rejected, %ld right-hand sides\n",
              tumble::name(st.choices.front().method), st.steps, st.rejected_steps, st.rhs_evals);
  std::printf("s(10 s) = %.9f m, angle %.9f deg; s between %.6f and %.6f m; dissipated %.3e J\n",
              s_end, angle_end * 180 / std::numbers::pi, s_low, s_high, e0 - e_prev);
  std::printf("|H_z - H0| <= %.1e of %.6f kg m^2/s; asymmetry <= %.1e; E rose by <= %.1e J "
              "between outputs (E0 = %.4f J); |C| <= %.1e m\n",
              worst_h, h0, worst_sym, rise, e0, worst_c);
  const bool ok = k == times.size() && std::abs(l0) <= 1e-15 && worst_h <= 1e-6 * std::abs(h0) &&
                  worst_sym <= 1e-9 && rise <= 1e-5 && worst_c <= 1e-12 && s_high > kS0 + 0.2;
  return ok ? 0 : 1;
}
