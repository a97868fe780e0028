#pragma once
// The scratch space of one evaluation of a scene (Pinocchio's Data to the scene's Model): the
// kinematics the loads read, the wrench each body receives and, for the exact Jacobian of a scene
// with couplings, each body's gain B = d qddot / dW. Sized once for a scene; the right-hand side
// (rhs.hpp) and the Jacobian (jacobian.hpp) then allocate nothing.
//
// A workspace belongs to whoever evaluates (an integrator, a thread, a test): two evaluations at
// once need two workspaces, while the scene itself is shared read-only. It is movable, not
// copyable (the kinematics views point into its own storage), and it fits every scene with the
// same bodies (it holds no pointer into the scene). Its buffers are whole cache lines of their own
// (core/cache_line.hpp): the scratch one thread writes at every evaluation never shares a line
// with another thread's data, wherever the heap puts them.

#include <algorithm>
#include <cstddef>
#include <numeric>
#include <stdexcept>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Cholesky>

#include "tumble/body/kinematics.hpp"
#include "tumble/body/wrench.hpp"
#include "tumble/core/cache_line.hpp"
#include "tumble/core/types.hpp"

namespace tumble {

/// The scratch of a mechanism's constraint solve (scene/joints.hpp), sized once for the scene's
/// m constraint equations and n bodies; empty for a scene without joints.
struct JointScratch {
  /// Where a joint's rows sit and which side of it a body is: the topology the solve walks.
  struct Touch {
    int row;   ///< first row of the joint
    int size;  ///< its number of rows
    int side;  ///< 0: the body is the joint's a, 1: its b
  };
  Eigen::Matrix<double, Eigen::Dynamic, 6> ja, jb;  ///< the velocity Jacobian blocks, m x 6
  Eigen::Matrix<double, 6, Eigen::Dynamic> xa, xb;  ///< B J^T (the bodies' wrench responses)
  Eigen::VectorXd c, gamma, rhs, lambda, work;      ///< m each
  /// J B J^T (Jacobi-scaled), in one of two storages chosen from the topology when the
  /// workspace is made (SceneWorkspace's constructor):
  /// - banded L D L^T, without pivoting, when the band of rows that share a body is narrower than
  ///   the matrix and either the joints form no closed loop (a chain or a tree: no redundant rows
  ///   to choose among; measured 0.6x the dense solve's time from 3 hinged bodies on) or the band
  ///   is narrow (4 (bandwidth + 1) <= m: a long ladder of loops, whose cost then grows linearly);
  /// - dense L D L^T (Eigen's LDLT, lower triangle) otherwise: closed loops, small mechanisms.
  ///   Its pivoting reads the original diagonal, all 1 after the scaling: which rows of a loop
  ///   come out redundant is set by rounding (docs/mechanisms.md).
  int bandwidth = -1;  ///< half-bandwidth of the banded storage, -1: dense
  /// Banded: row i holds A(i, k) for k = i - bandwidth..i in its columns 0..bandwidth (the
  /// diagonal last, a row's band contiguous), then L below the diagonal.
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> band;
  Eigen::VectorXd pivots;  ///< banded: D of L D L^T
  Eigen::VectorXd ld;      ///< banded: the column below the pivot being factored (bandwidth)
  Eigen::MatrixXd a;       ///< dense: m x m
  Eigen::LDLT<Eigen::MatrixXd> ldlt;
  /// Switches to the banded storage of half-bandwidth bw (>= the rows' own, see above).
  void use_band(int bw) {
    const Eigen::Index m = c.size();
    bandwidth = bw;
    band.setZero(m, bw + 1);
    pivots.setZero(m);
    ld.setZero(bw);
    a.resize(0, 0);
  }
  /// Switches to the dense storage (a second method for a test, or a band that would be wide).
  void use_dense() {
    const Eigen::Index m = c.size();
    bandwidth = -1;
    band.resize(0, 0);
    a.setZero(m, m);
    ldlt = Eigen::LDLT<Eigen::MatrixXd>(m);
  }
  Eigen::Matrix<double, 6, Eigen::Dynamic> acc;  ///< per body: [a_c; alpha] (free accelerations)
  Eigen::Matrix<double, 6, Eigen::Dynamic> nu;   ///< per body: [v; omega] (the projection's)
  std::vector<std::vector<Touch>> touches;       ///< per body: the joints on it
  std::vector<int> joint_a, joint_b;             ///< per row: its joint's bodies (-1: ground)
  Eigen::VectorXd y;                             ///< a state's copy (CVODE's projection)
  int rank = 0;                                  ///< the rank the last solve found
  /// The exact Jacobian's scratch (scene/jacobian.hpp), sized at its first use: df/dy at fixed
  /// multipliers (n x n), then d(J nudot - gamma)/dy and dlambda/dy (m x n), the rates.
  Eigen::MatrixXd jac_fixed, dlambda;
  Eigen::VectorXd f, column, solved;
  /// Per row: 1 when the row is frozen as redundant (joints.hpp, freeze_dependent): it carries no
  /// reaction and the solve leaves it out. Empty (the default): every row is solved for, and
  /// the dependent ones are found anew by each factorization.
  std::vector<char> dependent;
};

template <class SceneT> class SceneWorkspace {
 public:
  explicit SceneWorkspace(const SceneT& scene)
      : wrench_(scene.body_count()), views_(scene.body_count(), nullptr) {
    if (scene.body_count() == 0) {
      throw std::invalid_argument("tumble::Scene: the scene has no bodies");
    }
    scene.for_each_entry([&](const auto& e) {
      using Body = std::remove_cvref_t<decltype(e.body)>;
      std::get<SceneT::template group_of<Body>>(kinematics_).emplace_back();
    });
    scene.for_each_entry([&](const auto& e) { views_[e.id] = &kinematics(e); });
    if constexpr (SceneT::has_couplings || SceneT::has_joints) {
      gain_.assign(scene.body_count(), Matrix<double, 7, 6>::Zero());
    }
    if constexpr (SceneT::has_joints) {
      const int m = scene.constraint_count();
      const int n = scene.body_count();
      JointScratch& j = joints_;
      j.ja.setZero(m, 6);
      j.jb.setZero(m, 6);
      j.xa.setZero(6, m);
      j.xb.setZero(6, m);
      j.c.setZero(m);
      j.gamma.setZero(m);
      j.rhs.setZero(m);
      j.lambda.setZero(m);
      j.work.setZero(m);
      j.acc.setZero(6, n);
      j.nu.setZero(6, n);
      j.touches.assign(n, {});
      j.joint_a.assign(m, -1);
      j.joint_b.assign(m, -1);
      j.y.setZero(scene.size());
      scene.for_each_joint([&](const auto& at) {
        constexpr int size = std::remove_cvref_t<decltype(at.joint)>::size;
        j.touches[at.a].push_back({at.row, size, 0});
        if (at.b >= 0) {
          j.touches[at.b].push_back({at.row, size, 1});
        }
        for (int r = at.row; r < at.row + size; ++r) {
          j.joint_a[r] = at.a;
          j.joint_b[r] = at.b;
        }
      });
      int bw = 0;  // the farthest pair of rows that share a body
      for (const auto& touches : j.touches) {
        for (const JointScratch::Touch& p : touches) {
          for (const JointScratch::Touch& q : touches) {
            bw = std::max(bw, p.row + p.size - 1 - q.row);
          }
        }
      }
      // A closed loop: a joint between two bodies (or a body and the ground, node n) that the
      // joints before it already connect.
      const auto ground_node = static_cast<std::size_t>(n);
      std::vector<std::size_t> root(ground_node + 1);
      std::iota(root.begin(), root.end(), std::size_t{0});
      const auto find = [&](std::size_t x) {
        while (root[x] != x) {
          x = root[x] = root[root[x]];
        }
        return x;
      };
      bool loop = false;
      scene.for_each_joint([&](const auto& at) {
        const std::size_t ra = find(static_cast<std::size_t>(at.a));
        const std::size_t rb = find(at.b >= 0 ? static_cast<std::size_t>(at.b) : ground_node);
        loop = loop || ra == rb;
        root[ra] = rb;
      });
      if (bw + 1 < m && (!loop || 4 * (bw + 1) <= m)) {
        j.use_band(bw);
      } else {
        j.use_dense();
      }
    }
  }
  SceneWorkspace(const SceneWorkspace&) = delete;
  SceneWorkspace& operator=(const SceneWorkspace&) = delete;
  SceneWorkspace(SceneWorkspace&&) noexcept = default;  // vectors keep their buffers: views stay
  SceneWorkspace& operator=(SceneWorkspace&&) noexcept = default;

  /// The kinematics of a body (typed: what its one-body loads read).
  template <class Entry> auto& kinematics(const Entry& e) {
    using Body = std::remove_cvref_t<decltype(e.body)>;
    return std::get<SceneT::template group_of<Body>>(kinematics_)[e.local];
  }
  /// The same, untyped (what couplings read).
  [[nodiscard]] const KinematicsView<double>& view(int id) const { return *views_[id]; }
  [[nodiscard]] Wrench<double>& wrench(int id) { return wrench_[id]; }
  /// B = d rates' / dW of a coupled body (or one with joints): d qddot / dW (nq rows), or
  /// d(a_c, alpha) / dW (6 rows) in the quasi-velocity form; rows beyond those unused.
  [[nodiscard]] Matrix<double, 7, 6>& gain(int id) { return gain_[id]; }

  /// The constraint solve's scratch (a mechanism; empty otherwise).
  [[nodiscard]] JointScratch& joints() { return joints_; }
  [[nodiscard]] const JointScratch& joints() const { return joints_; }

  /// Euler parameters: the Baumgarte-stabilized constraint acceleration (Adams) when true, the
  /// plain constrained acceleration (BDF with projection) when false. See rhs.hpp.
  bool stabilize_constraints = true;

 private:
  typename SceneT::KinematicsStorage kinematics_;
  CacheLineVector<Wrench<double>> wrench_;
  CacheLineVector<const KinematicsView<double>*> views_;
  CacheLineVector<Matrix<double, 7, 6>> gain_;
  JointScratch joints_;
};

}  // namespace tumble
