#pragma once
// The constraint solve of a mechanism (a scene with joints, joint/): the multipliers lambda of
//   M nudot = f + W - J^T lambda,   J nudot = gamma
// (the reference chapter's Eq. 1.32, M qddot = f_v + Q, with the constraint forces -C_q^T lambda
// added and C_q qddot = gamma, written in each body's velocities nu = [v; omega], where M is the
// Newton-Euler mass matrix of Eqs. 1.21-1.23 in those velocities and C_q = J G^{-1}, Eq. 1.5),
// solved through the structure: M is block diagonal per body, and its inverse applied to a wrench
// is the body's closed form (RigidBody::wrench_response), so with B_i = M_i^{-1}
//   (J B J^T) lambda = J nudot_free - gamma,   nudot_free = B (f + W)
// is a system of the size of the constraints (the Schur complement), assembled from the pairs of
// joints that share a body. Then each joint adds its reaction -J_a^T lambda, -J_b^T lambda to
// its bodies' wrenches, and the scene's accelerations pass runs as for free bodies.
//
// Redundant constraints (a planar linkage built of spatial joints, Bricard's mechanism) make
// J B J^T singular though the motion exists. The solve is an LDL^T of the Jacobi-scaled matrix
// (banded, or Eigen's LDLT, see JointScratch), with pivots below kRankTolerance (relative) taken
// as zero: the dependent constraints carry no reaction (a basic solution, not the minimum-norm
// one). The accelerations do not depend on that choice: two solutions differ by a null vector of
// J^T.
//
// Which rows are dependent is decided once per run, not at every evaluation: the integrators
// freeze the rows found dependent at the initial state (freeze_dependent; JointScratch::
// dependent), and every later solve leaves exactly those out. Found anew at each evaluation, a
// rank that changes at an isolated position makes the right-hand side jump there: Bricard's
// mechanism (rank 29 of 30 rows) meets a position where a second row becomes dependent for an
// instant, and there the threshold dropped a row whose reaction has a finite limit, so the
// acceleration jumped and the step size collapsed (tests/joint/bricard.test.cpp, A04). With the
// rows frozen, the retained rows stay independent there, as the same mechanism with its last
// hinge made a universal joint (29 independent rows, the same motion) shows. Where the rows
// frozen at the start stop being the redundant ones, the integrators' projection after a step
// shows it, and they decide them again there (assembly.hpp, retained_rows_failed and
// project_mechanism).
//
// The solve reads the kinematics and wrenches the right-hand side's first two passes left in the
// workspace (rhs.hpp), and writes lambda there.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Cholesky>

#include "tumble/body/wrench.hpp"
#include "tumble/joint/concept.hpp"
#include "tumble/scene/scene.hpp"
#include "tumble/scene/workspace.hpp"

namespace tumble::detail {

/// Pivots of the Jacobi-scaled J B J^T below this (relative to the largest) count as zero.
inline constexpr double kRankTolerance = 1e-10;

/// Every joint's rows (C, J_a, J_b, gamma) at the kinematics in ws.
template <class SceneT> void joint_rows(const SceneT& scene, SceneWorkspace<SceneT>& ws) {
  JointScratch& j = ws.joints();
  scene.for_each_joint([&](const auto& at) {
    constexpr int m = std::remove_cvref_t<decltype(at.joint)>::size;
    ConstraintRows<double, m> r;
    at.joint.evaluate(ws.view(at.a), at.b >= 0 ? ws.view(at.b) : ground_view<double>(), r);
    j.c.template segment<m>(at.row) = r.c;
    j.ja.template middleRows<m>(at.row) = r.ja;
    j.jb.template middleRows<m>(at.row) = r.jb;
    j.gamma.template segment<m>(at.row) = r.gamma;
  });
}

/// X = B J^T, column by column: each body's response to the wrench of each row of its joints
/// (zero for the bodies `mobile` excludes, which then do not move in a projection).
template <class SceneT, class Mobile>
void joint_responses(const SceneT& scene, SceneWorkspace<SceneT>& ws, Mobile&& mobile) {
  JointScratch& j = ws.joints();
  scene.for_each_entry([&](const auto& e) {
    for (const JointScratch::Touch& t : j.touches[e.id]) {
      auto& x = t.side == 0 ? j.xa : j.xb;
      if (!mobile(e.id)) {
        x.middleCols(t.row, t.size).setZero();
        continue;
      }
      const auto& jac = t.side == 0 ? j.ja : j.jb;
      for (int r = t.row; r < t.row + t.size; ++r) {
        const Wrench<double> w{jac.row(r).template head<3>().transpose(),
                               jac.row(r).template tail<3>().transpose()};
        const auto vr = e.body.wrench_response(ws.view(e.id).rotation, w);
        x.col(r).template head<3>() = vr.acceleration;
        x.col(r).template tail<3>() = vr.alpha;
      }
    }
  });
}

/// The pivots of the dense factorization that count as zero: |d| <= this.
inline double dense_rank_threshold(const JointScratch& j) {
  const auto& d = j.ldlt.vectorD();
  return kRankTolerance * (d.size() > 0 ? d.cwiseAbs().maxCoeff() : 0.0);
}

/// The smallest pivot of the last joint_schur over its largest: how near the rows it factored are
/// to dependent (the matrix is Jacobi-scaled, and the frozen rows factor with unit pivots; a
/// pivot the rank test took for zero counts as zero). 1 for no rows, 0 for all pivots zero.
inline double pivot_ratio(const JointScratch& j) {
  const auto ratio = [](const auto& d) {
    if (d.size() == 0) {
      return 1.0;
    }
    const double largest = d.cwiseAbs().maxCoeff();
    return largest > 0.0 ? d.cwiseAbs().minCoeff() / largest : 0.0;
  };
  return j.bandwidth >= 0 ? ratio(j.pivots) : ratio(j.ldlt.vectorD());
}

/// The accuracy the right-hand side has at the position of the last joint_schur, as a tolerance
/// an error test can ask of a step from there: eps / pivot_ratio, at most sqrt(eps) (and that for
/// a ratio of 0). The accelerations come out of a solve whose pivots span 1 / pivot_ratio, and
/// rounding alone leaves them about eps / pivot_ratio off, relative. Near a singular position (the
/// N-four-bar with every link on the ground line) the ratio falls about as the square of the
/// time to it (N = 2: 7e-5 at 1.3 ms before, 6e-8 at 0.05 ms), and an explicit step asked for
/// more than this shrinks as it nears the position and never crosses it: the error it measures
/// is that rounding, not its truncation.
/// OdeintIntegrator raises its tolerances to this where it exceeds them; the cap keeps a step that
/// starts at the singular position itself from being accepted with any error.
inline double attainable_tolerance(const JointScratch& j) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  const double cap = std::sqrt(eps), ratio = pivot_ratio(j);
  return ratio * cap > eps ? eps / ratio : cap;
}

/// The rows frozen as dependent (JointScratch::dependent). Their identity rows factor with unit
/// pivots, which the rank counts do not count.
inline int frozen_rows(const JointScratch& j) {
  return static_cast<int>(std::count(j.dependent.begin(), j.dependent.end(), char(1)));
}

/// A = J B J^T from the pairs of joint rows that share a body, Jacobi-scaled (unit diagonal, so
/// that the rank test compares like with like whatever the rows' units, m or rad, and the
/// bodies' masses; a zero diagonal, a row no mobile body can change, stays zero), then factored:
/// Eigen's LDLT of the lower triangle (dense storage) or the banded one (see JointScratch).
inline void joint_schur(JointScratch& j) {
  const bool banded = j.bandwidth >= 0;
  const Eigen::Index m = j.c.size(), bw = j.bandwidth;
  if (banded) {
    j.band.setZero();
  } else {
    j.a.setZero();
  }
  for (const auto& touches : j.touches) {
    for (const JointScratch::Touch& p : touches) {
      const auto& jp = p.side == 0 ? j.ja : j.jb;
      for (const JointScratch::Touch& q : touches) {
        const auto& xq = q.side == 0 ? j.xa : j.xb;
        if (p.row < q.row) {
          continue;  // the upper triangle (joints' rows do not overlap): neither solve reads it
        }
        if (!banded) {
          j.a.block(p.row, q.row, p.size, q.size).noalias() +=
              jp.middleRows(p.row, p.size).lazyProduct(xq.middleCols(q.row, q.size));
          continue;
        }
        // The lower triangle: in row R of p, the columns k of q up to R (band column k - R + bw).
        for (int r = 0; r < p.size; ++r) {
          const Eigen::Index row = p.row + r;
          for (Eigen::Index k = q.row; k < q.row + q.size && k <= row; ++k) {
            j.band(row, k - row + bw) += jp.row(row).dot(xq.col(k).transpose());
          }
        }
      }
    }
  }
  // Rows frozen as dependent: their row and column replaced by the identity's, so that the
  // factorization solves the retained rows alone and the frozen ones get 0 (joint_solve).
  for (std::size_t i = 0; i < j.dependent.size(); ++i) {
    if (!j.dependent[i]) {
      continue;
    }
    const auto r = static_cast<Eigen::Index>(i);
    if (banded) {
      j.band.row(r).setZero();
      for (Eigen::Index row = r + 1; row <= std::min(m - 1, r + bw); ++row) {
        j.band(row, r - row + bw) = 0.0;
      }
      j.band(r, bw) = 1.0;
    } else {
      j.a.row(r).setZero();
      j.a.col(r).setZero();
      j.a(r, r) = 1.0;
    }
  }
  for (Eigen::Index i = 0; i < m; ++i) {
    const double d = banded ? j.band(i, bw) : j.a(i, i);
    j.work(i) = d > 0.0 ? 1.0 / std::sqrt(d) : 0.0;
  }
  if (!banded) {
    j.a = j.work.asDiagonal() * j.a * j.work.asDiagonal();
    j.ldlt.compute(j.a);
    return;
  }
  // Banded L D L^T without pivoting, in place (L below the diagonal of `band`, D in `pivots`),
  // column by column: with pivot d = A(c, c) and the column below it gathered into `ld`, each row
  // r of the band takes A(r, c+1..r) -= A(r, c) A(c+1..r, c) / d, one contiguous update, and then
  // L(r, c) = A(r, c) / d. A is positive semidefinite, so a pivot below the rank tolerance means
  // a dependent row, whose column of L is then zero (a basic solution, as the dense path's).
  for (Eigen::Index i = 0; i < m; ++i) {
    const Eigen::Index k0 = std::max<Eigen::Index>(0, i - bw);
    double* row = j.band.row(i).data() + (k0 - i + bw);
    const double* w = j.work.data() + k0;
    for (Eigen::Index k = 0; k <= i - k0; ++k) {
      row[k] *= j.work(i) * w[k];
    }
  }
  j.rank = -frozen_rows(j);
  double* col = j.ld.data();
  for (Eigen::Index c = 0; c < m; ++c) {
    const double d = j.band(c, bw);
    const bool independent = d > kRankTolerance;
    j.pivots(c) = independent ? d : 0.0;
    j.rank += independent ? 1 : 0;
    const Eigen::Index below = std::min(m - 1 - c, bw);
    for (Eigen::Index t = 0; t < below; ++t) {  // A(c + 1 + t, c), band column bw - 1 - t
      col[t] = j.band(c + 1 + t, bw - 1 - t);
    }
    const double inverse = independent ? 1.0 / d : 0.0;
    for (Eigen::Index t = 0; t < below; ++t) {
      const double l = col[t] * inverse;
      double* row = j.band.row(c + 1 + t).data() + (bw - t);  // A(c + 1 + t, c + 1..)
      for (Eigen::Index k = 0; k <= t; ++k) {
        row[k] -= l * col[k];
      }
      row[-1] = l;
    }
  }
}

/// x solving A x = b through the factorization of joint_schur (A = J B J^T, scaled inside): a
/// basic solution, the dependent rows' unknowns zero (the frozen ones among them). Sets j.rank.
/// x must not alias b.
inline void joint_solve(JointScratch& j, const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  x = j.work.asDiagonal() * b;
  for (std::size_t i = 0; i < j.dependent.size(); ++i) {
    if (j.dependent[i]) {
      x(static_cast<Eigen::Index>(i)) = 0.0;
    }
  }
  if (j.bandwidth >= 0) {
    const Eigen::Index m = x.size(), bw = j.bandwidth;
    for (Eigen::Index i = 1; i < m; ++i) {  // L y = x
      const Eigen::Index k0 = std::max<Eigen::Index>(0, i - bw);
      const double* row = j.band.row(i).data() + (k0 - i + bw);
      double s = x(i);
      for (Eigen::Index k = 0; k < i - k0; ++k) {
        s -= row[k] * x(k0 + k);
      }
      x(i) = s;
    }
    for (Eigen::Index i = 0; i < m; ++i) {  // D z = y
      x(i) = j.pivots(i) > 0.0 ? x(i) / j.pivots(i) : 0.0;
    }
    for (Eigen::Index i = m - 1; i > 0; --i) {  // L^T w = z: row i of L once w(i) is final
      const Eigen::Index k0 = std::max<Eigen::Index>(0, i - bw);
      const double* row = j.band.row(i).data() + (k0 - i + bw);
      const double xi = x(i);
      for (Eigen::Index k = 0; k < i - k0; ++k) {
        x(k0 + k) -= row[k] * xi;
      }
    }
    x = j.work.asDiagonal() * x;
    return;
  }
  x = j.ldlt.transpositionsP() * x;
  j.ldlt.matrixL().solveInPlace(x);
  const auto& d = j.ldlt.vectorD();
  const double tol = dense_rank_threshold(j);
  j.rank = -frozen_rows(j);
  for (Eigen::Index i = 0; i < d.size(); ++i) {
    if (std::abs(d(i)) > tol) {
      x(i) /= d(i);
      ++j.rank;
    } else {
      x(i) = 0.0;
    }
  }
  j.ldlt.matrixU().solveInPlace(x);
  x = j.ldlt.transpositionsP().transpose() * x;
  x = j.work.asDiagonal() * x;
}

/// Freezes as dependent the rows that the last joint_schur, run with no rows frozen, found
/// dependent (pivots below kRankTolerance); returns how many. Every later joint_schur and
/// joint_solve on j leaves them out (see the file comment).
inline int freeze_dependent(JointScratch& j) {
  const Eigen::Index m = j.c.size();
  j.dependent.assign(static_cast<std::size_t>(m), 0);
  int count = 0;
  const auto mark = [&](Eigen::Index row) {
    j.dependent[static_cast<std::size_t>(row)] = 1;
    ++count;
  };
  if (j.bandwidth >= 0) {
    for (Eigen::Index i = 0; i < m; ++i) {
      if (j.pivots(i) == 0.0) {
        mark(i);
      }
    }
    return count;
  }
  // The pivoted factorization P A P^T = L D L^T: position i of D belongs to row perm[i] of A,
  // P the transpositions applied in order (as Eigen's Transpositions * vector does).
  std::vector<Eigen::Index> perm(static_cast<std::size_t>(m));
  for (Eigen::Index i = 0; i < m; ++i) {
    perm[static_cast<std::size_t>(i)] = i;
  }
  const auto& t = j.ldlt.transpositionsP();
  for (Eigen::Index k = 0; k < t.size(); ++k) {
    std::swap(perm[static_cast<std::size_t>(k)], perm[static_cast<std::size_t>(t.coeff(k))]);
  }
  const auto& d = j.ldlt.vectorD();
  const double tol = dense_rank_threshold(j);
  for (Eigen::Index i = 0; i < m; ++i) {
    if (!(std::abs(d(i)) > tol)) {
      mark(perm[static_cast<std::size_t>(i)]);
    }
  }
  return count;
}

/// The rows' rate J nu' for per-body 6-vectors nu' (the columns of `per_body`).
inline void joint_apply(const JointScratch& j, const Eigen::Matrix<double, 6, Eigen::Dynamic>& v,
                        Eigen::VectorXd& out) {
  for (Eigen::Index r = 0; r < out.size(); ++r) {
    double s = j.ja.row(r).dot(v.col(j.joint_a[r]).transpose());
    if (j.joint_b[r] >= 0) {
      s += j.jb.row(r).dot(v.col(j.joint_b[r]).transpose());
    }
    out(r) = s;
  }
}

/// The change of each body's velocities (6-vector columns of `out`, zero for bodies without
/// joints) for the multipliers mu: -B J^T mu.
inline void joint_displacements(const JointScratch& j, const Eigen::VectorXd& mu,
                                Eigen::Matrix<double, 6, Eigen::Dynamic>& out) {
  out.setZero();
  for (Eigen::Index r = 0; r < mu.size(); ++r) {
    out.col(j.joint_a[r]) -= j.xa.col(r) * mu(r);
    if (j.joint_b[r] >= 0) {
      out.col(j.joint_b[r]) -= j.xb.col(r) * mu(r);
    }
  }
}

/// Adds each joint's reaction -J_a^T lambda, -J_b^T lambda (the rows and lambda in ws) to its
/// bodies' wrenches.
template <class SceneT> void add_reactions(SceneWorkspace<SceneT>& ws) {
  const JointScratch& j = ws.joints();
  for (Eigen::Index r = 0; r < j.lambda.size(); ++r) {
    const double l = j.lambda(r);
    Wrench<double>& wa = ws.wrench(j.joint_a[r]);
    wa.force -= j.ja.row(r).template head<3>().transpose() * l;
    wa.moment -= j.ja.row(r).template tail<3>().transpose() * l;
    if (j.joint_b[r] >= 0) {
      Wrench<double>& wb = ws.wrench(j.joint_b[r]);
      wb.force -= j.jb.row(r).template head<3>().transpose() * l;
      wb.moment -= j.jb.row(r).template tail<3>().transpose() * l;
    }
  }
}

/// The constraint forces of a mechanism: after the loads' pass (ws holds every body's kinematics
/// and applied wrench), solves for lambda (kept in ws.joints().lambda) and adds each joint's
/// reaction to its bodies' wrenches.
template <class SceneT> void constraint_forces(const SceneT& scene, SceneWorkspace<SceneT>& ws) {
  JointScratch& j = ws.joints();
  if (scene.constraint_count() == 0) {
    return;
  }
  joint_rows(scene, ws);
  // The bodies' free accelerations nudot_free = B (f + W), in the columns of j.acc.
  scene.for_each_entry([&](const auto& e) {
    if (j.touches[e.id].empty()) {
      return;
    }
    using Body = std::remove_cvref_t<decltype(e.body)>;
    const auto vr = e.body.velocity_rates(Body::Theta::Zero(), ws.kinematics(e), ws.wrench(e.id));
    j.acc.col(e.id).template head<3>() = vr.acceleration;
    j.acc.col(e.id).template tail<3>() = vr.alpha;
  });
  joint_responses(scene, ws, [](int) { return true; });
  joint_schur(j);
  joint_apply(j, j.acc, j.rhs);
  j.rhs -= j.gamma;
  joint_solve(j, j.rhs, j.lambda);
  add_reactions(ws);
}

}  // namespace tumble::detail
