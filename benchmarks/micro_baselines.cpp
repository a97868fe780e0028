// tumble_micro's baselines: what tumble's qddot is measured against.
//
//   dense_lu/<P>/<ref>            the generic route: assemble M (Eq. 1.23), f_v (Eqs. 1.26-1.27)
//                                 and Q (Eq. 1.31, the same loads as qddot_loads) densely, and
//                                 solve M qddot = f_v + Q (Eq. 1.32) by a general LU with partial
//                                 pivoting. For Euler parameters the constrained system
//                                   [M, C^T; C, 0] [qddot; lambda] = [f_v + Q; -2 |pdot|^2],
//                                   C = [0, 2 p^T]  (the second derivative of |p|^2 = 1),
//                                 is solved, 8 x 8. Everything tumble skips (the coupling terms at
//                                 the centroid, the factorization, G^T) is computed here, so
//                                 qddot_loads / dense_lu is the saving.
//   hand_written/EulerParameters/centroid        the floor: the fastest case written by hand
//   hand_written_loads/EulerParameters/centroid  in plain fixed-size Eigen, not calling tumble:
//                                 omega = 2 L(p) pdot, omegadot = I^-1 (M - omega x I omega),
//                                 pddot = 1/2 L^T omegadot - |pdot|^2 p, a = F / m; the first for
//                                 a given wrench (compare with qddot/...), the second with the
//                                 wrench of the same loads assembled by hand (compare with
//                                 qddot_loads/...).
//
// Before registering, every baseline is checked against tumble's accelerations on all states (a
// benchmark of a wrong result would mean nothing).

#include <cstdio>
#include <cstdlib>
#include <string>

#include <Eigen/LU>

#include "micro_common.hpp"

namespace tumble::bench {
namespace {

// --- the generic dense route ---------------------------------------------------------------
template <class Body>
typename Body::Coords dense_lu(const Body& body, const typename Body::Coords& q,
                               const typename Body::Coords& qdot, const LoadSet& l) {
  using P = typename Body::Param;
  constexpr int n = Body::nq;
  const typename Body::MassMatrix m = body.mass_matrix(q);
  const typename Body::Coords rhs =
      body.centrifugal_coriolis(q, qdot) +
      tumble::generalized_force(body, 0.0, q, qdot, l.gravity, l.force, l.moment);
  if constexpr (P::has_constraint) {
    const Vector4<double> p = q.template tail<4>();
    const Vector4<double> pd = qdot.template tail<4>();
    Matrix<double, n + 1, n + 1> a;
    a.template topLeftCorner<n, n>() = m;
    a.template block<1, 3>(n, 0).setZero();
    a.template block<1, 4>(n, 3) = 2.0 * p.transpose();
    a.template block<n, 1>(0, n) = a.template block<1, n>(n, 0).transpose();
    a(n, n) = 0.0;
    Vector<double, n + 1> b;
    b << rhs, -2.0 * pd.squaredNorm();
    const Vector<double, n + 1> x = Eigen::PartialPivLU<Matrix<double, n + 1, n + 1>>(a).solve(b);
    return x.template head<n>();
  } else {
    return Eigen::PartialPivLU<typename Body::MassMatrix>(m).solve(rhs);
  }
}

// --- the hand-written floor: a centroidal body in Euler parameters --------------------------
struct HandWritten {
  double mass = body_mass();
  Matrix3<double> inertia = body_inertia();
  Matrix3<double> inertia_inverse = body_inertia().inverse();
  Vector3<double> weight = body_mass() * load_gravity();
  Vector3<double> point = load_point();
  Vector3<double> point_force = load_point_force();
  Vector3<double> moment = load_moment();

  static Matrix<double, 3, 4> l_of(const Vector4<double>& p) {
    Matrix<double, 3, 4> l;
    l << -p(1), p(0), p(3), -p(2),  //
        -p(2), -p(3), p(0), p(1),   //
        -p(3), p(2), -p(1), p(0);
    return l;
  }

  /// qddot for the wrench (f inertial, mc body).
  Vector<double, 7> accelerations(const Vector<double, 7>& q, const Vector<double, 7>& qd,
                                  const Vector3<double>& f, const Vector3<double>& mc) const {
    const Vector4<double> p = q.tail<4>();
    const Vector4<double> pd = qd.tail<4>();
    const Matrix<double, 3, 4> l = l_of(p);
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

template <class Body> void check_dense(const States<Body>& s) {
  const Body body(mass_properties<Body::reference>());
  const LoadSet l;
  for (std::size_t i = 0; i < kStates; ++i) {
    const auto a =
        tumble::accelerations(body, 0.0, s.q[i], s.qdot[i], l.gravity, l.force, l.moment);
    const auto b = dense_lu(body, s.q[i], s.qdot[i], l);
    if (!((a - b).norm() <= 1e-8 * (1.0 + a.norm()))) {
      std::fprintf(stderr, "tumble_micro: dense LU and tumble disagree for %s/%s, state %zu\n",
                   std::string(Body::Param::name).c_str(), ref_name(Body::reference), i);
      std::exit(2);
    }
  }
}

template <class P, ReferencePoint Ref> void register_dense() {
  using Body = RigidBody<P, Ref, double>;
  check_dense(States<Body>());
  add(std::string("dense_lu/") + std::string(P::name) + "/" + ref_name(Ref),
      [](benchmark::State& st) {
        static const States<Body> s;
        const Body body(mass_properties<Ref>());
        const LoadSet l;
        run_cycling(st, [&](std::size_t i) { return dense_lu(body, s.q[i], s.qdot[i], l); });
      });
}

template <class... P> void register_dense_all() {
  (register_dense<P, ReferencePoint::centroid>(), ...);
  (register_dense<P, ReferencePoint::offset>(), ...);
}

void register_hand_written() {
  using Body = RigidBody<EulerParameters, ReferencePoint::centroid, double>;
  {
    const States<Body> s;
    const Body body(mass_properties<ReferencePoint::centroid>());
    const HandWritten h;
    const LoadSet l;
    for (std::size_t i = 0; i < kStates; ++i) {
      const auto a = body.accelerations(s.q[i], s.qdot[i], s.wrench[i]);
      const auto b = h.accelerations(s.q[i], s.qdot[i], s.wrench[i].force, s.wrench[i].moment);
      const auto c =
          tumble::accelerations(body, 0.0, s.q[i], s.qdot[i], l.gravity, l.force, l.moment);
      const auto d = h.accelerations_loads(s.q[i], s.qdot[i]);
      if (!((a - b).norm() <= 1e-10 * (1.0 + a.norm())) ||
          !((c - d).norm() <= 1e-10 * (1.0 + c.norm()))) {
        std::fprintf(stderr,
                     "tumble_micro: the hand-written closed form and tumble disagree, "
                     "state %zu\n",
                     i);
        std::exit(2);
      }
    }
  }
  add("hand_written/EulerParameters/centroid", [](benchmark::State& st) {
    static const States<Body> s;
    const HandWritten h;
    run_cycling(st, [&](std::size_t i) {
      return h.accelerations(s.q[i], s.qdot[i], s.wrench[i].force, s.wrench[i].moment);
    });
  });
  add("hand_written_loads/EulerParameters/centroid", [](benchmark::State& st) {
    static const States<Body> s;
    const HandWritten h;
    run_cycling(st, [&](std::size_t i) { return h.accelerations_loads(s.q[i], s.qdot[i]); });
  });
}

}  // namespace

void register_baselines() {
  register_hand_written();
  register_dense_all<EulerParameters, RodriguesParameters, ModifiedRodriguesParameters,
                     RotationVector, EulerXYZ, EulerXZY, EulerYXZ, EulerYZX, EulerZXY, EulerZYX,
                     EulerXYX, EulerXZX, EulerYXY, EulerYZY, EulerZXZ, EulerZYZ>();
}

}  // namespace tumble::bench
