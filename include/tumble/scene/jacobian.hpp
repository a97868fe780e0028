#pragma once
// The Jacobian J = df/dy of a scene's right-hand side (rhs.hpp), exact to rounding, by
// forward-mode automatic differentiation in Jet<N> scalars, block by block, never as a whole.
// With f = [qdot; qddot] per body (reference chapter notation; generalized state form):
// - the rows of qdot are [0 I];
// - body k's block d qddot_k / d(q_k, qdot_k) comes from one evaluation of its kinematics, its
//   one-body loads and its accelerations (the Baumgarte term included) with its own state
//   seeded, N = 2 nq_k directions; the wrenches of its couplings enter at their value;
// - a coupling between bodies a and b adds B_a dW_a/d(y_a, y_b) to the rows of qddot_a (and the
//   same for b), where B_a = d qddot_a / dW_a is found in body a's evaluation (6 more directions:
//   qddot is affine in the wrench) and dW_a/d(y_a, y_b) from one evaluation of the coupling with
//   both states seeded (N = 2 nq_a + 2 nq_b).
// In the quasi-velocity form, f = [v; G^{-1} omega; a_c; alpha] per body: the whole block
// d f_k / d(q_k, v_k, omega_k) comes from the body's evaluation (N = nq_k + 6), the gain
// B = d (a_c, alpha) / dW has 6 rows, and a coupling seeds both blocks (N = nq_a + nq_b + 12).
// The cost is linear in the number of bodies and couplings, and nothing is allocated. The chart
// bases are constant between switches, so they enter as constants.
// A mechanism (quasi-velocity form) adds the multipliers' derivative through the constraint solve
// (mechanism_jacobian below): its Jacobian is dense where loops and chains reach, formed in
// scratch of n x n sized at the first call.

#include <cstddef>
#include <span>
#include <tuple>
#include <type_traits>

#include "tumble/core/band_matrix.hpp"
#include "tumble/core/jet.hpp"
#include "tumble/force/concept.hpp"
#include "tumble/force/coupling.hpp"
#include "tumble/scene/detail/body_terms.hpp"
#include "tumble/scene/rhs.hpp"
#include "tumble/scene/scene.hpp"
#include "tumble/scene/workspace.hpp"

namespace tumble {

namespace detail {

/// Where the Jacobian's blocks go, behind one function pointer: a dense matrix, CVODE's band
/// storage or the preconditioner's block diagonal alike. The automatic differentiation below is
/// then compiled once per scene, not once per kind of matrix (which tripled the compiler's time
/// and memory for every scene type integrated with BDF); the price is one indirect call per
/// block, a few per body.
class JacobianSink {
 public:
  using Block = Eigen::Map<const Eigen::MatrixXd, 0, Eigen::OuterStride<>>;

  template <class Jac>
  explicit JacobianSink(Jac& jac)
      : target_(const_cast<void*>(static_cast<const void*>(&jac))), add_(&add_to<Jac>) {}

  /// jac(r0 + i, c0 + j) += b(i, j), through detail::add_block of the target's type.
  template <class Derived>
  void add_block(Eigen::Index r0, Eigen::Index c0, const Eigen::MatrixBase<Derived>& b) const {
    if constexpr (bool(Eigen::internal::traits<Derived>::Flags & Eigen::DirectAccessBit) &&
                  !bool(Eigen::internal::traits<Derived>::Flags & Eigen::RowMajorBit)) {
      add_(target_, r0, c0,
           Block(b.derived().data(), b.rows(), b.cols(), Eigen::OuterStride<>(b.outerStride())));
    } else {
      const typename Derived::PlainObject m = b;  // fixed-size here: no allocation
      add_(target_, r0, c0, Block(m.data(), m.rows(), m.cols(), Eigen::OuterStride<>(m.rows())));
    }
  }

 private:
  template <class Jac>
  static void add_to(void* target, Eigen::Index r0, Eigen::Index c0, const Block& b) {
    detail::add_block(*static_cast<Jac*>(target), r0, c0, b);
  }

  void* target_;
  void (*add_)(void*, Eigen::Index, Eigen::Index, const Block&);
};

/// Body e's one-body loads in scalar S with its kinematics k.
template <class SceneT, class Entry, class S, class K, std::size_t... I>
void one_body_loads([[maybe_unused]] const SceneT& scene, [[maybe_unused]] const Entry& e,
                    [[maybe_unused]] const S& t, [[maybe_unused]] const K& k,
                    [[maybe_unused]] Wrench<S>& w, std::index_sequence<I...>) {
  (
      [&] {
        using Load = std::tuple_element_t<I, typename SceneT::LoadTypes>;
        if constexpr (ForceElement<Load>) {
          const auto& list = scene.template loads<Load>();
          for (const int j : scene.template loads_on<I>(e.id)) {
            list[j].load.apply(t, k, w);
          }
        }
      }(),
      ...);
}

/// Body e's block in Jet<N>: its own state seeded along directions [0, nb) (nb = e.block_size),
/// and when N = nb + 6 the wrench along [nb, nb + 6), giving the gain B = d rates' / dW for its
/// couplings (the rows of qddot, or of [vdot; omegadot]: those that start at e.rates).
/// Generalized form: the rows of qddot (those of qdot are added by the caller). Quasi-velocity
/// form: the whole block, since thetadot = G^{-1} omega depends on theta and omega.
template <int N, class SceneT, class Entry, class Y, class Jac>
void body_block_in(const SceneT& scene, SceneWorkspace<SceneT>& ws, const Entry& e, double t,
                   const Y& y, const Matrix3<double>& base, Jac& jac) {
  using Body = std::remove_cvref_t<decltype(e.body)>;
  constexpr int nq = Body::nq, nr = Entry::rate_size, nb = Entry::block_size;
  using J = Jet<N>;
  const RigidBody<typename Body::Param, Body::reference, J> body(e.body);
  const Vector<J, nq> q = seed<N>(y.template segment<nq>(e.offset), 0);
  const Vector<J, nr> rates = seed<N>(y.template segment<nr>(e.rates), nq);
  BodyKinematics<J, Body::reference> k;
  body_kinematics<Entry::form>(body, q, rates, base, e.needs_rotation, k);
  Wrench<J> w;
  one_body_loads(scene, e, J(t), k, w,
                 std::make_index_sequence<std::tuple_size_v<typename SceneT::LoadTypes>>{});
  if constexpr (N > nb) {
    w.force += seed<N>(ws.wrench(e.id).force, nb);
    w.moment += seed<N>(ws.wrench(e.id).moment, nb + 3);
  }
  if constexpr (Entry::quasi) {
    const Matrix<double, nb, N> d =
        derivatives(body_quasi_rates(body, Vector<J, nq>(q), k, w, ws.stabilize_constraints));
    add_block(jac, e.offset, e.offset, d.template leftCols<nb>());
    if constexpr (N > nb) {
      ws.gain(e.id).template topRows<nr>() = d.template bottomRightCorner<nr, 6>();
    }
  } else {
    const Vector<J, nq> qd = rates;
    const Matrix<double, nq, N> d =
        derivatives(body_accelerations(body, q, qd, k, w, ws.stabilize_constraints));
    add_block(jac, e.rates, e.offset, d.template leftCols<nb>());
    if constexpr (N > nb) {
      ws.gain(e.id).template topRows<nr>() = d.template rightCols<6>();
    }
  }
}

/// The rates' rows of a coupled body (its n = rate_size rows from `rows`) += B dW/d(y_a, y_b)
/// for a wrench W in jets whose directions are [y_a (block of a, na entries); y_b].
template <int n, class SceneT, class J, class Jac>
void add_coupling_rows(SceneWorkspace<SceneT>& ws, int id, int rows, const Wrench<J>& w,
                       int offset_a, int offset_b, int na, Jac& jac) {
  constexpr int N = J::directions;
  Matrix<double, 6, N> dw;
  dw.template topRows<3>() = derivatives(w.force);
  dw.template bottomRows<3>() = derivatives(w.moment);
  const Matrix<double, n, N> r = ws.gain(id).template topRows<n>() * dw;
  add_block(jac, rows, offset_a, r.leftCols(na));
  add_block(jac, rows, offset_b, r.rightCols(N - na));
}

/// Body e's kinematics in Jet<N>, its block of y seeded along the directions [first, first +
/// e.block_size): [q; rates].
template <int N, class Entry, class Y>
auto seeded_kinematics(const Entry& e, const Y& y, const Matrix3<double>& base, int first) {
  using Body = std::remove_cvref_t<decltype(e.body)>;
  constexpr int nq = Body::nq, nr = Entry::rate_size;
  using J = Jet<N>;
  const RigidBody<typename Body::Param, Body::reference, J> body(e.body);
  BodyKinematics<J, Body::reference> k;
  body_kinematics<Entry::form>(
      body, Vector<J, nq>(seed<N>(y.template segment<nq>(e.offset), first)),
      Vector<J, nr>(seed<N>(y.template segment<nr>(e.rates), first + nq)), base, true, k);
  return k;
}

/// One coupling's blocks: dW/d(y_a, y_b) in Jet<na + nb> (the two bodies' blocks), times the
/// gains B_a and B_b.
template <class SceneT, class Load, class EntryA, class EntryB, class Y, class Jac>
void coupling_block(SceneWorkspace<SceneT>& ws, const Load& load, const EntryA& ea,
                    const EntryB& eb, double t, const Y& y, std::span<const Matrix3<double>> base,
                    Jac& jac) {
  constexpr int ra = EntryA::rate_size, rb = EntryB::rate_size;
  constexpr int na = EntryA::block_size, N = na + EntryB::block_size;
  using J = Jet<N>;
  const auto ka = seeded_kinematics<N>(ea, y, base[ea.id], 0);
  const auto kb = seeded_kinematics<N>(eb, y, base[eb.id], na);
  Wrench<J> wa, wb;
  load.apply(J(t), static_cast<const KinematicsView<J>&>(ka),
             static_cast<const KinematicsView<J>&>(kb), wa, wb);
  add_coupling_rows<ra>(ws, ea.id, ea.rates, wa, ea.offset, eb.offset, na, jac);
  add_coupling_rows<rb>(ws, eb.id, eb.rates, wb, ea.offset, eb.offset, na, jac);
}

/// One joint of a mechanism at fixed multipliers, in Jet<N> over its bodies' blocks of y (a's,
/// then b's; a's alone for a joint to the ground): its reactions -J_a^T lambda, -J_b^T lambda
/// differentiated as a coupling's wrenches, times the gains, into `jac`; and the part of
/// D = d(J nudot - gamma)/dy (fixed lambda) that comes from its own rows, dJ nudot - dgamma,
/// into ws.joints().dlambda, with the bodies' accelerations nudot read from f = rhs(y).
template <class SceneT, class Joint, class Y, class Jac, class EntryA, class... EntryB>
void joint_block(SceneWorkspace<SceneT>& ws, const Joint& joint, int row, const Y& y,
                 std::span<const Matrix3<double>> base, Jac& jac, const EntryA& ea,
                 const EntryB&... eb) {
  constexpr int m = Joint::size, na = EntryA::block_size;
  constexpr int N = (na + ... + EntryB::block_size);
  using J = Jet<N>;
  JointScratch& js = ws.joints();
  const auto ka = seeded_kinematics<N>(ea, y, base[ea.id], 0);
  ConstraintRows<J, m> rows;
  Vector<J, m> rate;  // J nudot - gamma
  const auto nudot = [&](const auto& e) {
    return Vector<J, 6>(js.f.template segment<6>(e.rates).template cast<J>());
  };
  if constexpr (sizeof...(EntryB) == 0) {
    joint.evaluate(static_cast<const KinematicsView<J>&>(ka), ground_view<J>(), rows);
    rate = rows.ja * nudot(ea) - rows.gamma;
  } else {
    const auto kb = seeded_kinematics<N>(eb..., y, base[eb.id]..., na);
    joint.evaluate(static_cast<const KinematicsView<J>&>(ka),
                   static_cast<const KinematicsView<J>&>(kb), rows);
    rate = rows.ja * nudot(ea) + rows.jb * (nudot(eb), ...) - rows.gamma;
  }
  const Vector<J, m> lambda = js.lambda.template segment<m>(row).template cast<J>();
  const Matrix<double, m, N> d = derivatives(rate);
  js.dlambda.block(row, ea.offset, m, na) += d.template leftCols<na>();
  const Wrench<J> wa{-(rows.ja.template leftCols<3>().transpose() * lambda),
                     -(rows.ja.template rightCols<3>().transpose() * lambda)};
  if constexpr (sizeof...(EntryB) == 0) {
    add_coupling_rows<6>(ws, ea.id, ea.rates, wa, ea.offset, 0, na, jac);
  } else {
    const int offset_b = (eb.offset, ...);
    js.dlambda.block(row, offset_b, m, N - na) += d.template rightCols<N - na>();
    const Wrench<J> wb{-(rows.jb.template leftCols<3>().transpose() * lambda),
                       -(rows.jb.template rightCols<3>().transpose() * lambda)};
    add_coupling_rows<6>(ws, ea.id, ea.rates, wa, ea.offset, offset_b, na, jac);
    add_coupling_rows<6>(ws, (eb.id, ...), (eb.rates, ...), wb, ea.offset, offset_b, na, jac);
  }
}

/// The Jacobian of a mechanism (quasi-velocity form) into a sink. With the reactions
/// R_i = -J_i^T lambda in body i's wrench, f depends on y directly (K = df/dy at fixed lambda:
/// the bodies' blocks, the couplings, and each joint's rows as a coupling's wrenches) and
/// through lambda, which solves J nudot(y, lambda) = gamma(y). Differentiating that,
///   (J B J^T) dlambda/dy = D,   D = d(J nudot - gamma)/dy at fixed lambda = dJ nudot - dgamma
///                                   + J K_nudot (K's rows of the accelerations),
/// solved column by column with the factorization of the right-hand side's solve (the same
/// basic solution: the frozen and dependent rows get zero), and
///   df_i/dy = K_i - B_i J_i^T dlambda/dy
/// for the rows of body i's accelerations (B_i its gain). The multipliers couple every body of
/// a loop or chain, so the result is dense there: it is formed in n x n scratch, sized at the
/// first call.
template <class SceneT>
void mechanism_jacobian(const SceneT& scene, SceneWorkspace<SceneT>& ws, double t,
                        const Eigen::Map<const Eigen::VectorXd>& y,
                        std::span<const Matrix3<double>> base, const JacobianSink& jac) {
  JointScratch& js = ws.joints();
  const Eigen::Index n = scene.size(), m = scene.constraint_count();
  if (js.jac_fixed.rows() != n) {
    js.jac_fixed.resize(n, n);
    js.dlambda.resize(m, n);
    js.f.resize(n);
    js.column.resize(m);
    js.solved.resize(m);
  }
  // f(y), lambda and the factorization of J B J^T (joints.hpp).
  rhs(scene, ws, t, y, base, js.f);
  // Every body's wrench but its one-body loads (body_block_in adds those in jets): the
  // couplings' and the reactions at lambda; the kinematics are rhs()'s, at the same y.
  scene.for_each_entry([&](const auto& e) { ws.wrench(e.id) = Wrench<double>{}; });
  scene.for_each_load([&](const auto& a) {
    if constexpr (CouplingElement<std::remove_cvref_t<decltype(a.load)>>) {
      a.load.apply(t, ws.view(a.a), ws.view(a.b), ws.wrench(a.a), ws.wrench(a.b));
    }
  });
  add_reactions(ws);
  js.jac_fixed.setZero();
  js.dlambda.setZero();
  scene.for_each_entry([&](const auto& e) {
    constexpr int nb = std::remove_cvref_t<decltype(e)>::block_size;
    bool gain = !js.touches[e.id].empty();
    if constexpr (SceneT::has_couplings) {
      gain = gain || scene.coupled(e.id);
    }
    if (gain) {
      body_block_in<nb + 6>(scene, ws, e, t, y, base[e.id], js.jac_fixed);
    } else {
      body_block_in<nb>(scene, ws, e, t, y, base[e.id], js.jac_fixed);
    }
  });
  if constexpr (SceneT::has_couplings) {
    scene.for_each_load([&](const auto& at) {
      if constexpr (CouplingElement<std::remove_cvref_t<decltype(at.load)>>) {
        scene.visit_entry(at.a, [&](const auto& ea) {
          scene.visit_entry(at.b, [&](const auto& eb) {
            coupling_block(ws, at.load, ea, eb, t, y, base, js.jac_fixed);
          });
        });
      }
    });
  }
  scene.for_each_joint([&](const auto& at) {
    scene.visit_entry(at.a, [&](const auto& ea) {
      if (at.b < 0) {
        joint_block(ws, at.joint, at.row, y, base, js.jac_fixed, ea);
      } else {
        scene.visit_entry(at.b, [&](const auto& eb) {
          joint_block(ws, at.joint, at.row, y, base, js.jac_fixed, ea, eb);
        });
      }
    });
  });
  // D += J K_nudot, K complete now.
  scene.for_each_entry([&](const auto& e) {
    for (const JointScratch::Touch& tc : js.touches[e.id]) {
      const auto& jr = tc.side == 0 ? js.ja : js.jb;
      js.dlambda.middleRows(tc.row, tc.size).noalias() +=
          jr.middleRows(tc.row, tc.size) * js.jac_fixed.middleRows(e.rates, 6);
    }
  });
  for (Eigen::Index c = 0; c < n; ++c) {  // dlambda/dy, column by column
    js.column = js.dlambda.col(c);
    if (js.column.isZero(0.0)) {
      continue;
    }
    joint_solve(js, js.column, js.solved);
    js.dlambda.col(c) = js.solved;
  }
  scene.for_each_entry([&](const auto& e) {
    for (const JointScratch::Touch& tc : js.touches[e.id]) {
      const auto& jr = tc.side == 0 ? js.ja : js.jb;
      for (int r = tc.row; r < tc.row + tc.size; ++r) {
        const Vector<double, 6> response =
            ws.gain(e.id).template topRows<6>() * jr.row(r).transpose();
        js.jac_fixed.middleRows(e.rates, 6).noalias() -= response * js.dlambda.row(r);
      }
    }
  });
  jac.add_block(0, 0, js.jac_fixed);
}

/// The Jacobian of a scene into a sink (see jacobian() below).
template <class SceneT>
void scene_jacobian(const SceneT& scene, SceneWorkspace<SceneT>& ws, double t,
                    const Eigen::Map<const Eigen::VectorXd>& y,
                    std::span<const Matrix3<double>> base, const JacobianSink& jac) {
  if constexpr (SceneT::has_joints) {
    static_assert(SceneT::form == StateForm::quasi_velocities,
                  "a mechanism is differentiated in the quasi-velocity form");
    mechanism_jacobian(scene, ws, t, y, base, jac);
  } else {
    if constexpr (SceneT::has_couplings) {
      // The coupling wrenches at y, in double: the body blocks need their value.
      detail::scene_kinematics(scene, ws, y, base);
      scene.for_each_load([&](const auto& a) {
        if constexpr (CouplingElement<std::remove_cvref_t<decltype(a.load)>>) {
          a.load.apply(t, ws.view(a.a), ws.view(a.b), ws.wrench(a.a), ws.wrench(a.b));
        }
      });
    }
    scene.for_each_entry([&](const auto& e) {
      using E = std::remove_cvref_t<decltype(e)>;
      constexpr int nq = std::remove_cvref_t<decltype(e.body)>::nq, nb = E::block_size;
      if constexpr (!E::quasi) {  // the rows of qdot: [0 I]
        const Matrix<double, nq, nq> identity = Matrix<double, nq, nq>::Identity();
        detail::add_block(jac, e.offset, e.rates, identity);
      }
      if constexpr (SceneT::has_couplings) {
        if (scene.coupled(e.id)) {
          detail::body_block_in<nb + 6>(scene, ws, e, t, y, base[e.id], jac);
          return;
        }
      }
      detail::body_block_in<nb>(scene, ws, e, t, y, base[e.id], jac);
    });
    if constexpr (SceneT::has_couplings) {
      scene.for_each_load([&](const auto& at) {
        if constexpr (CouplingElement<std::remove_cvref_t<decltype(at.load)>>) {
          scene.visit_entry(at.a, [&](const auto& ea) {
            scene.visit_entry(at.b, [&](const auto& eb) {
              detail::coupling_block(ws, at.load, ea, eb, t, y, base, jac);
            });
          });
        }
      });
    }
  }
}

}  // namespace detail

/// Adds J = df/dy at (t, y, base) into `jac`, which must hold zeros on entry: an Eigen dense
/// matrix (or Map) of size() x size(), a BandMatrixMap (entries outside its band are dropped),
/// or any sink with add_block(r0, c0, block). y is any Eigen vector with contiguous storage.
/// Throws NonFiniteError where rhs() would.
template <class SceneT, class Y, class Jac>
requires SceneT::differentiable void jacobian(const SceneT& scene, SceneWorkspace<SceneT>& ws,
                                              double t, const Y& y,
                                              std::span<const Matrix3<double>> base, Jac& jac) {
  const detail::JacobianSink sink(jac);
  detail::scene_jacobian(scene, ws, t, Eigen::Map<const Eigen::VectorXd>(y.data(), y.size()), base,
                         sink);
}

/// The same for an owned state.
template <class SceneT, class Jac>
requires SceneT::differentiable void jacobian(const SceneT& scene, SceneWorkspace<SceneT>& ws,
                                              double t, const SceneState& s, Jac& jac) {
  jacobian(scene, ws, t, s.y, std::span<const Matrix3<double>>(s.base), jac);
}

}  // namespace tumble
