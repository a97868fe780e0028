// tumble_micro's Pinocchio peer (built when CMake finds Pinocchio; TUMBLE_BENCH_PINOCCHIO).
//
// The same body as tumble's benchmarks (micro/common.hpp) as a Pinocchio model: one
// JointModelFreeFlyer at the reference point c with the body's mass, centroid offset (zero for
// ReferencePoint::centroid) and inertia about the centroid. Model gravity is zero and the applied
// wrench is the joint torque tau = [R^T F; M_c] (body frame, about c), the same wrench that
// qddot/<P>/<ref> is given, so both compute the same accelerations on the same 64 states:
//   pinocchio_aba/<ref>              pinocchio::aba (the articulated-body algorithm)
//   pinocchio_crba_nle/<ref>         pinocchio::crba + pinocchio::nonLinearEffects (M and the bias
//                                    forces, the assembly counterpart of mass_matrix +
//                                    centrifugal_coriolis)
//   pinocchio_crba_nle_solve/<ref>   the same + pinocchio::cholesky::decompose and solve (qddot;
//                                    both read the upper triangle crba fills)
// Pinocchio's algorithms are compiled from its headers (pinocchio::pinocchio_headers) with the
// same compiler and flags as tumble: no call into a separately built library, the most favorable
// setting for Pinocchio. The results are checked against tumble's before the benchmarks run.

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <pinocchio/multibody.hpp>
// (the model and data before the algorithms that take them)
#include <pinocchio/algorithm/aba.hpp>
#include <pinocchio/algorithm/cholesky.hpp>
#include <pinocchio/algorithm/crba.hpp>
#include <pinocchio/algorithm/rnea.hpp>

#include "micro/common.hpp"

namespace tumble::bench {
namespace {

using Vector6 = Eigen::Matrix<double, 6, 1>;

template <ReferencePoint Ref> struct PinocchioCase {
  pinocchio::Model model;
  std::vector<Eigen::VectorXd> q, v, tau;

  PinocchioCase() {
    const Vector3<double> lever =
        Ref == ReferencePoint::centroid ? Vector3<double>::Zero() : body_centroid_offset();
    const auto joint =
        model.addJoint(0, pinocchio::JointModelFreeFlyer(), pinocchio::SE3::Identity(), "body");
    model.appendBodyToJoint(joint, pinocchio::Inertia(body_mass(), lever, body_inertia()),
                            pinocchio::SE3::Identity());
    model.gravity.setZero();  // every load is in the wrench, as for tumble's qddot
    for (const auto& s : raw_states()) {
      const Matrix3<double> r = s.attitude.toRotationMatrix();
      Eigen::VectorXd qi(7), vi(6), ti(6);
      qi << s.position, s.attitude.x(), s.attitude.y(), s.attitude.z(), s.attitude.w();
      vi << r.transpose() * s.velocity, s.omega;  // free flyer: local linear velocity
      ti << r.transpose() * s.wrench.force, s.wrench.moment;
      q.push_back(qi);
      v.push_back(vi);
      tau.push_back(ti);
    }
  }

  /// aba's result against tumble's: alpha = 2 L(p) pddot and R^T rddot = a + omega x v.
  void check() const {
    using Body = RigidBody<EulerParameters, Ref, double>;
    const States<Body> s;
    const Body body(mass_properties<Ref>());
    pinocchio::Data data(model);
    for (std::size_t i = 0; i < kStates; ++i) {
      const Vector6 a = pinocchio::aba(model, data, q[i], v[i], tau[i]);
      const auto qdd = body.accelerations(s.q[i], s.qdot[i], s.wrench[i]);
      const Vector4<double> p = s.q[i].template tail<4>();
      const Vector3<double> alpha = EulerParameters::G(p) * qdd.template tail<4>();
      const Matrix3<double> r = EulerParameters::rotation(p);
      const Vector3<double> w = v[i].tail<3>();
      const Vector3<double> vl = v[i].head<3>();
      const Vector3<double> lin = r * (a.head<3>() + w.cross(vl));
      const double err = (alpha - a.tail<3>()).norm() + (lin - qdd.template head<3>()).norm();
      if (!(err <= 1e-9 * (1.0 + qdd.norm()))) {
        std::fprintf(stderr, "tumble_micro: Pinocchio and tumble disagree (%s, state %zu, %g)\n",
                     ref_name(Ref), i, err);
        std::exit(2);
      }
    }
  }
};

template <ReferencePoint Ref> void register_ref() {
  PinocchioCase<Ref>().check();
  const std::string ref = ref_name(Ref);
  add("pinocchio_aba/" + ref, [](benchmark::State& st) {
    static const PinocchioCase<Ref> c;
    pinocchio::Data data(c.model);
    run_cycling(st, [&](std::size_t i) {
      return Vector6(pinocchio::aba(c.model, data, c.q[i], c.v[i], c.tau[i]));
    });
  });
  add("pinocchio_crba_nle/" + ref, [](benchmark::State& st) {
    static const PinocchioCase<Ref> c;
    pinocchio::Data data(c.model);
    run_cycling(st, [&](std::size_t i) {
      pinocchio::crba(c.model, data, c.q[i]);
      pinocchio::nonLinearEffects(c.model, data, c.q[i], c.v[i]);
      benchmark::DoNotOptimize(data.M.data());
      return Vector6(data.nle);
    });
  });
  add("pinocchio_crba_nle_solve/" + ref, [](benchmark::State& st) {
    static const PinocchioCase<Ref> c;
    pinocchio::Data data(c.model);
    Eigen::VectorXd x(6);
    run_cycling(st, [&](std::size_t i) {
      pinocchio::crba(c.model, data, c.q[i]);
      pinocchio::nonLinearEffects(c.model, data, c.q[i], c.v[i]);
      pinocchio::cholesky::decompose(c.model, data);
      x = c.tau[i] - data.nle;
      pinocchio::cholesky::solve(c.model, data, x);
      return Vector6(x);
    });
  });
}

}  // namespace

void register_pinocchio() {
  register_ref<ReferencePoint::centroid>();
  register_ref<ReferencePoint::offset>();
}

}  // namespace tumble::bench
