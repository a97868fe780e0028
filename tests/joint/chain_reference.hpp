#pragma once
// An open spatial chain of six rods hinged end to end, the first to the ground, swinging under
// gravity: the second model in the six joint angles, independent of tumble (Eigen and
// Boost.Odeint only), shared by tests/joint/spatial_chain.test.cpp, which checks tumble's
// mechanism against it, and by the main job's study (e) (benchmarks/mechanisms/chain.cpp), which
// measures every run against it.
//
// The chain. Rod i (i = 0..5) is 0.3 m long, 1 kg, 3 cm square in section; its frame has its
// origin at its hinge (its top end) and the rod along its -z axis, so its centroid sits at
// (0, 0, -L/2) and its far end, where rod i + 1 hangs, at (0, 0, -L). Hinge i turns rod i
// relative to its parent (rod i - 1, or the ground, whose frame is the world's) about the unit
// axis a_i, whose components are the same in both frames:
//   R_i = R_(i-1) Rot(a_i, theta_i),  p_i = p_(i-1) + R_(i-1) (0, 0, -L),  p_0 = 0,
// R_i rod i's frame -> world, p_i its hinge point in the world. At theta = 0 the chain hangs
// straight down the world's -z; the axes (kAxes) alternate between x and y with two oblique ones,
// so that no two neighbours are parallel and the motion is spatial. Gravity is 9.81 m/s^2 along
// the world's -z.
//
// The dynamics, M(theta) theta'' + h(theta, theta') = 0, by the recursive Newton-Euler algorithm
// (Luh, Walker and Paul 1980) in world components, written out here:
//   forward, i = 0..n-1 (with omega_-1 = alpha_-1 = 0 and the ground's point p_0 fixed):
//     u_i = R_(i-1) a_i (world),  omega_i = omega_(i-1) + u_i theta_i',
//     alpha_i = alpha_(i-1) + u_i theta_i'' + omega_(i-1) x u_i theta_i'   (u_i turns with i - 1),
//     a(p_i) = a(p_(i-1)) + alpha_(i-1) x d + omega_(i-1) x (omega_(i-1) x d),  d = p_i - p_(i-1),
//     a(c_i) = a(p_i) + alpha_i x r_i + omega_i x (omega_i x r_i),  r_i = c_i - p_i;
//   backward, i = n-1..0, the force f_i and the moment n_i about p_i that rod i - 1 exerts on
//   rod i (through hinge i), with f_n = n_n = 0:
//     f_i = m (a(c_i) - g) + f_(i+1),
//     n_i = I_i alpha_i + omega_i x I_i omega_i + r_i x m (a(c_i) - g) + n_(i+1)
//           + (p_(i+1) - p_i) x f_(i+1),   I_i = R_i I R_i^T,
//   and the hinge's torque tau_i = u_i . n_i. So h = tau(theta, theta', theta'' = 0) with gravity,
//   and column j of M is tau(theta, 0, e_j) without it; M theta'' = -h is solved by LDL^T.
// Energy: T = sum 1/2 m |v(c_i)|^2 + 1/2 omega_i . I_i omega_i, V = -sum m g . c_i.
// Templated on the scalar: the reference runs in long double (Fehlberg 7(8), Boost.Odeint, at
// rtol = atol = 1e-14), the test in double too.

#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <boost/numeric/odeint.hpp>

namespace chain_test {

/// The chain's data (SI).
namespace data {
constexpr int n = 6;  // rods
constexpr double length = 0.3, mass = 1.0, side = 0.03, g = 9.81;
/// The start: the hinge angles (rad) from the straight chain, and their rates (rad/s). Moderate,
/// so that the swing is rich (every hinge moves, the tip travels over 2 m, the chain twists) but
/// not chaotic over the 5 s of study (e): a start 1e-9 rad off ends 1.9e-9 m off at the tip, and
/// the reference at 1e-14 agrees with itself at 1e-13 to 6.5e-13 m (measured; the benchmark,
/// benchmarks/mechanisms/chain.cpp, reports it with each run).
constexpr std::array<double, n> theta0{0.6, -0.4, 0.5, 0.3, -0.5, 0.4};
constexpr std::array<double, n> rate0{0.8, -0.6, 0.5, -0.7, 0.4, 0.9};
}  // namespace data

/// The hinges' axes a_i, unit, in the parent's frame (equal to the child's).
template <class S> std::array<Eigen::Matrix<S, 3, 1>, data::n> axes() {
  using V = Eigen::Matrix<S, 3, 1>;
  return {V::UnitX(), V::UnitY(), V(1, 1, 1).normalized(),
          V::UnitY(), V::UnitX(), V(1, -1, 1).normalized()};
}

/// A rod's inertia about its centroid, its own axes (kg m^2): a square prism along z.
template <class S> Eigen::Matrix<S, 3, 3> rod_inertia() {
  const S m = data::mass, l = data::length, s = data::side;
  return Eigen::Matrix<S, 3, 1>(m * (l * l + s * s) / 12, m * (l * l + s * s) / 12, m * s * s / 6)
      .asDiagonal();
}

/// The second model on scalar S: state y = (theta (n), theta' (n)).
template <class S> struct Chain {
  static constexpr int n = data::n;
  using State = std::vector<S>;
  using V = Eigen::Matrix<S, 3, 1>;
  using M3 = Eigen::Matrix<S, 3, 3>;
  using Vn = Eigen::Matrix<S, n, 1>;

  /// Positions and velocities of the rods at one state, world components.
  struct Kinematics {
    std::array<M3, n> rotation;  // R_i, rod i -> world
    std::array<V, n + 1> hinge;  // p_i; p_n the last rod's far end (the tip)
    std::array<V, n> centroid;   // c_i
    std::array<V, n> axis;       // u_i, hinge i's axis
    std::array<V, n> omega;      // rod i's angular velocity
    std::array<V, n> velocity;   // its centroid's velocity
  };

  std::array<V, n> a = axes<S>();
  M3 inertia = rod_inertia<S>();  // about the centroid, rod axes
  S m = data::mass, l = data::length;
  V g = V(0, 0, -data::g);

  [[nodiscard]] Kinematics kinematics(const State& y) const {
    Kinematics k;
    M3 parent = M3::Identity();
    V w = V::Zero(), p = V::Zero(), down(0, 0, -l);
    for (int i = 0; i < n; ++i) {
      const auto ui = static_cast<std::size_t>(i);
      k.axis[ui] = parent * a[ui];
      k.rotation[ui] = parent * Eigen::AngleAxis<S>(y[ui], a[ui]).toRotationMatrix();
      k.hinge[ui] = p;
      k.centroid[ui] = p + k.rotation[ui] * (down / 2);
      w += k.axis[ui] * y[ui + n];
      k.omega[ui] = w;
      p += k.rotation[ui] * down;
      parent = k.rotation[ui];
    }
    k.hinge[n] = p;
    // The hinge points' velocities, from the ground out: v(p_i+1) = v(p_i) + omega_i x (p_i+1 -
    // p_i).
    V vp = V::Zero();
    for (std::size_t i = 0; i < n; ++i) {
      k.velocity[i] = vp + k.omega[i].cross(k.centroid[i] - k.hinge[i]);
      vp += k.omega[i].cross(k.hinge[i + 1] - k.hinge[i]);
    }
    return k;
  }

  /// The hinges' torques for accelerations `dd` at the kinematics `k` (the rates in k), with
  /// gravity `grav`: the recursive Newton-Euler algorithm of the top comment. `rates` false: as
  /// if theta' = 0 (for M's columns).
  [[nodiscard]] Vn torques(const Kinematics& k, const Vn& dd, const V& grav, bool rates) const {
    std::array<V, n> alpha, acc;  // rods' angular accelerations, centroids' accelerations
    V w_prev = V::Zero(), al_prev = V::Zero(), ap = V::Zero();  // a(p_i), the ground's is 0
    for (std::size_t i = 0; i < n; ++i) {
      const V w = rates ? k.omega[i] : V::Zero();
      // omega_(i-1) x u_i theta_i', with theta_i' = (omega_i - omega_(i-1)) . u_i.
      const V coriolis = w_prev.cross(k.axis[i]) * (w - w_prev).dot(k.axis[i]);
      alpha[i] = al_prev + k.axis[i] * dd(Eigen::Index(i)) + coriolis;
      if (i > 0) {
        const V d = k.hinge[i] - k.hinge[i - 1];
        ap += al_prev.cross(d) + w_prev.cross(w_prev.cross(d));
      }
      const V r = k.centroid[i] - k.hinge[i];
      acc[i] = ap + alpha[i].cross(r) + w.cross(w.cross(r));
      w_prev = w;
      al_prev = alpha[i];
    }
    Vn tau;
    V f = V::Zero(), mo = V::Zero();  // from rod i + 1 onto rod i, moment about p_(i+1)
    for (int i = n - 1; i >= 0; --i) {
      const auto ui = static_cast<std::size_t>(i);
      const M3 ii = k.rotation[ui] * inertia * k.rotation[ui].transpose();
      const V w = rates ? k.omega[ui] : V::Zero();
      const V r = k.centroid[ui] - k.hinge[ui];
      const V fm = m * (acc[ui] - grav);
      mo = ii * alpha[ui] + w.cross(ii * w) + r.cross(fm) + mo +
           (k.hinge[ui + 1] - k.hinge[ui]).cross(f);
      f = fm + f;
      tau(i) = k.axis[ui].dot(mo);
    }
    return tau;
  }

  /// theta'' at y.
  [[nodiscard]] Vn accelerations(const State& y) const {
    const Kinematics k = kinematics(y);
    const Vn h = torques(k, Vn::Zero(), g, true);
    Eigen::Matrix<S, n, n> mass_matrix;
    for (int j = 0; j < n; ++j) {
      mass_matrix.col(j) = torques(k, Vn::Unit(j), V::Zero(), false);
    }
    return mass_matrix.ldlt().solve(-h);
  }

  void operator()(const State& y, State& dy, S /*t*/) const {
    const Vn dd = accelerations(y);
    for (std::size_t i = 0; i < n; ++i) {
      dy[i] = y[i + n];
      dy[i + n] = dd(Eigen::Index(i));
    }
  }

  /// T + V (J), V = 0 with every centroid at the height of the ground's hinge.
  [[nodiscard]] S energy(const State& y) const {
    const Kinematics k = kinematics(y);
    S e = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const M3 ii = k.rotation[i] * inertia * k.rotation[i].transpose();
      e += m * k.velocity[i].squaredNorm() / 2 + k.omega[i].dot(ii * k.omega[i]) / 2 -
           m * g.dot(k.centroid[i]);
    }
    return e;
  }

  static State start() {
    State y(2 * n);
    for (std::size_t i = 0; i < n; ++i) {
      y[i] = data::theta0[i];
      y[i + n] = data::rate0[i];
    }
    return y;
  }

  /// The states at `times` (from y(times[0]) = start(), which is the first), integrated by
  /// Boost.Odeint's controlled Fehlberg 7(8) at rtol = atol = tol.
  [[nodiscard]] std::vector<State> run(const std::vector<S>& times, S tol) const {
    namespace odeint = boost::numeric::odeint;
    std::vector<State> out;
    State y = start();
    odeint::integrate_times(
        odeint::make_controlled(tol, tol, odeint::runge_kutta_fehlberg78<State, S>()), *this, y,
        times.begin(), times.end(), S(1e-3), [&](const State& x, S) { out.push_back(x); });
    return out;
  }
};

}  // namespace chain_test
