// The C++ side of python/tests/test_against_cpp.py: the same computations as the Python tests,
// called directly on the headers, printed as JSON with 17 significant digits, so that the test
// can compare the bindings with C++ to the bit on the same inputs.
//
// Inputs (the test repeats them as the same decimal literals, which both languages round to the
// same doubles): the unit quaternion q0 = (0.5, 0.5, 0.5, 0.5) turned by 0.3 rad about x (below),
// omega0 = (0.3, -0.2, 0.7) rad/s, thetadot from it.

#include <cmath>
#include <cstdio>
#include <string>
#include <tuple>
#include <vector>

#include <Eigen/Geometry>

#include "tumble/integrate.hpp"
#include "tumble/tumble.hpp"

namespace {

std::string num(double x) {
  if (std::isinf(x)) {
    return x > 0 ? "Infinity" : "-Infinity";  // as Python's json reads them
  }
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

template <class Derived> std::string arr(const Eigen::MatrixBase<Derived>& m) {
  std::string s = "[";
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    if (m.cols() > 1)
      s += (i ? ",[" : "[");
    else if (i)
      s += ",";
    for (Eigen::Index j = 0; j < m.cols(); ++j) {
      s += (j ? "," : "") + num(m(i, j));
    }
    if (m.cols() > 1) s += "]";
  }
  return s + "]";
}

Eigen::Quaterniond q0() {
  // (0.5, 0.5, 0.5, 0.5) then a turn of 0.3 rad about the body x axis: a generic attitude.
  const Eigen::Quaterniond a(0.5, 0.5, 0.5, 0.5);
  const Eigen::Quaterniond b(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()));
  return a * b;
}

template <class P> std::string orientation() {
  const Eigen::Vector3d omega(0.3, -0.2, 0.7);
  const auto th = P::from_quaternion(q0());
  const auto thd = P::thetadot(th, omega);
  const Eigen::Quaterniond q = P::to_quaternion(th);
  const Eigen::Quaterniond in = q0();
  return "\"" + std::string(P::name) +
         "\": {\"q0\": " + arr(Eigen::Vector4d(in.w(), in.x(), in.y(), in.z())) +
         ", \"theta\": " + arr(th) + ", \"R\": " + arr(P::rotation(th)) +
         ", \"G\": " + arr(P::G(th)) + ", \"thetadot\": " + arr(thd) +
         ", \"Gdot_thetadot\": " + arr(P::Gdot_thetadot(th, thd)) +
         ", \"omega\": " + arr(P::omega(th, thd)) +
         ", \"quaternion\": " + arr(Eigen::Vector4d(q.w(), q.x(), q.y(), q.z())) +
         ", \"singularity_distance\": " + num(P::singularity_distance(th)) + "}";
}

template <class... P> std::string orientations() {
  std::string s;
  ((s += (s.empty() ? "" : ", ") + orientation<P>()), ...);
  return "{" + s + "}";
}

/// A body of P framed at Ref: M, f_v, Q and accelerations for a wrench, T, momenta.
template <class P, tumble::ReferencePoint Ref> std::string body(const std::string& key) {
  using B = tumble::RigidBody<P, Ref>;
  const auto mp = tumble::MassProperties<>::about_centroid(
      2.5, (Eigen::Matrix3d() << 0.3, 0.01, 0.02, 0.01, 0.4, 0.03, 0.02, 0.03, 0.5).finished(),
      Ref == tumble::ReferencePoint::centroid ? Eigen::Vector3d::Zero()
                                              : Eigen::Vector3d(0.1, -0.05, 0.2));
  const B b = [&] {
    if constexpr (B::fixed) {
      return B(mp, Eigen::Vector3d(0.0, 0.0, 1.0));
    } else {
      return B(mp);
    }
  }();
  const auto th = P::from_quaternion(q0());
  const auto thd = P::thetadot(th, Eigen::Vector3d(0.3, -0.2, 0.7));
  typename B::Coords q, qd;
  if constexpr (B::fixed) {
    q << th;
    qd << thd;
  } else {
    q << 0.1, 0.2, 0.3, th;
    qd << -0.4, 0.5, 0.6, thd;
  }
  const tumble::Wrench<> w{Eigen::Vector3d(1.0, -2.0, 3.0), Eigen::Vector3d(0.1, 0.2, -0.3)};
  return "\"" + key + "\": {\"q\": " + arr(q) + ", \"qdot\": " + arr(qd) +
         ", \"M\": " + arr(b.mass_matrix(q)) + ", \"fv\": " + arr(b.centrifugal_coriolis(q, qd)) +
         ", \"Q\": " + arr(b.generalized_force(q, w)) +
         ", \"qddot\": " + arr(b.accelerations(q, qd, w)) +
         ", \"T\": " + num(b.kinetic_energy(q, qd)) + ", \"p\": " + arr(b.linear_momentum(q, qd)) +
         ", \"h\": " + arr(b.angular_momentum(q, qd)) + "}";
}

/// The tumbling body of the README through the front door: I = diag(1, 2, 3) kg m^2,
/// omega0 = (0.1, 2, 0.05) rad/s, 101 outputs over 50 s, tolerances 1e-10.
template <class P> std::string tumbling() {
  using Body = tumble::RigidBody<P>;
  tumble::Scene<tumble::Bodies<Body>> scene;
  scene.add(
      Body(tumble::MassProperties<>::about_centroid(1.0, Eigen::Vector3d(1, 2, 3).asDiagonal())),
      {.omega = {0.1, 2.0, 0.05}});
  std::vector<double> times;
  for (int k = 0; k <= 100; ++k) times.push_back(0.5 * k);
  std::string ys;
  const tumble::AutoStatistics st = tumble::integrate(
      scene, 0.0, times,
      [&](double, const tumble::SceneState& s) { ys += (ys.empty() ? "" : ", ") + arr(s.y); },
      {.rtol = 1e-10, .atol = 1e-10});
  return "\"" + std::string(P::name) + "\": {\"y\": [" + ys +
         "], \"steps\": " + std::to_string(st.steps) +
         ", \"rhs_evals\": " + std::to_string(st.rhs_evals) +
         ", \"chart_switches\": " + std::to_string(st.chart_switches) + ", \"method\": \"" +
         tumble::name(st.method()) + "\"}";
}

}  // namespace

int main() {
  using namespace tumble;
  using RP = ReferencePoint;
  std::printf("{\"orientation\": %s,\n",
              orientations<EulerXYZ, EulerXZY, EulerYXZ, EulerYZX, EulerZXY, EulerZYX, EulerXYX,
                           EulerXZX, EulerYXY, EulerYZY, EulerZXZ, EulerZYZ, EulerParameters,
                           RodriguesParameters, ModifiedRodriguesParameters, RotationVector>()
                  .c_str());
  std::printf(
      "\"body\": {%s, %s, %s, %s},\n",
      body<EulerParameters, RP::centroid>("EulerParameters/centroid").c_str(),
      body<EulerZYX, RP::offset>("EulerZYX/offset").c_str(),
      body<ModifiedRodriguesParameters, RP::offset>("ModifiedRodriguesParameters/offset").c_str(),
      body<RotationVector, RP::fixed_point>("RotationVector/fixed_point").c_str());
  std::printf("\"tumbling\": {%s, %s}}\n", tumbling<EulerParameters>().c_str(),
              tumbling<EulerZYX>().c_str());
}
