// tumble_bench: the two reference methods that need only CVODE or nothing at all, each run on
// the same problems, timed and sampled exactly as tumble is (common/bench.hpp):
//  - the hand-written CVODE floor: the Euler-parameter equations written out by hand in a plain
//    tumble::Cvode system, with tumble's CVODE settings and constraint handling: what tumble's
//    scene costs above the integrator itself;
//  - fixed-step classical RK4 on the Euler-parameter equations, swept over step sizes.
//
// Euler parameters p = (e0, e1, e2, e3), scalar first, with L(p) = [-e | e0 I - S(e)]:
//   omega = 2 L(p) pdot,  pdot = 1/2 L(p)^T omega                      (reference chapter Eq. 1.5)
//   omegadot = I^-1 (M - omega x I omega)               (Euler's equations, about the centroid)
//   pddot = 1/2 L(p)^T omegadot - |pdot|^2 p     (Eq. 1.10 with Gdot pdot = 0; p.pddot = -|pdot|^2)

#include <algorithm>
#include <cmath>
#include <exception>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "common/bench.hpp"
#include "tumble/cvode.hpp"

namespace tumble::bench {

// ---- the hand-written CVODE floor ------------------------------------------------------------

namespace {

/// R(p) for Euler parameters (body -> inertial), written out.
Eigen::Matrix3d rotation_of(const Eigen::Vector4d& p) {
  const double e0 = p(0), e1 = p(1), e2 = p(2), e3 = p(3);
  Eigen::Matrix3d r;
  r << e0 * e0 + e1 * e1 - e2 * e2 - e3 * e3, 2 * (e1 * e2 - e0 * e3), 2 * (e1 * e3 + e0 * e2),  //
      2 * (e1 * e2 + e0 * e3), e0 * e0 - e1 * e1 + e2 * e2 - e3 * e3, 2 * (e2 * e3 - e0 * e1),   //
      2 * (e1 * e3 - e0 * e2), 2 * (e2 * e3 + e0 * e1), e0 * e0 - e1 * e1 - e2 * e2 + e3 * e3;
  return r;
}

/// omega = 2 L(p) pdot.
Eigen::Vector3d omega_of(const Eigen::Vector4d& p, const Eigen::Vector4d& pd) {
  return {2 * (-p(1) * pd(0) + p(0) * pd(1) + p(3) * pd(2) - p(2) * pd(3)),
          2 * (-p(2) * pd(0) - p(3) * pd(1) + p(0) * pd(2) + p(1) * pd(3)),
          2 * (-p(3) * pd(0) + p(2) * pd(1) - p(1) * pd(2) + p(0) * pd(3))};
}

/// 1/2 L(p)^T w.
Eigen::Vector4d half_lt(const Eigen::Vector4d& p, const Eigen::Vector3d& w) {
  return {0.5 * (-p(1) * w(0) - p(2) * w(1) - p(3) * w(2)),
          0.5 * (p(0) * w(0) - p(3) * w(1) + p(2) * w(2)),
          0.5 * (p(3) * w(0) + p(0) * w(1) - p(1) * w(2)),
          0.5 * (-p(2) * w(0) + p(1) * w(1) + p(0) * w(2))};
}

/// The hand-written system: y = [r_g (3); p (4); v_g (3); pdot (4)], the same 14 coordinates
/// and the same equations as tumble's centroidal Euler-parameter body, with the same
/// constraint handling: projection after each BDF step, the scene's Baumgarte-stabilized
/// constraint acceleration with Adams (scene/scene.hpp), so that the comparison is like for like.
struct HandWrittenSystem {
  Eigen::Vector3d inertia;
  Eigen::Vector3d inverse;
  Eigen::Vector3d gravity;
  bool stabilize = false;

  [[nodiscard]] int size() const { return 14; }

  void rhs(double /*t*/, ConstVectorMap y, VectorMap yd) const {
    const Eigen::Vector4d p = y.segment<4>(3);
    const Eigen::Vector4d pd = y.segment<4>(10);
    const Eigen::Vector3d w = omega_of(p, pd);
    const Eigen::Vector3d wd = -inverse.cwiseProduct(w.cross(inertia.cwiseProduct(w)));
    const double pd2 = pd.squaredNorm();
    Eigen::Vector4d pdd = half_lt(p, wd) - pd2 * p;
    if (stabilize) {
      // p.pddot = -|pdot|^2 - 2 g (p.pdot) - g^2 (|p|^2 - 1) / 2 with g = |omega|, as the scene.
      const double pp = p.squaredNorm();
      const double g2 = w.squaredNorm();
      const double g = std::sqrt(g2);
      const double nu = -(pd2 + 2.0 * g * p.dot(pd) + 0.5 * g2 * (pp - 1.0)) / pp;
      pdd += (nu + pd2) * p;
    }
    yd.segment<3>(0) = y.segment<3>(7);
    yd.segment<4>(3) = pd;
    yd.segment<3>(7) = gravity;
    yd.segment<4>(10) = pdd;
  }

  /// p -> p / |p|, pdot -> pdot - (p.pdot) p, and the error estimate's normal part removed.
  void project(double /*t*/, ConstVectorMap y, VectorMap corr, double /*eps*/,
               VectorMap err) const {
    corr.setZero();
    const Eigen::Vector4d p = y.segment<4>(3);
    const Eigen::Vector4d pd = y.segment<4>(10);
    const Eigen::Vector4d pn = p / p.norm();
    corr.segment<4>(3) = pn - p;
    corr.segment<4>(10) = -pn.dot(pd) * pn;
    if (err.size() > 0) {
      const Eigen::Vector4d ep = err.segment<4>(3);
      const Eigen::Vector4d ev = err.segment<4>(10);
      err.segment<4>(3) = ep - pn.dot(ep) * pn;
      err.segment<4>(10) = ev - pn.dot(ev) * pn;
    }
  }
};

Eigen::Vector4d quaternion_of(const Eigen::Matrix3d& r) {
  const Eigen::Quaterniond q(r);
  Eigen::Vector4d p(q.w(), q.x(), q.y(), q.z());
  return p.normalized();
}

}  // namespace

Run run_handwritten(const Problem& p, const MethodSetting& c, const Timing& timing) {
  Run run;
  run.samples.resize(p.times.size());
  // Initial state: the centroid's position and velocity, p and pdot.
  const Eigen::Vector4d p0 = quaternion_of(p.r0);
  Eigen::VectorXd y0(14);
  y0.segment<3>(0) = p.position0 + p.r0 * p.centroid;
  y0.segment<4>(3) = p0;
  y0.segment<3>(7) = p.velocity0 + p.r0 * p.omega0.cross(p.centroid);
  y0.segment<4>(10) = half_lt(p0, p.omega0);
  CvodeOptions o;
  o.method = c.scheme == Scheme::bdf ? CvodeMethod::bdf : CvodeMethod::adams;
  o.rtol = c.tol;
  o.atol = c.tol;
  o.projection = c.scheme == Scheme::bdf;
  o.fused_vector_operations = c.fused;
  const HandWrittenSystem system{p.inertia, p.inertia.cwiseInverse(), p.gravity,
                                 c.scheme != Scheme::bdf};
  std::vector<double> times;
  try {
    do {
      const Stopwatch watch;
      Cvode<HandWrittenSystem> cvode(system, 0.0, y0, o);
      std::size_t k = 0;
      cvode.integrate(p.times, [&](double, ConstVectorMap y) {
        Sample& s = run.samples[k++];
        const Eigen::Vector4d q = y.segment<4>(3);
        s.rotation = rotation_of(q);
        s.omega = omega_of(q, y.segment<4>(10));
        s.position = y.segment<3>(0) - s.rotation * p.centroid;
        s.velocity = y.segment<3>(7) - s.rotation * s.omega.cross(p.centroid);
      });
      record_time(run, times, watch, timing);
      const CvodeStatistics st = cvode.statistics();
      record_statistics(run, st);
      const Eigen::Vector4d q = cvode.state().segment<4>(3);
      run.constraint_drift = std::abs(q.norm() - 1.0);
    } while (another_rep(timing, times));
  } catch (const std::exception& e) {
    run.ok = false;
    run.error = e.what();
  }
  finish_timing(run, times);
  return run;
}

// ---- fixed-step RK4 ----------------------------------------------------------------------------

namespace {

/// The first-order Euler-parameter equations that fixed-step simulators integrate:
/// x = [r_g (3); v_g (3); p (4); omega (3)], rdot = v, vdot = g, pdot = 1/2 L(p)^T omega,
/// omegadot = I^-1 (-omega x I omega).
using Rk4State = Eigen::Matrix<double, 13, 1>;

struct Rk4System {
  Eigen::Vector3d inertia;
  Eigen::Vector3d inverse;
  Eigen::Vector3d gravity;

  [[nodiscard]] Rk4State operator()(const Rk4State& x) const {
    Rk4State d;
    const Eigen::Vector4d p = x.segment<4>(6);
    const Eigen::Vector3d w = x.segment<3>(10);
    d.segment<3>(0) = x.segment<3>(3);
    d.segment<3>(3) = gravity;
    d.segment<4>(6) = half_lt(p, w);
    d.segment<3>(10) = -inverse.cwiseProduct(w.cross(inertia.cwiseProduct(w)));
    return d;
  }
};

}  // namespace

Run run_rk4(const Problem& p, const MethodSetting& c, const Timing& timing) {
  const int substeps = c.substeps;
  Run run;
  run.samples.resize(p.times.size());
  Rk4State x0;
  x0.segment<3>(0) = p.position0 + p.r0 * p.centroid;
  x0.segment<3>(3) = p.velocity0 + p.r0 * p.omega0.cross(p.centroid);
  x0.segment<4>(6) = quaternion_of(p.r0);
  x0.segment<3>(10) = p.omega0;
  const Rk4System f{p.inertia, p.inertia.cwiseInverse(), p.gravity};
  std::vector<double> times;
  do {
    const Stopwatch watch;
    Rk4State x = x0;
    double t = 0;
    long steps = 0;
    for (std::size_t k = 0; k < p.times.size(); ++k) {
      const double h = (p.times[k] - t) / substeps;
      for (int i = 0; i < substeps; ++i) {
        const Rk4State k1 = f(x);
        const Rk4State k2 = f(x + 0.5 * h * k1);
        const Rk4State k3 = f(x + 0.5 * h * k2);
        const Rk4State k4 = f(x + h * k3);
        x += (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
        x.segment<4>(6).normalize();
      }
      steps += substeps;
      t = p.times[k];
      Sample& s = run.samples[k];
      s.rotation = rotation_of(x.segment<4>(6));
      s.omega = x.segment<3>(10);
      s.position = x.segment<3>(0) - s.rotation * p.centroid;
      s.velocity = x.segment<3>(3) - s.rotation * s.omega.cross(p.centroid);
    }
    record_time(run, times, watch, timing);
    run.steps = steps;
    run.rhs_evals = 4 * steps;
    run.constraint_drift = std::abs(x.segment<4>(6).norm() - 1.0);
  } while (another_rep(timing, times));
  finish_timing(run, times);
  return run;
}

}  // namespace tumble::bench
