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
// The hand-written floor (hand_written/..., micro/floor.hpp) is registered in micro/micro.cpp,
// beside the tumble benchmark it is compared with, so that both are compiled in one translation
// unit.
//
// Before registering, every baseline is checked against tumble's accelerations on all states (a
// benchmark of a wrong result would mean nothing).

#include <cstdio>
#include <cstdlib>
#include <string>

#include <Eigen/LU>

#include "micro/common.hpp"

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

}  // namespace

void register_baselines() {
  register_dense_all<EulerParameters, RodriguesParameters, ModifiedRodriguesParameters,
                     RotationVector, EulerXYZ, EulerXZY, EulerYXZ, EulerYZX, EulerZXY, EulerZYX,
                     EulerXYX, EulerXZX, EulerYXY, EulerYZY, EulerZXZ, EulerZYZ>();
}

}  // namespace tumble::bench
