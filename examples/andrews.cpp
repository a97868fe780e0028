// Andrews' squeezing mechanism (problem A03 of the IFToMM multibody benchmark library; the
// "seven body mechanism" of Giles 1978 and Manning 1981, in Schiehlen's collection and in
// Hairer & Wanner, Solving ODEs II, Sec. VII.7): seven planar links, ten hinges, a spring and a
// motor, on a very short time scale (the crank turns 2.5 times in 0.03 s).
//
// Problem (the data of the Test Set for IVP Solvers, problem "andrews", University of Bari):
// in the x-y plane, no gravity, at rest at t = 0 in the position given by the seven angles
// beta, Theta, gamma, Phi, delta, Omega, epsilon. The links, each a body here with its own
// coordinates (absolute, as the reference chapter writes a body), are
//   1  the crank OF, hinged to the ground at O, driven by the constant torque mom;
//   2  the rod FE, hinged to the crank at F;
//   3  the triangle BDE, hinged to the ground at B, pulled at D by the spring from C;
//   4  the rod EG and 5 the link AG, hinged at G, 5 to the ground at A;
//   6  the rod EH and 7 the link AH, hinged at H, 7 to the ground at A;
// and links 2, 3, 4 and 6 meet at E (three hinges). With every hinge about z, 7 bodies have 42
// coordinates and 10 hinges 50 constraint rows of rank 41: one degree of freedom, and nine rows
// redundant (the plane's, as for a planar linkage built of spatial hinges).
// Checks, printed: the seven angles and their rates at t = 0.03 s against the Test Set's
// reference solution (RADAU5 at tight tolerance), the energy balance T + V_spring - mom (beta -
// beta0) (no dissipation: constant), and the largest constraint residual. The program exits with
// status 1 if the reference or the energy is missed.
// Units: SI.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include <Eigen/Geometry>

#include "tumble/integrate.hpp"

namespace andrews {

using Eigen::Vector3d;

// The Test Set's data (kg, m, kg m^2, N/m, N m).
constexpr std::array<double, 7> kMass{0.04325, 0.00365, 0.02373, 0.00706,
                                      0.07050, 0.00706, 0.05498};
constexpr std::array<double, 7> kInertia{2.194e-6, 4.410e-7, 5.255e-6, 5.667e-7,
                                         1.169e-5, 5.667e-7, 1.912e-5};
constexpr double xa = -0.06934, ya = -0.00227, xb = -0.03635, yb = 0.03273, xc = 0.014, yc = 0.072;
constexpr double c0 = 4530, l0 = 0.07785, mom = 0.033;
constexpr double d = 28e-3, da = 115e-4, e = 2e-2, ea = 1421e-5, rr = 7e-3, ra = 92e-5;
constexpr double ss = 35e-3, sa = 1874e-5, sb = 1043e-5, sc = 18e-3, sd = 2e-2;
constexpr double ta = 2308e-5, tb = 916e-5, u = 4e-2, ua = 1228e-5, ub = 449e-5;
constexpr double zf = 2e-2, zt = 4e-2, fa = 1421e-5;

/// beta, Theta, gamma, Phi, delta, Omega, epsilon (rad), and their rates (rad/s).
using Angles = std::array<double, 7>;
constexpr Angles kStart{-0.0617138900142764496358948458001, 0.0,
                        0.455279819163070380255912382449,   0.222668390165885884674473185609,
                        0.487364979543842550225598953530,   -0.222668390165885884674473185609,
                        1.23054744454982119249735015568};
/// The Test Set's reference solution at t = 0.03 s.
constexpr Angles kEnd{0.1581077119629904e+2,  -0.1575637105984298e+2, 0.4082224013073101e-1,
                      -0.5347301163226948e+0, 0.5244099658805304e+0,  0.5347301163226948e+0,
                      0.1048080741042263e+1};
constexpr Angles kEndRates{0.1139920302151208e+4, -0.1424379294994111e+4, 0.1103291221937134e+2,
                           0.1929337464421385e+2, 0.5735699284790808e+0,  -0.1929337464421385e+2,
                           0.3231791658026955e+0};

/// The links' absolute angles about z from the Test Set's (some are relative to another link).
inline Angles absolute(const Angles& q) {
  return {q[0], q[0] + q[1], q[2], q[3] + q[4], q[4], q[5] + q[6], q[6]};
}
/// The Test Set's angles from the links' absolute angles.
inline Angles relative(const Angles& a) {
  return {a[0], a[1] - a[0], a[2], a[3] - a[4], a[4], a[5] - a[6], a[6]};
}

/// The mechanism of the file comment, its links' attitudes in the parameterization `Param` and
/// its state in the form `Form`. Each link's body frame turns with it about z, with its origin at
/// the link's centroid; the Test Set gives each link's points in a frame at its first hinge, and
/// `pt` moves them to the centroid.
template <class Param = tumble::EulerParameters,
          tumble::StateForm Form = tumble::StateForm::quasi_velocities>
struct Andrews {
  using Link = tumble::RigidBody<Param>;
  using SceneT = tumble::Mechanism<tumble::Bodies<Link>, tumble::Joints<tumble::Revolute>,
                                   tumble::Loads<tumble::SpringDamper, tumble::BodyMoment>, Form>;
  SceneT scene;
  std::array<tumble::BodyId<Link>, 7> links{};

  Andrews() {
    using tumble::ground;
    const Angles a = absolute(kStart);
    const auto turn = [&](int i, double x, double y) {
      return Vector3d(std::cos(a[i]) * x - std::sin(a[i]) * y,
                      std::sin(a[i]) * x + std::cos(a[i]) * y, 0);
    };
    // Each link: its centroid in the frame at its first hinge.
    const std::array<Vector3d, 7> centroid{
        Vector3d(ra, 0, 0),  Vector3d(-da, 0, 0), Vector3d(sb, -sa, 0), Vector3d(0, ea, 0),
        Vector3d(ta, tb, 0), Vector3d(-fa, 0, 0), Vector3d(-ub, -ua, 0)};
    const Vector3d O(0, 0, 0), A(xa, ya, 0), B(xb, yb, 0), C(xc, yc, 0);
    const Vector3d F = turn(0, rr, 0), E = F + turn(1, -d, 0);
    const std::array<Vector3d, 7> first_hinge{O, F, B, E, A, E, A};
    for (int i = 0; i < 7; ++i) {
      const double j = kInertia[i];  // about z; the out-of-plane inertia does not enter
      const Link link(
          tumble::MassProperties<>::about_centroid(kMass[i], Vector3d(j, j, j).asDiagonal()));
      links[i] = scene.add(
          link, {.position = first_hinge[i] + turn(i, centroid[i](0), centroid[i](1)),
                 .rotation = Eigen::AngleAxisd(a[i], Vector3d::UnitZ()).toRotationMatrix()});
    }
    const auto pt = [&](int i, double x, double y) {
      return Vector3d(x - centroid[i](0), y - centroid[i](1), 0);
    };
    const Vector3d z = Vector3d::UnitZ();
    const auto hinge = [&](int i, const Vector3d& pi, int k, const Vector3d& pk) {
      scene.add_joint(links[i], links[k], tumble::Revolute(pi, z, pk, z));
    };
    scene.add_joint(links[0], ground, tumble::Revolute(pt(0, 0, 0), z, O, z));  // O
    hinge(0, pt(0, rr, 0), 1, pt(1, 0, 0));                                     // F
    hinge(1, pt(1, -d, 0), 2, pt(2, 0, -ss));                                   // E
    hinge(1, pt(1, -d, 0), 3, pt(3, 0, 0));                                     // E
    hinge(1, pt(1, -d, 0), 5, pt(5, 0, 0));                                     // E
    scene.add_joint(links[2], ground, tumble::Revolute(pt(2, 0, 0), z, B, z));  // B
    hinge(3, pt(3, 0, e), 4, pt(4, zt, 0));                                     // G
    scene.add_joint(links[4], ground, tumble::Revolute(pt(4, 0, 0), z, A, z));  // A
    hinge(5, pt(5, -zf, 0), 6, pt(6, 0, -u));                                   // H
    scene.add_joint(links[6], ground, tumble::Revolute(pt(6, 0, 0), z, A, z));  // A
    scene.add_load(links[2],
                   tumble::SpringDamper(pt(2, sd, -sc), C, {.stiffness = c0, .rest_length = l0}));
    scene.add_load(links[0], tumble::BodyMoment(Vector3d(0, 0, mom)));
  }

  /// The links' absolute angles in s, each within pi of `near` (to follow them over turns).
  [[nodiscard]] Angles angles(const tumble::SceneState& s, const Angles& near) const {
    Angles a{};
    for (int i = 0; i < 7; ++i) {
      const Eigen::Matrix3d r = tumble::rotation(scene, links[i], s);
      const double wrapped = std::atan2(r(1, 0), r(0, 0));
      a[i] =
          wrapped + 2 * std::numbers::pi * std::round((near[i] - wrapped) / (2 * std::numbers::pi));
    }
    return a;
  }
  /// The links' angular rates about z in s.
  [[nodiscard]] Angles rates(const tumble::SceneState& s) const {
    Angles w{};
    for (int i = 0; i < 7; ++i) {
      w[i] = tumble::omega(scene, links[i], s)(2);
    }
    return w;
  }
  /// T + V_spring - mom (beta - beta0): constant (J).
  [[nodiscard]] double balance(const tumble::SceneState& s, double beta) const {
    return tumble::energy(scene, s) - mom * (beta - kStart[0]);
  }
};

/// What a run to 0.03 s gives: the Test Set's seven angles and their rates at the end, the
/// largest change of the energy balance (J) and the largest constraint residual (m).
struct Run {
  Angles q{}, rates{};
  double energy = 0, closure = 0;
};

/// Integrates `m` to 0.03 s with outputs every 0.3 ms (to follow the crank's turns): `integrate`
/// is called with the output times and the observer, and runs the integrator of one's choice.
template <class M, class Integrate> Run run(const M& m, Integrate&& integrate) {
  std::vector<double> times;
  for (int k = 0; k <= 100; ++k) {
    times.push_back(0.0003 * k);
  }
  Angles a = absolute(kStart);
  const double b0 = m.balance(m.scene.initial_state(), a[0]);
  Run r;
  tumble::SceneState last;
  integrate(times, [&](double, const tumble::SceneState& s) {
    a = m.angles(s, a);
    r.energy = std::max(r.energy, std::abs(m.balance(s, a[0]) - b0));
    r.closure = std::max(r.closure, tumble::constraint_residual(m.scene, s).position);
    last = s;
  });
  r.q = relative(a);
  r.rates = relative(m.rates(last));
  return r;
}

/// The largest |x - x_ref| / (1 + |x_ref|) over the seven values (the Test Set's mixed measure).
inline double mixed_error(const Angles& x, const Angles& ref) {
  double err = 0;
  for (int i = 0; i < 7; ++i) {
    err = std::max(err, std::abs(x[i] - ref[i]) / (1 + std::abs(ref[i])));
  }
  return err;
}

}  // namespace andrews

int main() {
  using namespace andrews;
  const Andrews<> m;
  const tumble::ConstraintResidual r0 =
      tumble::constraint_residual(m.scene, m.scene.initial_state());
  std::printf("%d constraint rows of rank %d; |C| = %.1e m at the start\n",
              m.scene.constraint_count(), r0.rank, r0.position);
  const double tol = 1e-10;
  tumble::AutoStatistics st;
  const Run r = run(m, [&](const std::vector<double>& times, const auto& observe) {
    st = tumble::integrate(m.scene, 0.0, times, observe, {.rtol = tol, .atol = tol});
  });
  const double eq = mixed_error(r.q, kEnd), ew = mixed_error(r.rates, kEndRates);
  std::printf("%s, %ld steps to 0.03 s\n", tumble::name(st.choices.front().method), st.steps);
  std::printf("beta = %.10f rad, beta' = %.6f rad/s at 0.03 s\n", r.q[0], r.rates[0]);
  std::printf("against the Test Set's reference: angles %.1e, rates %.1e "
              "(largest |x - x_ref| / (1 + |x_ref|))\n",
              eq, ew);
  std::printf("|E - E0| <= %.1e J (the motor's work: %.3f J), |C| <= %.1e m\n", r.energy,
              mom * (r.q[0] - kStart[0]), r.closure);
  // The Test Set's reference itself is within about 1e-10 (angles) and 3e-8 (rates) of the
  // exact solution (tests/joint/andrews.test.cpp).
  return eq <= 1e-9 && ew <= 1e-7 && r.energy <= 1e-9 ? 0 : 1;
}
