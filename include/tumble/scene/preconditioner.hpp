#pragma once
// A block-Jacobi preconditioner for iterative linear solvers (CVODE's GMRES with BDF):
// P = I - gamma J_D, where J_D is the block diagonal of J = df/dy (jacobian.hpp), one block
// per body ([q_k; qdot_k], or [q_k; v_k; omega_k] in the quasi-velocity form): its own loads and
// the part of its couplings that acts on its own state (a stiff spring between two bodies shows in
// both blocks). LU-factored per body, so setup and solve cost linear in the number of bodies. It
// belongs to the integrator that uses it; sized once for a scene, it then allocates nothing.

#include <span>
#include <stdexcept>
#include <tuple>
#include <type_traits>
#include <vector>

#include <Eigen/Core>
#include <Eigen/LU>

#include "tumble/core/cache_line.hpp"
#include "tumble/core/errors.hpp"
#include "tumble/core/math.hpp"
#include "tumble/scene/jacobian.hpp"
#include "tumble/scene/scene.hpp"
#include "tumble/scene/workspace.hpp"

namespace tumble {

template <class SceneT> class BlockPreconditioner;

template <class... B, class... L, StateForm Form>
class BlockPreconditioner<Scene<Bodies<B...>, Loads<L...>, Form>> {
  using SceneT = Scene<Bodies<B...>, Loads<L...>, Form>;
  static_assert(SceneT::differentiable, "the block preconditioner needs the exact Jacobian blocks");

  /// One block: J_kk and the LU factors of I - gamma J_kk.
  template <class Body> struct Block {
    static constexpr int m = SceneT::template Entry<Body>::block_size;
    Matrix<double, m, m> j = Matrix<double, m, m>::Zero();
    Eigen::PartialPivLU<Matrix<double, m, m>> lu;
    int offset = 0;
  };

 public:
  explicit BlockPreconditioner(const SceneT& scene)
      : owner_(scene.size(), -1),
        data_(scene.body_count(), nullptr),
        start_(scene.body_count(), 0),
        size_(scene.body_count(), 0) {
    scene.for_each_entry([&](const auto& e) {
      using Body = std::remove_cvref_t<decltype(e.body)>;
      auto& blocks = std::get<CacheLineVector<Block<Body>>>(blocks_);
      blocks.emplace_back();
      blocks.back().offset = e.offset;
      for (int r = 0; r < Block<Body>::m; ++r) {
        owner_[e.offset + r] = e.id;
      }
      start_[e.id] = e.offset;
      size_[e.id] = Block<Body>::m;
    });
    // Pointers last: the vectors of blocks no longer grow.
    scene.for_each_entry([&](const auto& e) {
      using Body = std::remove_cvref_t<decltype(e.body)>;
      data_[e.id] = std::get<CacheLineVector<Block<Body>>>(blocks_)[e.local].j.data();
    });
  }
  BlockPreconditioner(const BlockPreconditioner&) = delete;
  BlockPreconditioner& operator=(const BlockPreconditioner&) = delete;
  BlockPreconditioner(BlockPreconditioner&&) noexcept = default;
  BlockPreconditioner& operator=(BlockPreconditioner&&) noexcept = default;

  /// Forms P = I - gamma J_D at (t, y, base) and factors it. When jacobian_ok, the saved J_D is
  /// reused and only gamma changes. Returns true when J_D was recomputed (CVODE's jcur).
  template <class Y>
  bool setup(const SceneT& scene, SceneWorkspace<SceneT>& ws, double t, const Y& y,
             std::span<const Matrix3<double>> base, bool jacobian_ok, double gamma) {
    if (!jacobian_ok) {
      for_each_block([](auto& b) { b.j.setZero(); });
      DiagonalSink sink{this};
      jacobian(scene, ws, t, y, base, sink);
    }
    for_each_block([gamma](auto& b) {
      using M = std::remove_cvref_t<decltype(b.j)>;
      b.lu.compute(M(M::Identity() - gamma * b.j));
    });
    return !jacobian_ok;
  }

  /// z = P^{-1} r, body by body (after setup()). Throws NonFiniteError when the result is not
  /// finite (a singular block).
  template <class R, class Z> void solve(const R& r, Z&& z) const {
    bool finite = true;
    for_each_block([&](const auto& b) {
      constexpr int m = std::remove_cvref_t<decltype(b.j)>::RowsAtCompileTime;
      z.template segment<m>(b.offset) = b.lu.solve(r.template segment<m>(b.offset));
      finite = finite && detail::all_finite_fast(z.template segment<m>(b.offset));
    });
    if (!finite) [[unlikely]] {
      throw NonFiniteError(
          "tumble::BlockPreconditioner::solve: the block preconditioner I - gamma J_D is "
          "singular or the residual is not finite");
    }
  }

 private:
  /// A Jacobian "matrix" that keeps the diagonal blocks only (jacobian() writes through
  /// detail::add_block): the block of body k receives what falls in its rows and its columns.
  struct DiagonalSink {
    BlockPreconditioner* p;
    template <class Derived>
    void add_block(Eigen::Index r0, Eigen::Index c0, const Eigen::MatrixBase<Derived>& b) const {
      const int k = p->owner_[r0];
      if (p->owner_[c0] != k) {
        return;
      }
      const int o = p->start_[k], m = p->size_[k];
      Eigen::Map<Eigen::MatrixXd> jk(p->data_[k], m, m);
      jk.block(r0 - o, c0 - o, b.rows(), b.cols()) += b;
    }
  };

  template <class F> void for_each_block(F&& f) {
    std::apply([&](auto&... lists) { ((for_each_in(lists, f)), ...); }, blocks_);
  }
  template <class F> void for_each_block(F&& f) const {
    std::apply([&](const auto&... lists) { ((for_each_in(lists, f)), ...); }, blocks_);
  }
  template <class V, class F> static void for_each_in(V& list, F& f) {
    for (auto& b : list) {
      f(b);
    }
  }

  std::tuple<CacheLineVector<Block<B>>...> blocks_;  ///< written at each setup: lines of their own
  std::vector<int> owner_;                           ///< per state entry: its body
  std::vector<double*> data_;                        ///< per body: its J_kk
  std::vector<int> start_;                           ///< per body: its offset
  std::vector<int> size_;                            ///< per body: its block size
};

}  // namespace tumble
