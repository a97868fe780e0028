#pragma once
// Fixtures of the body and force suites (tests/body, tests/force): a random rigid body together
// with a point-mass model of it, random physical states written in any parameterization, the
// test's own evaluation of the chapter's sums (Eqs. 1.8, 1.11, 1.18, 1.19, 1.28, 1.31), AD
// helpers, relative errors and a table of the worst errors met (printed at exit when the
// environment variable TUMBLE_TEST_REPORT is set).
//
// Reference: Chapter 1, "Rigid body" (the "reference chapter").
//
// Everything here is computed from the orientation primitives (P::rotation, P::G,
// P::Gdot_thetadot, P::thetadot, P::from_rotation) and plain Eigen, never from RigidBody or the
// force elements, so that the suites compare the library against an independent evaluation.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "support/catch.hpp"
#include "support/finite_difference.hpp"
#include "support/parameterizations.hpp"
#include "support/random.hpp"
#include "tumble/body/mass_properties.hpp"
#include "tumble/body/rigid_body.hpp"
#include "tumble/core/math.hpp"
#include "tumble/force/gravity.hpp"
#include "tumble/force/loads.hpp"
#include "tumble/force/point_force.hpp"
#include "tumble/force/spring_damper.hpp"
#include "tumble/force/user_force.hpp"

namespace tumble::test {

using Eigen::Matrix3d;
using Eigen::Vector3d;

// --- errors --------------------------------------------------------------------------------------

/// max |a - b| / max |b| (entrywise; relative to the largest entry of the expectation b).
template <class A, class B> double rel_error(const A& a, const B& b) {
  const double scale = std::max(b.cwiseAbs().maxCoeff(), std::numeric_limits<double>::min());
  return (a - b).cwiseAbs().maxCoeff() / scale;
}

/// The worst error per (quantity, parameterization, reference point), printed at exit when
/// TUMBLE_TEST_REPORT is set. Lets the suites report their measured accuracy.
class ErrorReport {
 public:
  static ErrorReport& instance() {
    static ErrorReport report;
    return report;
  }
  void record(const std::string& key, double e) {
    double& w = worst_[key];
    w = std::max(w, e);
  }
  ErrorReport(const ErrorReport&) = delete;
  ErrorReport& operator=(const ErrorReport&) = delete;
  ~ErrorReport() {
    if (std::getenv("TUMBLE_TEST_REPORT") == nullptr) {
      return;
    }
    std::fprintf(stderr, "worst relative errors (quantity | parameterization | reference)\n");
    for (const auto& [key, e] : worst_) {
      std::fprintf(stderr, "  %-60s %.3e\n", key.c_str(), e);
    }
  }

 private:
  ErrorReport() = default;
  std::map<std::string, double> worst_;
};

inline const char* ref_name(ReferencePoint r) {
  return r == ReferencePoint::centroid ? "centroid" : "offset";
}

inline void record_error(std::string_view quantity, std::string_view param, ReferencePoint ref,
                         double e) {
  std::string key(quantity);
  key += " | ";
  key += param;
  key += " | ";
  key += ref_name(ref);
  ErrorReport::instance().record(key, e);
}

// --- AD helpers ----------------------------------------------------------------------------------

/// x with derivative seeds e_{offset + i} among `total` directions.
template <int N>
Eigen::Matrix<AD, N, 1> seeded(const Eigen::Matrix<double, N, 1>& x, int total, int offset = 0) {
  Eigen::Matrix<AD, N, 1> r;
  for (int i = 0; i < N; ++i) {
    r(i) = AD(x(i), total, offset + i);
  }
  return r;
}

template <int N> Eigen::Matrix<AD, N, 1> constant(const Eigen::Matrix<double, N, 1>& x) {
  return x.template cast<AD>();
}

/// The derivative (direction 0) of each entry.
template <class Derived> Eigen::VectorXd derivative(const Eigen::MatrixBase<Derived>& x) {
  Eigen::VectorXd d(x.size());
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    d(i) = x(i).derivatives().size() > 0 ? x(i).derivatives()(0) : 0.0;
  }
  return d;
}

// --- a body and its point-mass model -------------------------------------------------------------

struct PointMass {
  double mass;
  Vector3d rho;  ///< position relative to the reference point c, body components
};

/// A rigid body: mass, inertia about the centroid I_g, centroid r_g relative to the reference
/// point, and six point masses with the same mass, first moment and inertia.
struct BodyModel {
  double mass = 1;
  Matrix3d inertia_centroid = Matrix3d::Identity();
  Vector3d centroid = Vector3d::Zero();
  std::vector<PointMass> cloud;
};

/// The point-mass model: m/6 at r_g +- d_k a_k along each principal axis a_k of I_g, with
/// d_k^2 = 3 (tr(I_g)/2 - I_k) / m. Their second moment along a_k is 2 (m/6) d_k^2 = tr/2 - I_k,
/// so their inertia about the centroid is I_g; the points are symmetric about r_g, so the first
/// moment about c is m r_g. Needs the triangle inequality (tr/2 >= I_k).
inline std::vector<PointMass> point_cloud(double mass, const Vector3d& moments,
                                          const Matrix3d& axes, const Vector3d& centroid) {
  std::vector<PointMass> cloud;
  const double half_trace = 0.5 * moments.sum();
  for (int k = 0; k < 3; ++k) {
    const double d = std::sqrt(3.0 * (half_trace - moments(k)) / mass);
    cloud.push_back({mass / 6, centroid + d * axes.col(k)});
    cloud.push_back({mass / 6, centroid - d * axes.col(k)});
  }
  return cloud;
}

/// The principal moments of inertia of a solid box of mass m and sides (a, b, c) about its
/// centroid: m / 12 (b^2 + c^2, a^2 + c^2, a^2 + b^2).
inline Vector3d box_moments(double mass, const Vector3d& sides) {
  const Vector3d sq = sides.cwiseProduct(sides);
  return mass / 12.0 * Vector3d(sq(1) + sq(2), sq(0) + sq(2), sq(0) + sq(1));
}

/// A random solid box (sides in [side_min, side_max]; principal moments up to 100 apart with
/// the defaults) with random principal axes; the centroid at the reference point (`offset`
/// false) or at a random offset (|r_g| ~ 0.5).
inline BodyModel random_body(Random& rng, bool offset, double side_min = 0.2,
                             double side_max = 2.0) {
  BodyModel b;
  b.mass = rng.uniform(0.5, 5.0);
  const Vector3d sides(rng.uniform(side_min, side_max), rng.uniform(side_min, side_max),
                       rng.uniform(side_min, side_max));
  const Vector3d moments = box_moments(b.mass, sides);
  const Matrix3d axes = rng.rotation();
  b.inertia_centroid = axes * moments.asDiagonal() * axes.transpose();
  b.inertia_centroid = 0.5 * (b.inertia_centroid + b.inertia_centroid.transpose()).eval();
  b.centroid = offset ? rng.vector(0.5) : Vector3d::Zero();
  b.cloud = point_cloud(b.mass, moments, axes, b.centroid);
  return b;
}

inline double cloud_mass(const std::vector<PointMass>& cloud) {
  double m = 0;
  for (const auto& p : cloud) {
    m += p.mass;
  }
  return m;
}
inline Vector3d cloud_first_moment(const std::vector<PointMass>& cloud) {
  Vector3d s = Vector3d::Zero();
  for (const auto& p : cloud) {
    s += p.mass * p.rho;
  }
  return s;
}
/// sum m_i S(rho_i - o)^T S(rho_i - o): the inertia about the body point o (Eq. 1.22).
inline Matrix3d cloud_inertia(const std::vector<PointMass>& cloud, const Vector3d& o) {
  Matrix3d j = Matrix3d::Zero();
  for (const auto& p : cloud) {
    const Matrix3d s = skew(Vector3d(p.rho - o));
    j += p.mass * s.transpose() * s;
  }
  return j;
}

/// Mass properties of `b`: from I_g and r_g (about_centroid) or from the cloud's inertia about c
/// (about_reference), two independent routes to the same body.
template <class S = double>
MassProperties<S> mass_properties(const BodyModel& b, bool via_reference = false) {
  if (via_reference) {
    const Matrix3d ic = cloud_inertia(b.cloud, Vector3d::Zero());
    return MassProperties<S>::about_reference(S(b.mass), ic.cast<S>(), b.centroid.cast<S>());
  }
  return MassProperties<S>::about_centroid(S(b.mass), b.inertia_centroid.cast<S>(),
                                           b.centroid.cast<S>());
}

// --- states --------------------------------------------------------------------------------------

/// One physical state: attitude, angular velocity (body), reference point position and velocity.
struct PhysicalState {
  Matrix3d rotation;
  Vector3d omega;
  Vector3d position;
  Vector3d velocity;
};

/// N independent normal samples times `scale`.
template <int N> Eigen::Matrix<double, N, 1> random_vector(Random& rng, double scale = 1.0) {
  Eigen::Matrix<double, N, 1> v;
  for (int i = 0; i < N; ++i) {
    v(i) = scale * rng.normal();
  }
  return v;
}

inline PhysicalState random_physical_state(Random& rng) {
  return {rng.rotation(), rng.vector(2.0), rng.vector(1.0), rng.vector(1.0)};
}

/// The same state in the coordinates of P: q = [r; from_rotation(R)], qdot = [v; thetadot].
template <class P> struct State {
  using Coords = Eigen::Matrix<double, 3 + P::size, 1>;
  Coords q;
  Coords qdot;
  Matrix3d R;      ///< P::rotation(theta)
  Vector3d omega;  ///< G thetadot
  typename P::template Coords<double> theta() const { return q.template tail<P::size>(); }
  typename P::template Coords<double> thetadot() const { return qdot.template tail<P::size>(); }
};

template <class P> State<P> make_state(const PhysicalState& ps) {
  State<P> s;
  const auto th = P::from_rotation(ps.rotation);
  s.q << ps.position, th;
  s.qdot << ps.velocity, P::thetadot(th, ps.omega);
  s.R = P::rotation(th);
  s.omega = P::G(th) * s.qdot.template tail<P::size>();
  return s;
}

/// A random state at least `min_distance` rad from the nearest singular attitude of P (so that
/// relative errors measure the code, not the conditioning of G at a singularity).
inline constexpr double kMinSingularityDistance = 0.3;

template <class P>
bool usable(const PhysicalState& ps, double min_distance = kMinSingularityDistance) {
  return detail::value(P::singularity_distance(P::from_rotation(ps.rotation))) >= min_distance;
}

template <class P> State<P> random_state(Random& rng) {
  for (;;) {
    const PhysicalState ps = random_physical_state(rng);
    if (usable<P>(ps)) {
      return make_state<P>(ps);
    }
  }
}

/// The projector onto the tangent space of the constraint (identity for three-parameter sets):
/// blockdiag(I, I - p p^T / |p|^2).
template <class P>
Eigen::Matrix<double, 3 + P::size, 3 + P::size> tangent_projector(const State<P>& s) {
  Eigen::Matrix<double, 3 + P::size, 3 + P::size> t;
  t.setIdentity();
  if constexpr (P::has_constraint) {
    const auto p = s.theta();
    t.template bottomRightCorner<P::size, P::size>() -= p * p.transpose() / p.squaredNorm();
  }
  return t;
}

// --- the chapter's sums, evaluated in the test ---------------------------------------------------

/// Eq. (1.8): L_r = [I, -R S(rho) G].
template <class P>
Eigen::Matrix<double, 3, 3 + P::size> jacobian(const State<P>& s, const Vector3d& rho) {
  Eigen::Matrix<double, 3, 3 + P::size> l;
  l.template leftCols<3>().setIdentity();
  l.template rightCols<P::size>() = -s.R * skew(rho) * P::G(s.theta());
  return l;
}

/// Eq. (1.11): a_v = R [S(omega)^2 rho - S(rho) Gdot thetadot].
template <class P> Vector3d velocity_acceleration(const State<P>& s, const Vector3d& rho) {
  const Matrix3d so = skew(s.omega);
  const Vector3d gd = P::Gdot_thetadot(s.theta(), s.thetadot());
  return s.R * (so * so * rho - skew(rho) * gd);
}

/// Eq. (1.18) as a sum over the point masses: M = sum m_i L_i^T L_i.
template <class P>
Eigen::Matrix<double, 3 + P::size, 3 + P::size> cloud_mass_matrix(const BodyModel& b,
                                                                  const State<P>& s) {
  Eigen::Matrix<double, 3 + P::size, 3 + P::size> m;
  m.setZero();
  for (const auto& p : b.cloud) {
    const auto l = jacobian(s, p.rho);
    m += p.mass * l.transpose() * l;
  }
  return m;
}

/// Eq. (1.19) as a sum over the point masses: f_v = -sum m_i L_i^T a_v,i.
template <class P>
typename State<P>::Coords cloud_centrifugal_coriolis(const BodyModel& b, const State<P>& s) {
  typename State<P>::Coords f = State<P>::Coords::Zero();
  for (const auto& p : b.cloud) {
    f -= p.mass * jacobian(s, p.rho).transpose() * velocity_acceleration(s, p.rho);
  }
  return f;
}

/// The magnitude of the sums of Eqs. (1.18), (1.19) without cancellation, entrywise:
/// sum m_i |L_i|^T |L_i| and sum m_i |L_i|^T |a_v,i|. Relative errors of M and f_v are measured
/// against these: an entry that cancels to nearly zero has rounding errors of the size of its
/// terms.
template <class P>
Eigen::Matrix<double, 3 + P::size, 3 + P::size> cloud_mass_matrix_scale(const BodyModel& b,
                                                                        const State<P>& s) {
  Eigen::Matrix<double, 3 + P::size, 3 + P::size> m;
  m.setZero();
  for (const auto& p : b.cloud) {
    const auto l = jacobian(s, p.rho).cwiseAbs().eval();
    m += p.mass * l.transpose() * l;
  }
  return m;
}
template <class P>
typename State<P>::Coords cloud_centrifugal_coriolis_scale(const BodyModel& b, const State<P>& s) {
  typename State<P>::Coords f = State<P>::Coords::Zero();
  for (const auto& p : b.cloud) {
    f += p.mass * jacobian(s, p.rho).cwiseAbs().transpose() *
         velocity_acceleration(s, p.rho).cwiseAbs();
  }
  return f;
}

/// max |a - b| / max scale (entrywise).
template <class A, class B, class C> double scaled_error(const A& a, const B& b, const C& scale) {
  return (a - b).cwiseAbs().maxCoeff() /
         std::max(scale.cwiseAbs().maxCoeff(), std::numeric_limits<double>::min());
}

/// Condition number of the inertia about the centroid (largest / smallest principal moment).
inline double inertia_condition(const BodyModel& b) {
  const Eigen::SelfAdjointEigenSolver<Matrix3d> eig(b.inertia_centroid, Eigen::EigenvaluesOnly);
  return eig.eigenvalues()(2) / eig.eigenvalues()(0);
}

/// Inertial position and velocity of the body point rho (Eqs. 1.1, 1.4).
template <class P> Vector3d point_position(const State<P>& s, const Vector3d& rho) {
  return s.q.template head<3>() + s.R * rho;
}
template <class P> Vector3d point_velocity(const State<P>& s, const Vector3d& rho) {
  return s.qdot.template head<3>() + s.R * s.omega.cross(rho);
}

// --- a set of loads, as force elements and as the test's own sums --------------------------------

/// A user force: linear drag -drag v_c at the reference point and a rotational drag
/// -rot_drag omega (body components). Reads no rotation matrix.
struct Drag {
  double drag;
  double rot_drag;
  template <class S, ReferencePoint Ref>
  Wrench<S> operator()(const S& /*t*/, const BodyKinematics<S, Ref>& k) const {
    Wrench<S> w;
    w.force = -S(drag) * k.velocity;
    w.moment = -S(rot_drag) * k.omega;
    return w;
  }
};

/// Every kind of load tumble has: gravity, a force at a body point in inertial components, one
/// in body components, a moment, a spring-damper to the ground, and a user force.
struct LoadSet {
  Vector3d g{0.0, 0.0, -9.81};
  Vector3d inertial_point, inertial_force;
  Vector3d body_point, body_force;
  Vector3d moment;
  Vector3d spring_point, anchor;
  SpringDamperParameters spring{};
  Drag drag{0.3, 0.2};
};

inline LoadSet random_loads(Random& rng) {
  LoadSet l;
  l.inertial_point = rng.vector(0.7);
  l.inertial_force = rng.vector(5.0);
  l.body_point = rng.vector(0.7);
  l.body_force = rng.vector(5.0);
  l.moment = rng.vector(3.0);
  l.spring_point = rng.vector(0.7);
  l.anchor = rng.vector(2.0) + Vector3d(0, 0, 3);
  l.spring = {rng.uniform(5.0, 50.0), rng.uniform(0.1, 2.0), rng.uniform(0.5, 1.5)};
  return l;
}

/// The force on the body at the spring's end (hand computation: tension k (L - L0) + c Ldot along
/// the unit vector from the body point to the anchor; L0 = 0: k d - c v_p).
inline Vector3d spring_force(const SpringDamperParameters& sd, const Vector3d& p,
                             const Vector3d& vp, const Vector3d& anchor) {
  const Vector3d d = anchor - p;
  if (sd.rest_length == 0) {
    return sd.stiffness * d - sd.damping * vp;
  }
  const double len = d.norm();
  const Vector3d u = d / len;
  const double len_dot = -u.dot(vp);
  return (sd.stiffness * (len - sd.rest_length) + sd.damping * len_dot) * u;
}

/// Forces (inertial) at body points and the total pure moment (body) of a LoadSet.
struct AppliedForces {
  std::vector<std::pair<Vector3d, Vector3d>> forces;  ///< (rho, F inertial)
  Vector3d moment = Vector3d::Zero();
};

/// The loads of `l` on body `b` in the physical state `ps` (R, omega, r_oc, rdot_oc).
inline AppliedForces applied_forces(const BodyModel& b, const PhysicalState& ps, const LoadSet& l) {
  AppliedForces a;
  a.forces.emplace_back(b.centroid, b.mass * l.g);
  a.forces.emplace_back(l.inertial_point, l.inertial_force);
  a.forces.emplace_back(l.body_point, ps.rotation * l.body_force);
  const Vector3d p = ps.position + ps.rotation * l.spring_point;
  const Vector3d vp = ps.velocity + ps.rotation * ps.omega.cross(l.spring_point);
  a.forces.emplace_back(l.spring_point, spring_force(l.spring, p, vp, l.anchor));
  a.forces.emplace_back(Vector3d::Zero(), -l.drag.drag * ps.velocity);
  a.moment = l.moment - l.drag.rot_drag * ps.omega;
  return a;
}

/// The physical state that the coordinates of s describe.
template <class P> PhysicalState physical(const State<P>& s) {
  return {s.R, s.omega, s.q.template head<3>(), s.qdot.template head<3>()};
}

template <class P>
AppliedForces applied_forces(const BodyModel& b, const State<P>& s, const LoadSet& l) {
  return applied_forces(b, physical(s), l);
}

/// Eqs. (1.28), (1.31): Q = sum L_r(rho_j)^T F_j + [0; G^T M].
template <class P>
typename State<P>::Coords generalized_force(const State<P>& s, const AppliedForces& a) {
  typename State<P>::Coords q = State<P>::Coords::Zero();
  for (const auto& [rho, f] : a.forces) {
    q += jacobian(s, rho).transpose() * f;
  }
  q.template tail<P::size>() += P::G(s.theta()).transpose() * a.moment;
  return q;
}

/// Calls fn(elements...) with the force elements of the LoadSet.
template <class Fn> decltype(auto) with_elements(const LoadSet& l, Fn&& fn) {
  const UniformGravity gravity(l.g);
  const PointForce inertial(l.inertial_point, l.inertial_force, Components::inertial);
  const PointForce body(l.body_point, l.body_force, Components::body);
  const BodyMoment moment(l.moment);
  const SpringDamper spring(l.spring_point, l.anchor, l.spring);
  const auto user = make_user_force<false>(l.drag);
  return fn(gravity, inertial, body, moment, spring, user);
}

}  // namespace tumble::test
