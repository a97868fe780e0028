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

#include <cstddef>
#include <stdexcept>
#include <tuple>
#include <utility>
#include <vector>

#include "tumble/body/kinematics.hpp"
#include "tumble/body/wrench.hpp"
#include "tumble/core/cache_line.hpp"
#include "tumble/core/types.hpp"

namespace tumble {

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
    if constexpr (SceneT::has_couplings) {
      gain_.assign(scene.body_count(), Matrix<double, 7, 6>::Zero());
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
  /// B = d rates' / dW of a coupled body: d qddot / dW (nq rows), or d(a_c, alpha) / dW (6 rows)
  /// in the quasi-velocity form; rows beyond those unused.
  [[nodiscard]] Matrix<double, 7, 6>& gain(int id) { return gain_[id]; }

  /// Euler parameters: the Baumgarte-stabilized constraint acceleration (Adams) when true, the
  /// plain constrained acceleration (BDF with projection) when false. See rhs.hpp.
  bool stabilize_constraints = true;

 private:
  typename SceneT::KinematicsStorage kinematics_;
  CacheLineVector<Wrench<double>> wrench_;
  CacheLineVector<const KinematicsView<double>*> views_;
  CacheLineVector<Matrix<double, 7, 6>> gain_;
};

}  // namespace tumble
