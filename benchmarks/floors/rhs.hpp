#pragma once
// tumble_bench: the hand-written first-order right-hand side that the integrator floors share
// (floors/sundials.cpp: CVODE and ARKODE; floors/odeint.cpp:
// Boost.Odeint). One closed form, written out by hand in scalars, not calling tumble:
//
//   N = 7, a torque-free body framed at its centroid:  x = [p (4); omega (3)]
//   N = 13, any of the problems:                       x = [r_g (3); p (4); v_g (3); omega (3)]
//
// with Euler parameters p (scalar first), omega in body components, r_g, v_g the centroid's
// position and velocity (inertial), and L(p) = [-e | e0 I - S(e)]:
//   pdot     = 1/2 L(p)^T omega                               (reference chapter, Eq. 1.5)
//   omegadot = I^-1 (M_g - omega x I omega)                   (Euler's equations, principal I)
//   vdot_g   = g + F / m,   rdot_g = v_g
// The loads of the 13-state form: uniform gravity, and the stiff top's isotropic spring-damper
// (zero rest length) from the reference point c (r_c = r_g - R c_f, c_f the centroid's offset in
// the body) to the inertial origin: F = -k r_c - d v_c, v_c = v_g - R (omega x c_f), with the
// moment about the centroid M_g = (-c_f) x R^T F. p is not kept unit inside the right-hand side
// (no stabilization): an output normalizes it (rotation_of_unit), as simulators do; the drift of
// |p| is reported.
//
// operator() counts every evaluation (`evals`), as tumble's integrators count theirs, so that
// methods whose integrator does not count its right-hand sides (Boost.Odeint) report them as
// the SUNDIALS ones do; rates() is the closed form itself. Constant factors are computed once
// (the Euler coefficients (I_2 - I_3) / I_1, ..., 1/m, 1/2 folded into omega): no division per
// evaluation but the one by |p|^2 that the spring needs (three divisions per evaluation made
// the Fehlberg 7(8) floor 1.2x slower, docs/benchmarks/floors.md, 2026-11-26).

#include <array>
#include <cmath>
#include <cstddef>

#include <Eigen/Geometry>

#include "common/bench.hpp"

namespace tumble::bench {

template <int N> struct FloorRhs {
  static_assert(N == 7 || N == 13, "the floors' state is [p; omega] or [r_g; p; v_g; omega]");
  static constexpr int size = N;
  static constexpr int p_at = N == 7 ? 0 : 3;  ///< index of e0
  static constexpr int w_at = N == 7 ? 4 : 10;

  double i1 = 1, i2 = 1, i3 = 1;  ///< principal inertia about the centroid
  double mass = 1;
  double gx = 0, gy = 0, gz = 0;  ///< gravity
  double k = 0, d = 0;            ///< the spring-damper at the reference point (13 states only)
  double cx = 0, cy = 0, cz = 0;  ///< the centroid's offset from the reference point, body
  double c1 = 0, c2 = 0, c3 = 0;  ///< (i2 - i3) / i1, (i3 - i1) / i2, (i1 - i2) / i3
  double j1 = 1, j2 = 1, j3 = 1;  ///< 1 / i1, 1 / i2, 1 / i3
  double inv_mass = 1;
  mutable long evals = 0;

  explicit FloorRhs(const Problem& p)
      : i1(p.inertia.x()),
        i2(p.inertia.y()),
        i3(p.inertia.z()),
        mass(p.mass),
        gx(p.gravity.x()),
        gy(p.gravity.y()),
        gz(p.gravity.z()),
        k(p.stiffness),
        d(p.damping),
        cx(p.centroid.x()),
        cy(p.centroid.y()),
        cz(p.centroid.z()),
        c1((i2 - i3) / i1),
        c2((i3 - i1) / i2),
        c3((i1 - i2) / i3),
        j1(1 / i1),
        j2(1 / i2),
        j3(1 / i3),
        inv_mass(1 / mass) {}

  /// Whether the problem fits the 7-state form (torque-free and framed at its centroid).
  static bool fits(const Problem& p) {
    return N == 13 || (p.at_centroid && p.gravity.isZero() && p.stiffness == 0);
  }

  /// xd = f(x), counted.
  void operator()(const double* x, double* xd) const {
    ++evals;
    rates(x, xd);
  }

  /// xd = f(x).
  void rates(const double* x, double* xd) const {
    const double e0 = x[p_at], e1 = x[p_at + 1], e2 = x[p_at + 2], e3 = x[p_at + 3];
    const double w1 = x[w_at], w2 = x[w_at + 1], w3 = x[w_at + 2];
    double m1 = 0, m2 = 0, m3 = 0;  // moment about the centroid, body
    if constexpr (N == 13) {
      double fx = 0, fy = 0, fz = 0;  // the spring's force, inertial
      if (k != 0 || d != 0) {
        // R columns (body -> inertial) from p.
        const double r00 = e0 * e0 + e1 * e1 - e2 * e2 - e3 * e3, r01 = 2 * (e1 * e2 - e0 * e3),
                     r02 = 2 * (e1 * e3 + e0 * e2), r10 = 2 * (e1 * e2 + e0 * e3),
                     r11 = e0 * e0 - e1 * e1 + e2 * e2 - e3 * e3, r12 = 2 * (e2 * e3 - e0 * e1),
                     r20 = 2 * (e1 * e3 - e0 * e2), r21 = 2 * (e2 * e3 + e0 * e1),
                     r22 = e0 * e0 - e1 * e1 - e2 * e2 + e3 * e3;
        const double s = 1.0 / (e0 * e0 + e1 * e1 + e2 * e2 + e3 * e3);  // R of p / |p|
        // r_c = r_g - R c, v_c = v_g - R (omega x c)
        const double ux = w2 * cz - w3 * cy, uy = w3 * cx - w1 * cz, uz = w1 * cy - w2 * cx;
        const double rcx = x[0] - s * (r00 * cx + r01 * cy + r02 * cz);
        const double rcy = x[1] - s * (r10 * cx + r11 * cy + r12 * cz);
        const double rcz = x[2] - s * (r20 * cx + r21 * cy + r22 * cz);
        const double vcx = x[7] - s * (r00 * ux + r01 * uy + r02 * uz);
        const double vcy = x[8] - s * (r10 * ux + r11 * uy + r12 * uz);
        const double vcz = x[9] - s * (r20 * ux + r21 * uy + r22 * uz);
        fx = -k * rcx - d * vcx;
        fy = -k * rcy - d * vcy;
        fz = -k * rcz - d * vcz;
        // F in the body, then M_g = (-c) x F_b
        const double bx = s * (r00 * fx + r10 * fy + r20 * fz);
        const double by = s * (r01 * fx + r11 * fy + r21 * fz);
        const double bz = s * (r02 * fx + r12 * fy + r22 * fz);
        m1 = -(cy * bz - cz * by);
        m2 = -(cz * bx - cx * bz);
        m3 = -(cx * by - cy * bx);
      }
      xd[0] = x[7];
      xd[1] = x[8];
      xd[2] = x[9];
      xd[7] = gx + fx * inv_mass;
      xd[8] = gy + fy * inv_mass;
      xd[9] = gz + fz * inv_mass;
    }
    // pdot = 1/2 L(p)^T omega
    const double h1 = 0.5 * w1, h2 = 0.5 * w2, h3 = 0.5 * w3;
    xd[p_at] = -e1 * h1 - e2 * h2 - e3 * h3;
    xd[p_at + 1] = e0 * h1 - e3 * h2 + e2 * h3;
    xd[p_at + 2] = e3 * h1 + e0 * h2 - e1 * h3;
    xd[p_at + 3] = -e2 * h1 + e1 * h2 + e0 * h3;
    // Euler's equations, principal axes
    if constexpr (N == 13) {
      xd[w_at] = m1 * j1 + c1 * w2 * w3;
      xd[w_at + 1] = m2 * j2 + c2 * w3 * w1;
      xd[w_at + 2] = m3 * j3 + c3 * w1 * w2;
    } else {  // torque-free
      (void)m1, (void)m2, (void)m3;
      xd[w_at] = c1 * w2 * w3;
      xd[w_at + 1] = c2 * w3 * w1;
      xd[w_at + 2] = c3 * w1 * w2;
    }
  }

  /// The initial state of problem `p`.
  [[nodiscard]] std::array<double, N> initial(const Problem& p) const {
    const Eigen::Quaterniond q(p.r0);
    std::array<double, N> x{};
    if constexpr (N == 13) {
      const Eigen::Vector3d rg = p.position0 + p.r0 * p.centroid;
      const Eigen::Vector3d vg = p.velocity0 + p.r0 * p.omega0.cross(p.centroid);
      for (int i = 0; i < 3; ++i) {
        x[static_cast<std::size_t>(i)] = rg(i);
        x[static_cast<std::size_t>(7 + i)] = vg(i);
      }
    }
    const Eigen::Vector4d p0 = Eigen::Vector4d(q.w(), q.x(), q.y(), q.z()).normalized();
    for (int i = 0; i < 4; ++i) {
      x[static_cast<std::size_t>(p_at + i)] = p0(i);
    }
    for (int i = 0; i < 3; ++i) {
      x[static_cast<std::size_t>(w_at + i)] = p.omega0(i);
    }
    return x;
  }

  /// The sample of state x (p normalized first).
  [[nodiscard]] Sample sample(const Problem& p, const double* x) const {
    Eigen::Vector4d q(x[p_at], x[p_at + 1], x[p_at + 2], x[p_at + 3]);
    q.normalize();
    Sample s;
    s.rotation = Eigen::Quaterniond(q(0), q(1), q(2), q(3)).toRotationMatrix();
    s.omega = Eigen::Vector3d(x[w_at], x[w_at + 1], x[w_at + 2]);
    if constexpr (N == 13) {
      const Eigen::Vector3d rg(x[0], x[1], x[2]);
      const Eigen::Vector3d vg(x[7], x[8], x[9]);
      s.position = rg - s.rotation * p.centroid;
      s.velocity = vg - s.rotation * s.omega.cross(p.centroid);
    }
    return s;
  }

  /// | |p| - 1 | of state x.
  [[nodiscard]] static double drift(const double* x) {
    const Eigen::Vector4d q(x[p_at], x[p_at + 1], x[p_at + 2], x[p_at + 3]);
    return std::abs(q.norm() - 1.0);
  }
};

}  // namespace tumble::bench
