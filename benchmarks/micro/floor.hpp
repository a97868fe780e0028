#pragma once
// tumble_micro's floor: the fastest case of tumble's qddot (Euler parameters, body framed at its
// centroid) written by hand in plain fixed-size Eigen, not calling tumble:
//   omega = 2 L(p) pdot,  omegadot = I^-1 (M - omega x I omega),
//   pddot = 1/2 L^T omegadot - |pdot|^2 p,  a = F / m
// (reference chapter, Eqs. 1.5, 1.10 and 1.33). A header, so that the benchmark that times it is
// compiled in the translation unit of the tumble benchmark it is compared with (micro/micro.cpp),
// with the same harness and data.
//
// Why it is written this way: until 2026-11-25 the floor lived in micro/baselines.cpp and was
// written with nested Eigen product expressions (2 * (l * pd), I^-1 * (mc - w x (I w)),
// 0.5 * (l^T * wd)). GCC 12 -O3 compiled it as an out-of-line function, called from the
// benchmark loop, which itself called Eigen's cross(Product) and a product_evaluator::coeff(i)
// per coefficient out of line (objdump -dr of micro/baselines.cpp.o): tumble_micro timed that
// at 44-57 ns, where the same equations take 14-17 ns inlined. tumble's own qddot evaluates
// its products into named vectors for the same reason (body/rigid_body.hpp). The floor does
// the same now: every product goes into a named fixed-size vector, L(p) products are written out.

#include "micro/common.hpp"

namespace tumble::bench {

struct HandWritten {
  double mass = body_mass();
  Matrix3<double> inertia = body_inertia();
  Matrix3<double> inertia_inverse = body_inertia().inverse();
  Vector3<double> weight = body_mass() * load_gravity();
  Vector3<double> point = load_point();
  Vector3<double> point_force = load_point_force();
  Vector3<double> moment = load_moment();

  /// qddot for the wrench (f inertial, mc body).
  Vector<double, 7> accelerations(const Vector<double, 7>& q, const Vector<double, 7>& qd,
                                  const Vector3<double>& f, const Vector3<double>& mc) const {
    const double e0 = q(3), e1 = q(4), e2 = q(5), e3 = q(6);
    const double d0 = qd(3), d1 = qd(4), d2 = qd(5), d3 = qd(6);
    // omega = 2 L(p) pdot
    const Vector3<double> w(2.0 * (-e1 * d0 + e0 * d1 + e3 * d2 - e2 * d3),
                            2.0 * (-e2 * d0 - e3 * d1 + e0 * d2 + e1 * d3),
                            2.0 * (-e3 * d0 + e2 * d1 - e1 * d2 + e0 * d3));
    const Vector3<double> h = inertia.lazyProduct(w);
    const Vector3<double> mg = mc - w.cross(h);
    const Vector3<double> wd = inertia_inverse.lazyProduct(mg);
    const double pd2 = d0 * d0 + d1 * d1 + d2 * d2 + d3 * d3;
    Vector<double, 7> qdd;
    qdd.head<3>() = f / mass;
    // pddot = 1/2 L(p)^T omegadot - |pdot|^2 p
    qdd(3) = 0.5 * (-e1 * wd(0) - e2 * wd(1) - e3 * wd(2)) - pd2 * e0;
    qdd(4) = 0.5 * (e0 * wd(0) - e3 * wd(1) + e2 * wd(2)) - pd2 * e1;
    qdd(5) = 0.5 * (e3 * wd(0) + e0 * wd(1) - e1 * wd(2)) - pd2 * e2;
    qdd(6) = 0.5 * (-e2 * wd(0) + e1 * wd(1) + e0 * wd(2)) - pd2 * e3;
    return qdd;
  }

  /// The former floor, the same equations as nested Eigen product expressions: kept for
  /// tumble_floor_check (micro/floor_check.cpp), which shows what the form alone costs.
  Vector<double, 7> accelerations_nested(const Vector<double, 7>& q, const Vector<double, 7>& qd,
                                         const Vector3<double>& f,
                                         const Vector3<double>& mc) const {
    const Vector4<double> p = q.tail<4>();
    const Vector4<double> pd = qd.tail<4>();
    Matrix<double, 3, 4> l;
    l << -p(1), p(0), p(3), -p(2),  //
        -p(2), -p(3), p(0), p(1),   //
        -p(3), p(2), -p(1), p(0);
    const Vector3<double> w = 2.0 * (l * pd);
    const Vector3<double> wd = inertia_inverse * (mc - w.cross(inertia * w));
    Vector<double, 7> qdd;
    qdd.head<3>() = f / mass;
    qdd.tail<4>() = 0.5 * (l.transpose() * wd) - pd.squaredNorm() * p;
    return qdd;
  }

  /// qddot under gravity + the point force (inertial) + the body moment.
  Vector<double, 7> accelerations_loads(const Vector<double, 7>& q,
                                        const Vector<double, 7>& qd) const {
    const double e0 = q(3), e1 = q(4), e2 = q(5), e3 = q(6);
    // R^T f with R = (e0^2 - e.e) I + 2 e e^T + 2 e0 S(e): R^T f = (e0^2 - e.e) f + 2 (e.f) e
    // - 2 e0 e x f.
    const Vector3<double> e(e1, e2, e3);
    const Vector3<double> fb = (e0 * e0 - e.squaredNorm()) * point_force +
                               (2.0 * e.dot(point_force)) * e - (2.0 * e0) * e.cross(point_force);
    return accelerations(q, qd, weight + point_force, moment + point.cross(fb));
  }
};

}  // namespace tumble::bench
