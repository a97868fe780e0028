// The second model of IFToMM A03, Andrews' squeezing mechanism, for andrews.test.cpp and
// andrews_bdf.test.cpp: the Test Set's seven joint angles q = (beta, Theta, gamma, Phi, delta,
// Omega, epsilon) with six loop-closure constraints, integrated in long double.
//
// Every point of the mechanism is a sum of vectors turned by linear combinations of the angles,
// p(q) = p0 + sum_k R(l_k . q) v_k (the absolute angle of a link is l . q for an integer vector
// l), so its Jacobian is sum_k R'(l_k . q) v_k l_k^T and its acceleration at qddot = 0 is
// -sum_k (l_k . qdot)^2 R(l_k . q) v_k. The links form a tree from the ground (O-1-2, B-3, A-5-4,
// A-7-6) cut at E; the constraints say that the four branches reach the same E. Lagrange's
// equations with multipliers,
//   [M  G^T] [qddot ]   [Q - sum_i m_i J_i^T a0_i]
//   [G  0  ] [lambda] = [-gddot at qddot = 0     ],   M = sum_i m_i J_i^T J_i + I_i l_i l_i^T,
// are solved by LU at every right-hand side and integrated by Boost.Odeint's Fehlberg 7(8) in
// long double (64-bit mantissa) to 1e-17: its error is far below double's rounding.
//
// Include after examples/andrews.cpp (its data, namespace andrews).

#pragma once

#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include <Eigen/Dense>
#include <boost/numeric/odeint.hpp>

#include "tumble/integrate.hpp"

namespace andrews_test {

using Real = long double;
using V2 = Eigen::Matrix<Real, 2, 1>;
using Q7 = Eigen::Matrix<Real, 7, 1>;
using J27 = Eigen::Matrix<Real, 2, 7>;

/// R(l . q) v, one vector of a point's sum.
struct Arm {
  std::array<int, 7> l;
  V2 v;
};
/// p0 + the sum of its arms.
struct Point {
  V2 p0 = V2::Zero();
  std::vector<Arm> arms;
  [[nodiscard]] V2 at(const Q7& q) const {
    V2 p = p0;
    for (const Arm& a : arms) {
      p += turn(angle(a, q)) * a.v;
    }
    return p;
  }
  [[nodiscard]] J27 jacobian(const Q7& q) const {
    J27 j = J27::Zero();
    for (const Arm& a : arms) {
      const V2 d = turn(angle(a, q)) * V2(-a.v(1), a.v(0));  // R' v = R (z x v)
      for (int c = 0; c < 7; ++c) {
        j.col(c) += Real(a.l[c]) * d;
      }
    }
    return j;
  }
  /// The acceleration at qddot = 0.
  [[nodiscard]] V2 centripetal(const Q7& q, const Q7& qd) const {
    V2 a0 = V2::Zero();
    for (const Arm& a : arms) {
      const Real w = angle(a, qd);
      a0 -= w * w * (turn(angle(a, q)) * a.v);
    }
    return a0;
  }
  static Real angle(const Arm& a, const Q7& q) {
    Real s = 0;
    for (int c = 0; c < 7; ++c) {
      s += Real(a.l[c]) * q(c);
    }
    return s;
  }
  static Eigen::Matrix<Real, 2, 2> turn(Real t) {
    Eigen::Matrix<Real, 2, 2> r;
    r << std::cos(t), -std::sin(t), std::sin(t), std::cos(t);
    return r;
  }
};

/// The Test Set's angles: the links' absolute angles as combinations of q.
inline constexpr std::array<std::array<int, 7>, 7> kLink{{{1, 0, 0, 0, 0, 0, 0},
                                                          {1, 1, 0, 0, 0, 0, 0},
                                                          {0, 0, 1, 0, 0, 0, 0},
                                                          {0, 0, 0, 1, 1, 0, 0},
                                                          {0, 0, 0, 0, 1, 0, 0},
                                                          {0, 0, 0, 0, 0, 1, 1},
                                                          {0, 0, 0, 0, 0, 0, 1}}};

/// The mechanism in the seven angles (the data of examples/andrews.cpp).
struct MinimalModel {
  std::array<Point, 7> centroid;
  std::array<Point, 4> ends;  // E reached through 1-2, 3, 5-4 and 7-6
  Point spring_end;           // D, the spring's end on the triangle

  MinimalModel() {
    using namespace andrews;
    const V2 a(xa, ya), b(xb, yb);
    const auto arm = [](int link, Real x, Real y) { return Arm{kLink[link], V2(x, y)}; };
    centroid[0] = {V2::Zero(), {arm(0, ra, 0)}};
    centroid[1] = {V2::Zero(), {arm(0, rr, 0), arm(1, -da, 0)}};
    centroid[2] = {b, {arm(2, sb, -sa)}};
    centroid[3] = {a, {arm(4, zt, 0), arm(3, 0, ea - e)}};
    centroid[4] = {a, {arm(4, ta, tb)}};
    centroid[5] = {a, {arm(6, 0, -u), arm(5, zf - fa, 0)}};
    centroid[6] = {a, {arm(6, -ub, -ua)}};
    ends[0] = {V2::Zero(), {arm(0, rr, 0), arm(1, -andrews::d, 0)}};
    ends[1] = {b, {arm(2, 0, -ss)}};
    ends[2] = {a, {arm(4, zt, 0), arm(3, 0, -e)}};
    ends[3] = {a, {arm(6, 0, -u), arm(5, zf, 0)}};
    spring_end = {b, {arm(2, sd, -sc)}};
  }

  /// g(q): E through 1-2 minus E through each other branch.
  [[nodiscard]] Eigen::Matrix<Real, 6, 1> closure(const Q7& q) const {
    Eigen::Matrix<Real, 6, 1> g;
    for (int k = 0; k < 3; ++k) {
      g.segment<2>(2 * k) = ends[0].at(q) - ends[k + 1].at(q);
    }
    return g;
  }

  /// qddot at (q, qdot).
  [[nodiscard]] Q7 accelerations(const Q7& q, const Q7& qd) const {
    using namespace andrews;
    Eigen::Matrix<Real, 13, 13> a = Eigen::Matrix<Real, 13, 13>::Zero();
    Eigen::Matrix<Real, 13, 1> rhs = Eigen::Matrix<Real, 13, 1>::Zero();
    for (int i = 0; i < 7; ++i) {
      const J27 j = centroid[i].jacobian(q);
      Q7 l;
      for (int c = 0; c < 7; ++c) {
        l(c) = Real(kLink[i][c]);
      }
      a.topLeftCorner<7, 7>() +=
          Real(kMass[i]) * j.transpose() * j + Real(kInertia[i]) * l * l.transpose();
      rhs.head<7>() -= Real(kMass[i]) * j.transpose() * centroid[i].centripetal(q, qd);
    }
    rhs(0) += Real(mom);  // the motor turns link 1, whose angle is beta
    const V2 cd = spring_end.at(q) - V2(xc, yc);
    const Real len = cd.norm();
    const V2 spring = -Real(c0) * (len - Real(l0)) / len * cd;  // on D
    rhs.head<7>() += spring_end.jacobian(q).transpose() * spring;
    for (int k = 0; k < 3; ++k) {
      const J27 g = ends[0].jacobian(q) - ends[k + 1].jacobian(q);
      a.block<2, 7>(7 + 2 * k, 0) = g;
      a.block<7, 2>(0, 7 + 2 * k) = g.transpose();
      rhs.segment<2>(7 + 2 * k) = -(ends[0].centripetal(q, qd) - ends[k + 1].centripetal(q, qd));
    }
    return a.fullPivLu().solve(rhs).head<7>();
  }
};

/// [q; qdot]: a vector rather than an array, whose uninitialized scratch in Odeint's steppers
/// GCC 12 at -O3 flags when they are copied.
using State14 = std::vector<Real>;

/// The second model's angles and rates at t = 0.03 s, from rest at the Test Set's start.
inline State14 minimal_reference(Real& closure) {
  const MinimalModel model;
  State14 x(14, Real(0));
  for (int i = 0; i < 7; ++i) {
    x[i] = Real(andrews::kStart[i]);
  }
  namespace odeint = boost::numeric::odeint;
  auto f = [&](const State14& y, State14& dy, Real) {
    const Q7 q = Eigen::Map<const Q7>(y.data());
    const Q7 qd = Eigen::Map<const Q7>(y.data() + 7);
    const Q7 qdd = model.accelerations(q, qd);
    for (int i = 0; i < 7; ++i) {
      dy[i] = y[i + 7];
      dy[i + 7] = qdd(i);
    }
  };
  odeint::integrate_adaptive(odeint::make_controlled<odeint::runge_kutta_fehlberg78<State14, Real>>(
                                 Real(1e-17), Real(1e-17)),
                             f, x, Real(0), Real(0.03), Real(1e-6));
  closure = model.closure(Eigen::Map<const Q7>(x.data())).cwiseAbs().maxCoeff();
  return x;
}

/// The second model's angles (first) and rates (second) in double.
inline std::pair<andrews::Angles, andrews::Angles> split(const State14& x) {
  andrews::Angles q{}, w{};
  for (int i = 0; i < 7; ++i) {
    q[i] = static_cast<double>(x[i]);
    w[i] = static_cast<double>(x[i + 7]);
  }
  return {q, w};
}

/// tumble's run of `M` to 0.03 s with the integrator `I` at rtol = atol = tol.
template <class I, class M> andrews::Run tumble_run(const M& m, double tol) {
  return andrews::run(m, [&](const std::vector<double>& times, const auto& observe) {
    typename I::Options opt;
    opt.rtol = tol;
    opt.atol = tol;
    I integrator(m.scene, 0.0, opt);
    integrator.integrate(times, observe);
  });
}

}  // namespace andrews_test
