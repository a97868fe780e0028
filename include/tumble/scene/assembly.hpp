#pragma once
// A mechanism's state on its constraints (scene/joints.hpp): the projection of positions and
// velocities onto C(q) = 0 and J nu = 0 that the integrators apply after every step, the assembly
// of an initial state from a rough one, the constraint residuals, and the joints' reactions.
//
// Projection, in each body's velocities nu = [v; omega] with the metric of the mass matrix M:
// - positions: Newton on C, each step the smallest displacement in the kinetic-energy norm,
//     delta = -B J^T (J B J^T)^+ C,   B = M^{-1} per body (RigidBody::wrench_response),
//   applied as r_oc += delta_v and theta += P::thetadot(theta, delta_omega) (a small rotation in
//   body components; Euler parameters renormalized), until max |C| <= the tolerance;
// - velocities: nu -= B J^T (J B J^T)^+ J nu, exact in one step (the constraint is linear in nu).
// The Euler-parameter projection (projection.hpp) is the one-constraint case of the same idea and
// is applied first. CVODE's local error estimate is projected with the same map, linearized
// (project_error_estimate).

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "tumble/scene/joints.hpp"
#include "tumble/scene/projection.hpp"
#include "tumble/scene/rhs.hpp"
#include "tumble/scene/scene.hpp"
#include "tumble/scene/workspace.hpp"

namespace tumble {

/// How far a state is from a mechanism's constraints, and where.
struct ConstraintResidual {
  double position = 0.0;  ///< max |C| over all rows (m for points, dimensionless for directions)
  double velocity = 0.0;  ///< max |J nu| (m/s, rad/s)
  int joint = -1;         ///< the joint with the largest |C| (global index), -1 without joints
  int rank = 0;           ///< the rank of J B J^T (< constraint_count(): redundant constraints)
};

/// Options of assemble().
struct AssemblyOptions {
  /// The bodies (ids) that must not move: the rest are placed around them (say, a crank given
  /// its angle and rate).
  std::vector<int> keep;
  /// Stop when max |C| <= tolerance * L, L = max(1 m, the largest |r_oc|) (relative to the
  /// mechanism's size), and the velocities are projected exactly.
  double tolerance = 1e-12;
  int max_iterations = 50;
};

/// What assemble() did.
struct AssemblyReport {
  int iterations = 0;
  ConstraintResidual before;
  ConstraintResidual after;
};

/// The reaction of a joint on its two bodies at one state, each reduced to that body's reference
/// point as loads' wrenches are (wrench.hpp: force inertial, moment about c in body components);
/// on the ground side `on_b` is the reaction on the ground (force inertial, moment about the
/// inertial origin, inertial components).
struct JointReaction {
  Wrench<double> on_a;
  Wrench<double> on_b;
};

namespace detail {

/// The integrators' projection after each step: Newton until max |C| <= this times the length
/// scale (a step leaves |C| at the local error, so one or two iterations), at most this many.
inline constexpr double kJointProjectionTolerance = 1e-13;
inline constexpr int kJointProjectionIterations = 8;
/// A residual above this (m) after the projection is a failure (the step went off the manifold
/// further than Newton can bring it back).
inline constexpr double kJointProjectionFailure = 1e-6;

/// The name and bodies of joint `id`, for messages.
template <class SceneT> std::string describe_joint(const SceneT& scene, int id) {
  std::string out = "joint " + std::to_string(id);
  scene.for_each_joint([&](const auto& at) {
    if (at.id == id) {
      out += std::string(" (") + std::remove_cvref_t<decltype(at.joint)>::name + ", body " +
             std::to_string(at.a) + " to " +
             (at.b >= 0 ? "body " + std::to_string(at.b) : std::string("the ground")) + ")";
    }
  });
  return out;
}

/// max |C| and the joint that has it, from the rows in ws.
template <class SceneT>
void position_residual(const SceneT& scene, const JointScratch& j, ConstraintResidual& r) {
  r.position = 0.0;
  r.joint = -1;
  scene.for_each_joint([&](const auto& at) {
    constexpr int m = std::remove_cvref_t<decltype(at.joint)>::size;
    const double c = j.c.template segment<m>(at.row).cwiseAbs().maxCoeff();
    if (!(c <= r.position)) {  // NaN counts as the worst
      r.position = c;
      r.joint = at.id;
    }
  });
}

/// Every body's velocities nu = [v; omega] (6-vector columns; v = 0 held at a point) from ws.
template <class SceneT>
void body_velocities(const SceneT& scene, const SceneWorkspace<SceneT>& ws,
                     Eigen::Matrix<double, 6, Eigen::Dynamic>& nu) {
  scene.for_each_entry([&](const auto& e) {
    nu.col(e.id).template head<3>() = ws.view(e.id).velocity;
    nu.col(e.id).template tail<3>() = ws.view(e.id).omega;
  });
}

/// Moves each body by the displacement delta (6-vector columns: [dr; dphi], dphi a small rotation
/// in body components).
template <class SceneT, class Y>
void displace(const SceneT& scene, const Eigen::Matrix<double, 6, Eigen::Dynamic>& delta, Y& y) {
  scene.for_each_entry([&](const auto& e) {
    using Body = std::remove_cvref_t<decltype(e.body)>;
    using P = typename Body::Param;
    if constexpr (!Body::fixed) {
      y.template segment<3>(e.offset) += delta.col(e.id).template head<3>();
    }
    const int it = e.offset + e.theta_at;
    typename Body::Theta th = y.template segment<Body::n_theta>(it);
    th += P::thetadot(th, Vector3<double>(delta.col(e.id).template tail<3>()));
    if constexpr (P::has_constraint) {
      th /= th.norm();
    }
    y.template segment<Body::n_theta>(it) = th;
  });
}

/// Writes each body's velocities nu (6-vector columns) into y in the scene's state form.
template <class SceneT, class Y>
void set_velocities(const SceneT& scene, const Eigen::Matrix<double, 6, Eigen::Dynamic>& nu, Y& y) {
  scene.for_each_entry([&](const auto& e) {
    using Body = std::remove_cvref_t<decltype(e.body)>;
    using E = std::remove_cvref_t<decltype(e)>;
    if constexpr (!Body::fixed) {
      y.template segment<3>(e.rates) = nu.col(e.id).template head<3>();
    }
    const Vector3<double> om = nu.col(e.id).template tail<3>();
    if constexpr (E::quasi) {
      y.template segment<3>(e.rates + Body::n_r) = om;
    } else {
      const typename Body::Theta th = y.template segment<Body::n_theta>(e.offset + e.theta_at);
      y.template segment<Body::n_theta>(e.rates + Body::n_r) = Body::Param::thetadot(th, om);
    }
  });
}

/// The length that makes the projection's tolerance relative: max(1 m, the largest |r_oc|).
template <class SceneT> double length_scale(const SceneT& scene, const SceneWorkspace<SceneT>& ws) {
  double l = 1.0;
  scene.for_each_entry([&](const auto& e) { l = std::max(l, ws.view(e.id).position.norm()); });
  return l;
}

/// Freezes a mechanism's redundant rows for a run (joints.hpp, freeze_dependent): the rows that
/// J B J^T at the state (y, base) shows dependent. Returns how many. The integrators call it when
/// they start or restart, so that which rows carry no reaction is decided once, not at every
/// evaluation.
template <class SceneT, class Y>
int freeze_redundant_rows(const SceneT& scene, SceneWorkspace<SceneT>& ws, const Y& y,
                          std::span<const Matrix3<double>> base) {
  JointScratch& j = ws.joints();
  j.dependent.clear();
  if (scene.constraint_count() == 0) {
    return 0;
  }
  scene_kinematics(scene, ws, y, base);
  joint_rows(scene, ws);
  joint_responses(scene, ws, [](int) { return true; });
  joint_schur(j);
  return freeze_dependent(j);
}

/// After project_constraints: true when its result shows that the rows retained as independent
/// (those not frozen as redundant, freeze_redundant_rows) no longer determine the motion well,
/// so that the rows must be decided again at this position:
/// - they are near dependent: the smallest pivot of their factorization at the projected
///   position is below kRetainedPivotRatio of the largest (joints.hpp, pivot_ratio). Bricard's
///   mechanism (A04, 30 rows of rank 29) has no position where all 30 are independent, but which
///   row is the redundant one changes along the motion. With the row frozen at t = 0 the
///   retained rows' ratio stays between 8e-4 and 1e-2 over the first 2 s; with the row frozen at
///   t = 0.15 s (where the front door handed over) it falls through 1e-7 at t = 0.890 s to
///   1.2e-10 at 0.894 s (the rank test counts 1e-10 as zero), and Dormand-Prince's steps stalled
///   there (561 of 1000 attempts rejected). Decided again at such a position, the rows are
///   those an unfrozen factorization finds dependent there. The motion does not depend on the
///   choice (the retained rows span the same rows either way), so a new choice changes the
///   right-hand side only by rounding;
/// - or Newton on them did not converge in kJointProjectionIterations, or the velocities they
///   leave violate some row (the frozen ones included) by more than kRetainedRowsVelocity
///   relative to the largest body velocity: a solve on independent rows meets every row to
///   rounding. (Where the retained rows became dependent between two checks, the velocity
///   residual after the projection grew from 1e-15 to 7e-3 within a few steps,
///   docs/benchmarks/mechanisms.md, 2026-11-27.)
inline constexpr double kRetainedRowsVelocity = 1e-8;
inline constexpr double kRetainedPivotRatio = 1e-6;
inline bool retained_rows_failed(const JointScratch& j, const ConstraintResidual& r,
                                 int iterations) {
  if (j.dependent.empty()) {  // nothing frozen: the rows are found by each factorization
    return false;
  }
  const double scale = j.nu.size() > 0 ? std::max(1.0, j.nu.cwiseAbs().maxCoeff()) : 1.0;
  return iterations >= kJointProjectionIterations || r.velocity > kRetainedRowsVelocity * scale ||
         pivot_ratio(j) < kRetainedPivotRatio;
}

/// The projection of the file comment, in place, for the bodies `mobile(id)` allows to move:
/// Newton until max |C| <= tolerance * length_scale (or max_iterations), then the velocities.
/// Allocates nothing. Returns the residuals after it and the iterations taken in `iterations`.
template <class SceneT, class Y, class Mobile>
ConstraintResidual project_constraints(const SceneT& scene, SceneWorkspace<SceneT>& ws, Y& y,
                                       std::span<const Matrix3<double>> base, double tolerance,
                                       int max_iterations, Mobile&& mobile, int& iterations) {
  JointScratch& j = ws.joints();
  Eigen::Matrix<double, 6, Eigen::Dynamic>& delta = j.acc;  // scratch: no solve is running
  ConstraintResidual res;
  iterations = 0;
  double tol = tolerance;
  for (;;) {
    scene_kinematics(scene, ws, y, base);
    joint_rows(scene, ws);
    position_residual(scene, j, res);
    if (iterations == 0) {
      tol = tolerance * length_scale(scene, ws);
    }
    if (res.position <= tol || iterations >= max_iterations || !std::isfinite(res.position)) {
      break;
    }
    joint_responses(scene, ws, mobile);
    joint_schur(j);
    joint_solve(j, j.c, j.lambda);
    joint_displacements(j, j.lambda, delta);
    displace(scene, delta, y);
    ++iterations;
  }
  // Velocities at the final positions (the rows are those of the last evaluation).
  joint_responses(scene, ws, mobile);
  joint_schur(j);
  body_velocities(scene, ws, j.nu);
  joint_apply(j, j.nu, j.rhs);
  joint_solve(j, j.rhs, j.lambda);
  joint_displacements(j, j.lambda, delta);
  j.nu += delta;
  set_velocities(scene, j.nu, y);
  scene_kinematics(scene, ws, y, base);
  joint_rows(scene, ws);
  body_velocities(scene, ws, j.nu);
  joint_apply(j, j.nu, j.rhs);
  res.velocity = j.rhs.size() > 0 ? j.rhs.cwiseAbs().maxCoeff() : 0.0;
  res.rank = j.rank;
  return res;
}

/// An integrator's projection of y onto a mechanism's joints between steps (both integrators):
/// project_constraints for every body; where its result shows the rows retained as independent
/// failing (retained_rows_failed), the redundant rows are decided again at the projected y
/// (freeze_redundant_rows) and the projection repeated.
template <class SceneT, class Y>
ConstraintResidual project_mechanism(const SceneT& scene, SceneWorkspace<SceneT>& ws, Y& y,
                                     std::span<const Matrix3<double>> base) {
  int iterations = 0;
  const auto project = [&] {
    return project_constraints(
        scene, ws, y, base, kJointProjectionTolerance, kJointProjectionIterations,
        [](int) { return true; }, iterations);
  };
  ConstraintResidual r = project();
  if (retained_rows_failed(ws.joints(), r, iterations)) [[unlikely]] {
    freeze_redundant_rows(scene, ws, y, base);
    r = project();
  }
  return r;
}

/// Removes from a step's local error estimate `err` (in y's coordinates) its components normal
/// to a mechanism's constraints, to first order, right after project_constraints put y on them:
/// the projection of the file comment applied as a linear map to err's displacements
/// [dr; dphi] and, apart, to its velocities [dv; domega], with the rows and the factorization
/// that projection left in ws (no new factorization; allocates nothing). What it removes is what
/// the projection takes out of the step anyway, so it is no error of the projected solution;
/// left in, it need not shrink with the step size (on Andrews' mechanism at 1e-11 it held at
/// 50-100 times the tolerance while CVODE's BDF cut h to 1e-68). CVODE's error projection
/// (CVodeSetProjErrEst) asks for exactly this. The velocity part leaves out the term
/// d(J nu)/dq dq that couples it to the position part: a first-order estimate of an estimate.
template <class SceneT, class Y, class E>
void project_error_estimate(const SceneT& scene, SceneWorkspace<SceneT>& ws, const Y& y, E& err) {
  JointScratch& j = ws.joints();
  if (j.rhs.size() == 0) {
    return;
  }
  Eigen::Matrix<double, 6, Eigen::Dynamic>& d = j.nu;         // err as displacements, velocities
  Eigen::Matrix<double, 6, Eigen::Dynamic>& removed = j.acc;  // scratch: no solve is running
  const auto remove_normal = [&] {
    joint_apply(j, d, j.rhs);
    joint_solve(j, j.rhs, j.lambda);
    joint_displacements(j, j.lambda, removed);  // -B J^T (J B J^T)^+ J d
  };
  // Positions: dr, and dphi from dtheta as omega from thetadot.
  scene.for_each_entry([&](const auto& e) {
    using Body = std::remove_cvref_t<decltype(e.body)>;
    using P = typename Body::Param;
    const typename Body::Theta th = y.template segment<Body::n_theta>(e.offset + e.theta_at);
    d.col(e.id).template head<3>().setZero();
    if constexpr (!Body::fixed) {
      d.col(e.id).template head<3>() = err.template segment<3>(e.offset);
    }
    const typename Body::Theta dth = err.template segment<Body::n_theta>(e.offset + e.theta_at);
    d.col(e.id).template tail<3>() = P::omega(th, dth);
  });
  remove_normal();
  scene.for_each_entry([&](const auto& e) {
    using Body = std::remove_cvref_t<decltype(e.body)>;
    using P = typename Body::Param;
    const typename Body::Theta th = y.template segment<Body::n_theta>(e.offset + e.theta_at);
    if constexpr (!Body::fixed) {
      err.template segment<3>(e.offset) += removed.col(e.id).template head<3>();
    }
    err.template segment<Body::n_theta>(e.offset + e.theta_at) +=
        P::thetadot(th, Vector3<double>(removed.col(e.id).template tail<3>()));
  });
  // Velocities: [dv; domega] (the quasi-velocity form holds them; the generalized form thetadot).
  scene.for_each_entry([&](const auto& e) {
    using Body = std::remove_cvref_t<decltype(e.body)>;
    using P = typename Body::Param;
    using Entry = std::remove_cvref_t<decltype(e)>;
    d.col(e.id).template head<3>().setZero();
    if constexpr (!Body::fixed) {
      d.col(e.id).template head<3>() = err.template segment<3>(e.rates);
    }
    if constexpr (Entry::quasi) {
      d.col(e.id).template tail<3>() = err.template segment<3>(e.rates + Body::n_r);
    } else {
      const typename Body::Theta th = y.template segment<Body::n_theta>(e.offset + e.theta_at);
      const typename Body::Theta dth = err.template segment<Body::n_theta>(e.rates + Body::n_r);
      d.col(e.id).template tail<3>() = P::omega(th, dth);
    }
  });
  remove_normal();
  scene.for_each_entry([&](const auto& e) {
    using Body = std::remove_cvref_t<decltype(e.body)>;
    using P = typename Body::Param;
    using Entry = std::remove_cvref_t<decltype(e)>;
    if constexpr (!Body::fixed) {
      err.template segment<3>(e.rates) += removed.col(e.id).template head<3>();
    }
    const Vector3<double> dom = removed.col(e.id).template tail<3>();
    if constexpr (Entry::quasi) {
      err.template segment<3>(e.rates + Body::n_r) += dom;
    } else {
      const typename Body::Theta th = y.template segment<Body::n_theta>(e.offset + e.theta_at);
      err.template segment<Body::n_theta>(e.rates + Body::n_r) += P::thetadot(th, dom);
    }
  });
}

}  // namespace detail

/// The residuals of a state on a mechanism's constraints.
template <class SceneT>
ConstraintResidual constraint_residual(const SceneT& scene, const SceneStateView& s) {
  ConstraintResidual res;
  if constexpr (SceneT::has_joints) {
    SceneWorkspace<SceneT> ws(scene);
    detail::scene_kinematics(scene, ws, s.y, s.base);
    detail::joint_rows(scene, ws);
    JointScratch& j = ws.joints();
    detail::position_residual(scene, j, res);
    Eigen::Matrix<double, 6, Eigen::Dynamic> nu(6, scene.body_count());
    detail::body_velocities(scene, ws, nu);
    detail::joint_apply(j, nu, j.rhs);
    res.velocity = j.rhs.size() > 0 ? j.rhs.cwiseAbs().maxCoeff() : 0.0;
    detail::joint_responses(scene, ws, [](int) { return true; });
    detail::joint_schur(j);
    detail::joint_solve(j, j.rhs, j.lambda);
    res.rank = j.rank;
  }
  return res;
}

/// Puts a rough initial state of a mechanism onto its constraints (Newton on C, then the
/// velocities; see the file comment), moving only the bodies not in options.keep.
/// \throws std::invalid_argument naming the joint with the largest residual when the constraints
///         cannot be met (the loop does not close, or only kept bodies could close it); the
///         state is then left as it was.
template <class SceneT>
AssemblyReport assemble(const SceneT& scene, SceneState& s, const AssemblyOptions& options = {}) {
  static_assert(SceneT::has_joints, "assemble() is for scenes with joints (Joints<...>)");
  if (s.y.size() != scene.size() || static_cast<int>(s.base.size()) != scene.body_count()) {
    throw std::invalid_argument("tumble::assemble: the state does not fit the scene");
  }
  if (!(options.tolerance > 0.0) || options.max_iterations < 1) {
    throw std::invalid_argument("tumble::assemble: the tolerance must be > 0 and max_iterations "
                                ">= 1");
  }
  std::vector<char> mobile(static_cast<std::size_t>(scene.body_count()), 1);
  for (const int id : options.keep) {
    if (id < 0 || id >= scene.body_count()) {
      throw std::invalid_argument("tumble::assemble: keep names body " + std::to_string(id) +
                                  ", which is not in the scene");
    }
    mobile[static_cast<std::size_t>(id)] = 0;
  }
  AssemblyReport report;
  report.before = constraint_residual(scene, s);
  SceneWorkspace<SceneT> ws(scene);
  Eigen::VectorXd y = s.y;
  if constexpr (SceneT::has_constraints) {
    project_in_place(scene, y);
  }
  detail::project_constraints(
      scene, ws, y, std::span<const Matrix3<double>>(s.base), options.tolerance,
      options.max_iterations, [&](int id) { return mobile[static_cast<std::size_t>(id)] != 0; },
      report.iterations);
  // The kept bodies' blocks bit for bit as given (the Newton steps left them alone but for the
  // renormalization of their Euler parameters); then the residuals and the rank of the whole
  // mechanism, every body mobile.
  double scale = 1.0;
  scene.for_each_entry([&](const auto& e) {
    using E = std::remove_cvref_t<decltype(e)>;
    if (mobile[static_cast<std::size_t>(e.id)] == 0) {
      y.template segment<E::block_size>(e.offset) = s.y.template segment<E::block_size>(e.offset);
    }
    if constexpr (!std::remove_cvref_t<decltype(e.body)>::fixed) {
      scale = std::max(scale, y.template segment<3>(e.offset).norm());
    }
  });
  report.after = constraint_residual(
      scene, SceneStateView(y.data(), y.size(), std::span<const Matrix3<double>>(s.base)));
  if (!(report.after.position <= options.tolerance * scale) ||
      !(report.after.velocity <= 1e-9 * scale * (1.0 + report.before.velocity))) {
    std::ostringstream os;
    os.precision(6);
    os << "tumble::assemble: the constraints cannot be met: "
       << detail::describe_joint(scene, report.after.joint)
       << " is off by |C| = " << report.after.position << " after " << report.iterations
       << " Newton iterations (tolerance " << options.tolerance << "; started at "
       << report.before.position << ", " << detail::describe_joint(scene, report.before.joint)
       << "); check the joints' points and axes, and that the bodies not kept can close the loop";
    throw std::invalid_argument(os.str());
  }
  s.y = y;
  return report;
}

/// The reaction of joint j on its bodies at the state s and time t (the loads are evaluated at t),
/// from the multipliers of the constraint solve: -J_a^T lambda_j on body a, -J_b^T lambda_j on b.
template <class SceneT, class Joint>
JointReaction joint_reaction(const SceneT& scene, const SceneStateView& s, double t,
                             JointId<Joint> joint) {
  const auto& at = scene.joint(joint);
  SceneWorkspace<SceneT> ws(scene);
  Eigen::VectorXd ydot(scene.size());
  rhs(scene, ws, t, s.y, s.base, ydot);
  const JointScratch& j = ws.joints();
  constexpr int m = Joint::size;
  const auto l = j.lambda.template segment<m>(at.row);
  JointReaction r;
  r.on_a.force = -j.ja.template middleRows<m>(at.row).template leftCols<3>().transpose() * l;
  r.on_a.moment = -j.ja.template middleRows<m>(at.row).template rightCols<3>().transpose() * l;
  r.on_b.force = -j.jb.template middleRows<m>(at.row).template leftCols<3>().transpose() * l;
  r.on_b.moment = -j.jb.template middleRows<m>(at.row).template rightCols<3>().transpose() * l;
  return r;
}

}  // namespace tumble
