#pragma once
// Joints: ideal constraints between two bodies, or between a body and the ground, in the
// reference chapter's absolute coordinates (every body keeps its own q = [r_oc; theta]).
//
// A joint of `size` M gives, at one instant, from the kinematics of its two bodies (KinematicsView:
// r_oc, R, v = rdot_oc and omega, as loads read them), its rows (ConstraintRows):
//   C(q) = 0                                  the position constraint, M entries;
//   dC/dt = J_a nu_a + J_b nu_b               its velocity Jacobian, one M x 6 block per body,
//                                             in the body's velocities nu = [v (inertial);
//                                             omega (body components)];
//   J_a nudot_a + J_b nudot_b = gamma         the acceleration constraint (d2C/dt2 = 0).
// The blocks are written in nu rather than in qdot: nu is what the Newton-Euler equations of a
// body integrate (RigidBody::velocity_rates), its dual is the wrench (force inertial, moment about
// c in body components, wrench.hpp), so a joint's reaction on body a is the wrench -J_a^T lambda,
// and the same rows serve every parameterization and both state forms (qdot = [v; G^{-1} omega]:
// C_q = J G^{-1}, where the scene needs it). The multipliers lambda come from the scene's solve
// (scene/joints.hpp).
//
// A joint type J provides
//   static constexpr int size;                         number of constraint equations M
//   static constexpr const char* name;                 for messages
//   template <class S> void evaluate(const KinematicsView<S>& a, const KinematicsView<S>& b,
//                                    ConstraintRows<S, size>& rows) const;
// For a joint to the ground, b is the ground (ground_view: at the origin, at rest, R = I), and
// the joint's data for side b are inertial. Joints are built from the primitives below (Haug's
// and Nikravesh's basic constraints), each written once for any scalar type.

#include <cmath>
#include <concepts>
#include <sstream>
#include <stdexcept>
#include <string>

#include "tumble/body/kinematics.hpp"
#include "tumble/core/math.hpp"
#include "tumble/core/types.hpp"

namespace tumble {

/// The constraint rows of a joint at one instant (see the file comment).
template <class S, int M> struct ConstraintRows {
  Vector<S, M> c;      ///< C(q), m or rad-like (dimensionless) per row
  Matrix<S, M, 6> ja;  ///< dC/dnu_a, nu_a = [v_a (inertial); omega_a (body a)]
  Matrix<S, M, 6> jb;  ///< dC/dnu_b
  Vector<S, M> gamma;  ///< J_a nudot_a + J_b nudot_b = gamma
};

template <class J>
concept JointElement = requires(const J& j, const KinematicsView<double>& a,
                                const KinematicsView<double>& b,
                                ConstraintRows<double, J::size>& rows) {
  { J::size } -> std::convertible_to<int>;
  { J::name } -> std::convertible_to<const char*>;
  j.evaluate(a, b, rows);
};

/// The kinematics of the ground: the inertial frame, at rest.
template <class S> [[nodiscard]] const KinematicsView<S>& ground_view() {
  static const KinematicsView<S> g{};
  return g;
}

/// A frame attached to a body (or the ground): its origin r_cp (body components, from the body's
/// reference point c; inertial for the ground) and its axes (columns x, y, z in the same
/// components; z is the joint's axis where it has one).
struct JointFrame {
  Vector3<double> point = Vector3<double>::Zero();
  Matrix3<double> axes = Matrix3<double>::Identity();
};

namespace detail {

/// Rejects a non-finite point.
inline void check_joint_point(const char* joint, const char* what, const Vector3<double>& p) {
  if (!detail::all_finite(p)) {
    throw std::invalid_argument(std::string("tumble::") + joint + ": the " + what +
                                " is not finite");
  }
}

/// Rejects an axis that is not a unit vector (to 1e-9), naming it.
inline void check_joint_axis(const char* joint, const char* what, const Vector3<double>& n) {
  if (!detail::all_finite(n) || std::abs(n.norm() - 1.0) > 1e-9) {
    std::ostringstream os;
    os.precision(17);
    os << "tumble::" << joint << ": the " << what << " must be a unit vector (|n| = " << n.norm()
       << ")";
    throw std::invalid_argument(os.str());
  }
}

/// Rejects frame axes that are not a proper rotation (to 1e-9).
inline void check_joint_frame(const char* joint, const char* what, const JointFrame& f) {
  check_joint_point(joint, what, f.point);
  const double orth = (f.axes.transpose() * f.axes - Matrix3<double>::Identity()).norm();
  if (!detail::all_finite(f.axes) || orth > 1e-9 || f.axes.determinant() < 0) {
    throw std::invalid_argument(std::string("tumble::") + joint + ": the axes of the " + what +
                                " must be a proper rotation matrix (columns x, y, z)");
  }
}

/// A frame with z = axis and x, y completing it (any: the joints that use only z do not care).
inline JointFrame frame_from_axis(const Vector3<double>& point, const Vector3<double>& axis) {
  JointFrame f;
  f.point = point;
  const Vector3<double> z = axis.normalized();
  // The coordinate axis least aligned with z, made orthogonal to it.
  Eigen::Index i = 0;
  z.cwiseAbs().minCoeff(&i);
  Vector3<double> x = Vector3<double>::Unit(i) - z(i) * z;
  x.normalize();
  f.axes.col(0) = x;
  f.axes.col(1) = z.cross(x);
  f.axes.col(2) = z;
  return f;
}

/// What the primitives read of one side of a joint: a point s on it (r_cp, body components) in
/// inertial terms. u = R s, p = r_oc + u, w = R omega (inertial angular velocity),
/// pdot = v + w x u (Eq. 1.4).
template <class S> struct JointSide {
  const KinematicsView<S>& k;
  Vector3<S> u, p, w, pdot;

  JointSide(const KinematicsView<S>& kin, const Vector3<double>& s)
      : k(kin),
        u(kin.rotation * s.template cast<S>()),
        p(kin.position + u),
        w(kin.rotation * kin.omega),
        pdot(kin.velocity + w.cross(u)) {}
};

/// Point coincidence (3 rows from row I): p_a - p_b = 0. dp/dnu = [I, -R S(s)]; the quadratic
/// part of pddot is w x (w x u).
template <int I, class S, int M>
void point_coincidence(const JointSide<S>& a, const Vector3<double>& sa, const JointSide<S>& b,
                       const Vector3<double>& sb, ConstraintRows<S, M>& r) {
  r.c.template segment<3>(I) = a.p - b.p;
  r.ja.template block<3, 3>(I, 0).setIdentity();
  r.ja.template block<3, 3>(I, 3) = -(a.k.rotation * skew(sa.template cast<S>()));
  r.jb.template block<3, 3>(I, 0) = -Matrix3<S>::Identity();
  r.jb.template block<3, 3>(I, 3) = b.k.rotation * skew(sb.template cast<S>());
  r.gamma.template segment<3>(I) = b.w.cross(b.w.cross(b.u)) - a.w.cross(a.w.cross(a.u));
}

/// Perpendicular vectors (1 row at I): h_a . h_b = 0, h_a = R_a x (x fixed in a), h_b = R_b y.
/// dC/dt = (w_a - w_b) . n, n = h_a x h_b; gamma = -(w_a - w_b) . ndot with the rotation rates
/// only (ndot = (w_a x h_a) x h_b + h_a x (w_b x h_b)).
template <int I, class S, int M>
void perpendicular(const JointSide<S>& a, const Vector3<double>& x, const JointSide<S>& b,
                   const Vector3<double>& y, ConstraintRows<S, M>& r) {
  const Vector3<S> ha = a.k.rotation * x.template cast<S>();
  const Vector3<S> hb = b.k.rotation * y.template cast<S>();
  const Vector3<S> n = ha.cross(hb);
  r.c(I) = ha.dot(hb);
  r.ja.row(I).template head<3>().setZero();
  r.ja.row(I).template tail<3>() = (a.k.rotation.transpose() * n).transpose();
  r.jb.row(I).template head<3>().setZero();
  r.jb.row(I).template tail<3>() = -(b.k.rotation.transpose() * n).transpose();
  const Vector3<S> ndot = a.w.cross(ha).cross(hb) + ha.cross(b.w.cross(hb));
  r.gamma(I) = -(a.w - b.w).dot(ndot);
}

/// A vector of a perpendicular to the segment between the joint's points (1 row at I):
/// h_a . d = 0, h_a = R_a x, d = p_b - p_a. With e = d + u_a = p_b - r_oc,a:
///   dC/dt = -h_a . v_a + w_a . (h_a x e) + h_a . v_b + w_b . (u_b x h_a).
template <int I, class S, int M>
void offset_perpendicular(const JointSide<S>& a, const Vector3<double>& x, const JointSide<S>& b,
                          ConstraintRows<S, M>& r) {
  const Vector3<S> ha = a.k.rotation * x.template cast<S>();
  const Vector3<S> d = b.p - a.p;
  const Vector3<S> e = d + a.u;
  r.c(I) = ha.dot(d);
  r.ja.row(I).template head<3>() = -ha.transpose();
  r.ja.row(I).template tail<3>() = (a.k.rotation.transpose() * ha.cross(e)).transpose();
  r.jb.row(I).template head<3>() = ha.transpose();
  r.jb.row(I).template tail<3>() = (b.k.rotation.transpose() * b.u.cross(ha)).transpose();
  const Vector3<S> hadot = a.w.cross(ha);
  const Vector3<S> ddot = b.pdot - a.pdot;
  const Vector3<S> quad = a.w.cross(a.u);
  r.gamma(I) = -(a.w.dot(hadot.cross(e) + ha.cross(ddot + quad)) +
                 b.w.dot(b.w.cross(b.u).cross(ha) + b.u.cross(hadot)) +
                 hadot.dot(b.k.velocity - a.k.velocity));
}

/// Distance (1 row at I): |p_a - p_b| - L = 0 (L > 0). With d = p_a - p_b, dhat = d/|d|:
/// dC/dt = dhat . ddot, and J nudot = dhat . gamma_pp - (|ddot|^2 - (dhat . ddot)^2)/|d|, where
/// gamma_pp is the point coincidence's gamma.
template <int I, class S, int M>
void distance(const JointSide<S>& a, const Vector3<double>& sa, const JointSide<S>& b,
              const Vector3<double>& sb, double length, ConstraintRows<S, M>& r) {
  using std::sqrt;
  const Vector3<S> d = a.p - b.p;
  const S dn = sqrt(d.squaredNorm());
  const Vector3<S> dh = d / dn;
  const Vector3<S> dd = a.pdot - b.pdot;
  r.c(I) = dn - S(length);
  r.ja.row(I).template head<3>() = dh.transpose();
  r.ja.row(I).template tail<3>() = -(dh.transpose() * a.k.rotation * skew(sa.template cast<S>()));
  r.jb.row(I).template head<3>() = -dh.transpose();
  r.jb.row(I).template tail<3>() = dh.transpose() * b.k.rotation * skew(sb.template cast<S>());
  const Vector3<S> gpp = b.w.cross(b.w.cross(b.u)) - a.w.cross(a.w.cross(a.u));
  const S along = dh.dot(dd);
  r.gamma(I) = dh.dot(gpp) - (dd.squaredNorm() - along * along) / dn;
}

}  // namespace detail
}  // namespace tumble
