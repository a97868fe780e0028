// tumble_bench: Pinocchio's articulated-body algorithm (aba) inside the same CVODE setup as
// tumble, when Pinocchio is installed (`pip install pin`; found by peers/peers.cmake, and
// main/tumble_bench.cmake defines TUMBLE_BENCH_HAVE_PINOCCHIO for this file only). Without it the
// functions below say so and do nothing.
//
// The model: one body on a free-flyer joint, the joint frame at the body's reference point and
// the inertia placed with the centroid's lever, so Pinocchio integrates the same body in the same
// frame as tumble (centroid or offset). Its configuration is q = [position (3, inertial);
// quaternion (x, y, z, w)] and its velocity v = [linear (3); angular (3)], both in the joint
// (body) frame; aba (LOCAL convention) returns dv/dt. The CVODE state is y = [q (7); v (6)] with
//   d(position)/dt = R v_lin,   d(quat)/dt = 1/2 quat (x) (0, omega),   dv/dt = aba(q, v, 0),
// the usual way to put a floating base into an ODE solver. With BDF the quaternion is projected
// onto |quat| = 1 after each step, as tumble does; with Adams it is left alone (its kinematics
// preserve the norm up to the integration error). The attitude is R of the normalized quaternion.

#include <string>
#include <vector>

#include "common/bench.hpp"

#if defined(TUMBLE_BENCH_HAVE_PINOCCHIO) && TUMBLE_BENCH_HAVE_PINOCCHIO

#include <cmath>
#include <exception>

#include <Eigen/Geometry>
#include <pinocchio/algorithm/aba.hpp>
#include <pinocchio/multibody.hpp>

#include "tumble/cvode.hpp"

namespace tumble::bench {

namespace {

struct PinocchioSystem {
  pinocchio::Model model;
  pinocchio::Data data;
  Eigen::VectorXd q = Eigen::VectorXd::Zero(7);
  Eigen::VectorXd v = Eigen::VectorXd::Zero(6);
  Eigen::VectorXd tau = Eigen::VectorXd::Zero(6);

  explicit PinocchioSystem(const Problem& p) {
    model.gravity.linear(p.gravity);
    model.gravity.angular(Eigen::Vector3d::Zero());
    const auto joint = model.addJoint(0, pinocchio::JointModelFreeFlyer(),
                                      pinocchio::SE3::Identity(), "free_flyer");
    model.appendBodyToJoint(
        joint, pinocchio::Inertia(p.mass, p.centroid, Eigen::Matrix3d(p.inertia.asDiagonal())),
        pinocchio::SE3::Identity());
    data = pinocchio::Data(model);
  }
  // Data keeps no pointer into Model, so copies are independent.
  PinocchioSystem(const PinocchioSystem&) = default;
  PinocchioSystem& operator=(const PinocchioSystem&) = default;
  PinocchioSystem(PinocchioSystem&&) = default;
  PinocchioSystem& operator=(PinocchioSystem&&) = default;
  ~PinocchioSystem() = default;

  [[nodiscard]] int size() const { return 13; }

  void rhs(double /*t*/, ConstVectorMap y, VectorMap yd) {
    q = y.head<7>();
    v = y.tail<6>();
    const Eigen::VectorXd& a = pinocchio::aba(model, data, q, v, tau);
    const Eigen::Quaterniond quat(y(6), y(3), y(4), y(5));  // w-first constructor
    const Eigen::Vector3d w = v.tail<3>();
    const Eigen::Vector3d qv(y(3), y(4), y(5));
    yd.head<3>() = quat.toRotationMatrix() * v.head<3>();
    yd.segment<3>(3) = 0.5 * (y(6) * w + qv.cross(w));
    yd(6) = -0.5 * qv.dot(w);
    yd.tail<6>() = a;
  }

  void project(double /*t*/, ConstVectorMap y, VectorMap corr, double /*eps*/,
               VectorMap err) const {
    corr.setZero();
    const Eigen::Vector4d qq = y.segment<4>(3);
    const Eigen::Vector4d qn = qq / qq.norm();
    corr.segment<4>(3) = qn - qq;
    if (err.size() > 0) {
      const Eigen::Vector4d e = err.segment<4>(3);
      err.segment<4>(3) = e - qn.dot(e) * qn;
    }
  }
};

}  // namespace

bool pinocchio_available() { return true; }

std::string pinocchio_description() {
  return std::string("Pinocchio ") + PINOCCHIO_VERSION + " (aba, header-only, same compiler flags)";
}

Run run_pinocchio(const Problem& p, const MethodSetting& c, const Timing& timing) {
  Run run;
  run.samples.resize(p.times.size());
  const Eigen::Quaterniond q0(p.r0);
  Eigen::VectorXd y0(13);
  y0.head<3>() = p.position0;
  y0.segment<4>(3) = Eigen::Vector4d(q0.x(), q0.y(), q0.z(), q0.w()).normalized();
  y0.segment<3>(7) = p.r0.transpose() * p.velocity0;
  y0.segment<3>(10) = p.omega0;
  CvodeOptions o;
  o.method = c.scheme == Scheme::bdf ? CvodeMethod::bdf : CvodeMethod::adams;
  o.rtol = c.tol;
  o.atol = c.tol;
  o.projection = c.scheme == Scheme::bdf;
  o.fused_vector_operations = c.fused;
  std::vector<double> times;
  try {
    do {
      PinocchioSystem system(p);  // model and data: not timed, like building a tumble scene
      const Stopwatch watch;
      Cvode<PinocchioSystem&> cvode(system, 0.0, y0, o);
      std::size_t k = 0;
      cvode.integrate(p.times, [&](double, ConstVectorMap y) {
        Sample& s = run.samples[k++];
        const Eigen::Quaterniond quat = Eigen::Quaterniond(y(6), y(3), y(4), y(5)).normalized();
        s.rotation = quat.toRotationMatrix();
        s.omega = y.segment<3>(10);
        s.position = y.head<3>();
        s.velocity = s.rotation * y.segment<3>(7);
      });
      record_time(run, times, watch, timing);
      const CvodeStatistics st = cvode.statistics();
      record_statistics(run, st);
      run.constraint_drift = std::abs(cvode.state().segment<4>(3).norm() - 1.0);
    } while (another_rep(timing, times));
  } catch (const std::exception& e) {
    run.ok = false;
    run.error = e.what();
  }
  finish_timing(run, times);
  return run;
}

}  // namespace tumble::bench

#else

namespace tumble::bench {

bool pinocchio_available() { return false; }

std::string pinocchio_description() {
  return "Pinocchio not found at configure time (pip install pin, then re-run cmake)";
}

Run run_pinocchio(const Problem& /*p*/, const MethodSetting& /*c*/, const Timing& /*timing*/) {
  Run run;
  run.ok = false;
  run.error = pinocchio_description();
  return run;
}

}  // namespace tumble::bench

#endif
