#pragma once
// A scene: any number of rigid bodies, each with its own parameterization and reference point,
// and the loads on them, integrated as one first-order system y' = f(t, y).
//
// State layout: for each body in the order it was added, [q; qdot] with q = [r_oc; theta]
// (reference chapter Eq. 1.6), so body k occupies 2 nq_k entries starting at offset(k).
//
// Types are resolved at compile time: `Scene<Bodies<B...>, Loads<L...>>` lists the body types
// and the load types the scene may hold. The right-hand side loops over each body type and each
// load type with the concrete type known, so a centroidal body never computes coupling terms, a
// body whose loads need no rotation matrix never forms R, Gdot thetadot is never computed for
// Euler parameters, and an unloaded body never forms its generalized force: the accelerations
// are computed from the wrench directly (rigid_body.hpp). The right-hand side allocates nothing:
// all scratch space is sized by prepare(), which the integrator calls once.
//
// Constraints and singularities (see chart.hpp):
// - Euler parameters keep |p| = 1 by CVODE's projection with BDF (project()), or, with Adams,
//   by a Baumgarte-stabilized constraint acceleration: p.pddot = -|pdot|^2 - 2 g (p.pdot)
//   - g^2 (|p|^2 - 1)/2 with the rate g = |omega| of the body itself, so that the drift decays on
//   the body's own time scale without adding stiffness.
// - Three-parameter sets are re-centered (or MRP shadowed) through root functions.

#include <array>
#include <cmath>
#include <cstddef>
#include <functional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/LU>

#include "tumble/body/rigid_body.hpp"
#include "tumble/core/band_matrix.hpp"
#include "tumble/core/errors.hpp"
#include "tumble/core/jet.hpp"
#include "tumble/force/concept.hpp"
#include "tumble/force/coupling.hpp"
#include "tumble/orientation/euler_parameters.hpp"
#include "tumble/scene/chart.hpp"

namespace tumble {

template <class... B> struct Bodies {};
template <class... L> struct Loads {};

/// The physical initial state of one body.
struct InitialState {
  Vector3<double> position = Vector3<double>::Zero();      ///< r_oc, inertial, m
  Matrix3<double> rotation = Matrix3<double>::Identity();  ///< R, body -> inertial
  Vector3<double> velocity = Vector3<double>::Zero();      ///< rdot_oc, inertial, m/s
  Vector3<double> omega = Vector3<double>::Zero();         ///< angular velocity, body, rad/s
};

/// A typed handle to a body of a scene.
template <class Body> struct BodyId {
  int id = -1;     ///< global index (order of addition)
  int local = -1;  ///< index among the bodies of the same type
};

/// A user event: a root function g(t, y) whose zero crossing (in `direction`: +1 rising, -1
/// falling, 0 both) triggers `action(t, y)`, which may change the state (an impulse, ...).
struct Event {
  std::function<double(double, const Eigen::Ref<const Eigen::VectorXd>&)> function;
  int direction = 0;
  std::function<void(double, Eigen::Ref<Eigen::VectorXd>)> action;
};

namespace detail {
template <class T, class... Ts> constexpr std::size_t index_of() {
  constexpr bool found[] = {std::is_same_v<T, Ts>...};
  for (std::size_t i = 0; i < sizeof...(Ts); ++i) {
    if (found[i]) {
      return i;
    }
  }
  return sizeof...(Ts);
}
template <class T, class... Ts> constexpr bool contains = (std::is_same_v<T, Ts> || ...);
template <class T, class... Ts> constexpr int count() { return (int(std::is_same_v<T, Ts>) + ...); }

/// A load the scene can evaluate in Jet scalars, so that its Jacobian is exact (Scene::jacobian):
/// its apply() is a template over the scalar type, as every tumble load is. A user callable
/// written for double (UserForce/UserCoupling over a function of double) is not, and a scene
/// with one leaves its Jacobian to CVODE's difference quotients.
template <class L>
concept DifferentiableLoad = requires(const L& l, const Jet<2>& t,
                                      const BodyKinematics<Jet<2>, ReferencePoint::centroid>& k0,
                                      const BodyKinematics<Jet<2>, ReferencePoint::offset>& k1,
                                      Wrench<Jet<2>>& w) {
  l.apply(t, k0, w);
  l.apply(t, k1, w);
}
|| requires(const L& l, const Jet<2>& t, const KinematicsView<Jet<2>>& ka,
            const KinematicsView<Jet<2>>& kb, Wrench<Jet<2>>& wa, Wrench<Jet<2>>& wb) {
  l.apply(t, ka, kb, wa, wb);
};
}  // namespace detail

template <class BodyList, class LoadList = Loads<>> class Scene;

template <class... B, class... L> class Scene<Bodies<B...>, Loads<L...>> {
  static_assert(sizeof...(B) > 0, "a Scene needs at least one body type");
  static_assert((std::is_same_v<typename B::Scalar, double> && ...),
                "bodies integrated with CVODE use the scalar type double");
  static_assert(((detail::count<B, B...>() == 1) && ...), "list each body type once");
  static_assert(((detail::count<L, L...>() == 1) && ...), "list each load type once");
  static_assert(((ForceElement<L> || CouplingElement<L>)&&...),
                "each load type must be a ForceElement (one body) or a CouplingElement (two)");

  template <class Body> struct Entry {
    Body body;
    int id;
    int offset;
    Matrix3<double> base = Matrix3<double>::Identity();  ///< chart base R0
    bool has_base = false;
    bool needs_rotation = !Body::at_centroid;
    double switch_distance = Chart<typename Body::Param>::switch_distance();
    long switches = 0;
    BodyKinematics<double, Body::reference> kin{};
  };

  template <class Load> struct Attached {
    Load load;
    int a;
    int b;  ///< second body of a coupling, -1 otherwise
  };

 public:
  using State = Eigen::VectorXd;

  /// True when every load type can be evaluated in Jet scalars: then jacobian() is available.
  static constexpr bool differentiable = (detail::DifferentiableLoad<L> && ...);
  /// True when some load type acts between two bodies.
  static constexpr bool has_couplings = (CouplingElement<L> || ...);

  Scene() = default;
  // Kinematics views point into the body storage: copying would leave them dangling.
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;
  Scene(Scene&&) = default;
  Scene& operator=(Scene&&) = default;

  // --- building -------------------------------------------------------------------------------
  /// Add a body with its physical initial state. Returns its handle.
  /// \throws std::invalid_argument for a non-finite or non-orthonormal initial state.
  template <class Body> BodyId<Body> add(Body body, const InitialState& s = {}) {
    static_assert(detail::contains<Body, B...>, "this body type is not in the scene's Bodies<...>");
    check_initial_state(s);
    using P = typename Body::Param;
    constexpr int nq = Body::nq;
    auto& group = std::get<std::vector<Entry<Body>>>(groups_);
    const int id = body_count();
    Entry<Body> e{std::move(body), id, size_};
    e.kin.mass_properties = nullptr;  // set in prepare(): the vector may still move
    typename P::template Coords<double> theta = P::from_rotation(s.rotation);
    if constexpr (Chart<P>::has_singularity) {
      if (P::singularity_distance(theta) < e.switch_distance) {
        const auto c = Chart<P>::center();
        e.base = s.rotation * P::rotation(c).transpose();
        e.has_base = true;
        theta = c;
      }
    }
    y0_.conservativeResize(size_ + 2 * nq);
    y0_.template segment<3>(size_) = s.position;
    y0_.template segment<Body::n_theta>(size_ + 3) = theta;
    y0_.template segment<3>(size_ + nq) = s.velocity;
    y0_.template segment<Body::n_theta>(size_ + nq + 3) = P::thetadot(theta, s.omega);
    group.push_back(std::move(e));
    size_ += 2 * nq;
    locations_.push_back({detail::index_of<Body, B...>(), static_cast<int>(group.size()) - 1});
    prepared_ = false;
    return BodyId<Body>{id, static_cast<int>(group.size()) - 1};
  }

  /// Attach a one-body load.
  template <class Body, class Load> void add_load(BodyId<Body> body, Load load) {
    static_assert(detail::contains<Load, L...>, "this load type is not in the scene's Loads<...>");
    static_assert(ForceElement<Load>, "a two-body load needs two bodies");
    Entry<Body>& e = entry(body);
    if constexpr (Load::needs_rotation(Body::reference)) {
      e.needs_rotation = true;
    }
    std::get<std::vector<Attached<Load>>>(loads_).push_back({std::move(load), body.id, -1});
  }

  /// Attach a load between two bodies.
  template <class BodyA, class BodyB, class Load>
  void add_load(BodyId<BodyA> a, BodyId<BodyB> b, Load load) {
    static_assert(detail::contains<Load, L...>, "this load type is not in the scene's Loads<...>");
    static_assert(CouplingElement<Load>, "a one-body load takes one body");
    if (a.id == b.id) {
      throw std::invalid_argument("tumble::Scene::add_load: a coupling needs two different bodies");
    }
    entry(a).needs_rotation = true;
    entry(b).needs_rotation = true;
    std::get<std::vector<Attached<Load>>>(loads_).push_back({std::move(load), a.id, b.id});
  }

  /// Add a user event (see Event).
  void add_event(Event event) {
    if (!event.function) {
      throw std::invalid_argument("tumble::Scene::add_event: the event has no root function");
    }
    events_.push_back(std::move(event));
  }

  /// Size the scratch space and bind the kinematics views; called by the integrator. After it,
  /// rhs() allocates nothing.
  void prepare() {
    if (body_count() == 0) {
      throw std::invalid_argument("tumble::Scene: the scene has no bodies");
    }
    wrench_.assign(body_count(), Wrench<double>{});
    views_.assign(body_count(), nullptr);
    for_each_entry([&](auto& e) {
      e.kin.mass_properties = &e.body.mass_properties();
      views_[e.id] = &e.kin;
    });
    chart_bodies_.clear();
    for_each_entry([&](auto& e) {
      using Body = std::remove_cvref_t<decltype(e.body)>;
      if constexpr (Chart<typename Body::Param>::has_singularity) {
        chart_bodies_.push_back(e.id);
      }
    });
    directions_.assign(chart_bodies_.size() + events_.size(), -1);
    for (std::size_t i = 0; i < events_.size(); ++i) {
      directions_[chart_bodies_.size() + i] = events_[i].direction;
    }
    index_loads(std::index_sequence_for<L...>{});
    preconditioner_ready_ = false;
    prepared_ = true;
  }

  // --- sizes and state ------------------------------------------------------------------------
  [[nodiscard]] int size() const { return size_; }
  [[nodiscard]] int body_count() const { return static_cast<int>(locations_.size()); }
  /// The initial state assembled from the bodies' InitialState.
  [[nodiscard]] const State& initial_state() const { return y0_; }
  template <class Body> [[nodiscard]] int offset(BodyId<Body> b) const { return entry(b).offset; }
  template <class Body> [[nodiscard]] const Body& body(BodyId<Body> b) const {
    return entry(b).body;
  }

  /// Use the Baumgarte-stabilized quaternion constraint (Adams) or not (BDF with projection).
  void set_constraint_stabilization(bool on) { stabilize_ = on; }

  // --- the right-hand side --------------------------------------------------------------------
  /// y' = f(t, y). Throws NonFiniteError (recoverable in CVODE) on a non-finite result.
  template <class Y, class Ydot> void rhs(double t, const Y& y, Ydot&& ydot) {
    if (!prepared_) [[unlikely]] {
      prepare();
    }
    for_each_entry([&](auto& e) {
      evaluate_kinematics(e, y);
      wrench_[e.id] = Wrench<double>{};
    });
    apply_loads(t);
    for_each_entry([&](auto& e) { write_derivative(e, y, ydot); });
  }

  // --- the Jacobian ---------------------------------------------------------------------------
  /// Adds J = df/dy at (t, y) into `jac`, which must hold zeros on entry: an Eigen dense matrix
  /// (or Map) of size() x size(), or a BandMatrixMap (entries outside its band are dropped).
  ///
  /// Computed exactly (to rounding) by forward-mode automatic differentiation in Jet<N> scalars,
  /// block by block, never as a whole (reference chapter notation, f = [qdot; qddot] per body):
  /// - the rows of qdot are [0 I];
  /// - body k's block d qddot_k / d(q_k, qdot_k) comes from one evaluation of its kinematics, its
  ///   one-body loads and its accelerations (the Baumgarte term included) with its own state
  ///   seeded, N = 2 nq_k directions; the wrenches of its couplings enter at their value;
  /// - a coupling between bodies a and b adds B_a dW_a/d(y_a, y_b) to the rows of qddot_a (and the
  ///   same for b), where B_a = d qddot_a / dW_a is found in body a's evaluation (6 more
  ///   directions: qddot is affine in the wrench) and dW_a/d(y_a, y_b) from one evaluation of the
  ///   coupling with both states seeded (N = 2 nq_a + 2 nq_b).
  /// The cost is linear in the number of bodies and couplings, and nothing is allocated.
  /// Throws NonFiniteError where rhs() would.
  template <class Y, class Jac>
  requires differentiable void jacobian(double t, const Y& y, Jac& jac) {
    if (!prepared_) [[unlikely]] {
      prepare();
    }
    if constexpr (has_couplings) {
      // The coupling wrenches at y, in double: body blocks need their value.
      for_each_entry([&](auto& e) {
        evaluate_kinematics(e, y);
        wrench_[e.id] = Wrench<double>{};
      });
      (apply_coupling_type<L>(t), ...);
    }
    for_each_entry([&](const auto& e) { body_block(e, t, y, jac); });
    if constexpr (has_couplings) {
      (coupling_blocks<L>(t, y, jac), ...);
    }
  }

  // --- block-Jacobi preconditioner (BDF with GMRES) --------------------------------------------
  /// Allocates the preconditioner's blocks; called by SceneIntegrator for GMRES. After it,
  /// precondition_setup() and precondition_solve() allocate nothing.
  void prepare_preconditioner() requires differentiable {
    if (!prepared_) {
      prepare();
    }
    owner_.assign(size_, -1);
    block_data_.assign(body_count(), nullptr);
    block_start_.assign(body_count(), 0);
    block_size_.assign(body_count(), 0);
    for_each_group_with_blocks([&](auto& entries, auto& blocks) {
      blocks.resize(entries.size());
      for (std::size_t i = 0; i < entries.size(); ++i) {
        const auto& e = entries[i];
        const int m = static_cast<int>(blocks[i].j.rows());
        for (int r = 0; r < m; ++r) {
          owner_[e.offset + r] = e.id;
        }
        block_data_[e.id] = blocks[i].j.data();
        block_start_[e.id] = e.offset;
        block_size_[e.id] = m;
      }
    });
    preconditioner_ready_ = true;
  }

  /// P = I - gamma J_D, where J_D is the block diagonal of J = df/dy: one block [q_k; qdot_k] per
  /// body, its own loads and the part of its couplings that acts on its own state (a stiff spring
  /// between two bodies shows in both blocks). LU-factored per body, so the cost is linear in the
  /// bodies. When jacobian_ok, the saved J_D is reused and only gamma changes. Returns true when
  /// J_D was recomputed (CVODE's jcur).
  template <class Y>
  bool precondition_setup(double t, const Y& y, bool jacobian_ok,
                          double gamma) requires differentiable {
    if (!preconditioner_ready_) [[unlikely]] {
      prepare_preconditioner();
    }
    if (!jacobian_ok) {
      for_each_group_with_blocks([](auto&, auto& blocks) {
        for (auto& b : blocks) {
          b.j.setZero();
        }
      });
      DiagonalSink sink{this};
      jacobian(t, y, sink);
    }
    for_each_group_with_blocks([gamma](auto&, auto& blocks) {
      for (auto& b : blocks) {
        using M = std::remove_cvref_t<decltype(b.j)>;
        b.lu.compute(M(M::Identity() - gamma * b.j));
      }
    });
    return !jacobian_ok;
  }

  /// z = P^{-1} r, body by body (after precondition_setup()). Throws NonFiniteError when the
  /// result is not finite (a singular block).
  template <class R, class Z> void precondition_solve(const R& r, Z&& z) {
    bool finite = true;
    for_each_group_with_blocks([&](const auto& entries, const auto& blocks) {
      for (std::size_t i = 0; i < entries.size(); ++i) {
        constexpr int m = std::remove_cvref_t<decltype(blocks[i].j)>::RowsAtCompileTime;
        const int o = entries[i].offset;
        z.template segment<m>(o) = blocks[i].lu.solve(r.template segment<m>(o));
        finite = finite && detail::all_finite_fast(z.template segment<m>(o));
      }
    });
    if (!finite) [[unlikely]] {
      throw NonFiniteError(
          "tumble::Scene::precondition_solve: the block preconditioner I - gamma J_D is "
          "singular or the residual is not finite");
    }
  }

  // --- constraints and charts -----------------------------------------------------------------
  /// Number of root functions: one per body with a singular chart, then the user events.
  [[nodiscard]] int root_count() const {
    return static_cast<int>(chart_bodies_.size() + events_.size());
  }
  [[nodiscard]] const std::vector<int>& root_directions() const { return directions_; }

  template <class Y, class G> void roots(double t, const Y& y, G&& g) const {
    int i = 0;
    for_each_entry([&](const auto& e) {
      using Body = std::remove_cvref_t<decltype(e.body)>;
      using P = typename Body::Param;
      if constexpr (Chart<P>::has_singularity) {
        const typename P::template Coords<double> th =
            y.template segment<Body::n_theta>(e.offset + 3);
        g[i++] = P::singularity_distance(th) - e.switch_distance;
      }
    });
    for (const Event& ev : events_) {
      g[i++] = ev.function(t, y);
    }
  }

  /// Act on the roots found (`which[i]` nonzero for root i): re-center charts, shadow MRP, run
  /// user actions. Returns true when the state changed (the integrator must restart).
  template <class Y> bool on_root(double t, Y&& y, const int* which) {
    bool changed = false;
    int i = 0;
    for_each_entry([&](auto& e) {
      using Body = std::remove_cvref_t<decltype(e.body)>;
      if constexpr (Chart<typename Body::Param>::has_singularity) {
        if (which[i++] != 0) {
          leave_chart(e, y);
          changed = true;
        }
      }
    });
    for (Event& ev : events_) {
      if (which[i++] != 0 && ev.action) {
        Eigen::Map<Eigen::VectorXd> ym(y.data(), y.size());
        ev.action(t, ym);
        changed = true;
      }
    }
    return changed;
  }

  /// Re-center every chart that is closer to its singularity than its switch distance (used at
  /// start and after the user changes the state). Returns true if any chart changed.
  template <class Y> bool recenter_charts(Y&& y) {
    bool changed = false;
    for_each_entry([&](auto& e) {
      using Body = std::remove_cvref_t<decltype(e.body)>;
      using P = typename Body::Param;
      if constexpr (Chart<P>::has_singularity) {
        const typename P::template Coords<double> th =
            y.template segment<Body::n_theta>(e.offset + 3);
        if (P::singularity_distance(th) < e.switch_distance) {
          leave_chart(e, y);
          changed = true;
        }
      }
    });
    return changed;
  }

  /// The half-bandwidth of the Jacobian df/dy in the scene's state ordering: a body's block
  /// [q; qdot] is dense, and a coupling between bodies a and b links their two blocks. For a chain
  /// of bodies added in order this stays constant as the chain grows, so CVODE's band solver
  /// (with banded difference quotients) costs O(N) per Jacobian and per solve.
  [[nodiscard]] int half_bandwidth() const {
    std::vector<std::pair<int, int>> block(locations_.size());  // [first, last] index per body
    for_each_entry([&](const auto& e) {
      using Body = std::remove_cvref_t<decltype(e.body)>;
      block[e.id] = {e.offset, e.offset + 2 * Body::nq - 1};
    });
    int bw = 0;
    for (const auto& [first, last] : block) {
      bw = std::max(bw, last - first);
    }
    auto couple = [&](int a, int b) {
      bw = std::max({bw, block[b].second - block[a].first, block[a].second - block[b].first});
    };
    std::apply(
        [&](const auto&... attached) {
          (
              [&] {
                for (const auto& at : attached) {
                  if (at.b >= 0) {
                    couple(at.a, at.b);
                  }
                }
              }(),
              ...);
        },
        loads_);
    return bw;
  }

  /// True if the scene has constrained coordinates (Euler parameters).
  [[nodiscard]] static constexpr bool has_constraints() {
    return (B::Param::has_constraint || ...);
  }

  /// The correction `corr` that takes y onto the constraint manifold of the Euler parameters:
  /// p -> p/|p| and pdot -> pdot - (p.pdot) p (the orthogonal projection); zero elsewhere.
  /// When `err` is not empty (the local error estimate) its component normal to the manifold is
  /// removed too, as CVODE's projection expects.
  template <class Y, class C, class E> void project(const Y& y, C&& corr, E&& err) const {
    corr.setZero();
    for_each_entry([&](const auto& e) {
      using Body = std::remove_cvref_t<decltype(e.body)>;
      if constexpr (Body::Param::has_constraint) {
        const int ip = e.offset + 3, iv = e.offset + Body::nq + 3;
        const Vector4<double> p = y.template segment<4>(ip);
        const Vector4<double> pd = y.template segment<4>(iv);
        const Vector4<double> pn = p / p.norm();
        corr.template segment<4>(ip) = pn - p;
        corr.template segment<4>(iv) = -pn.dot(pd) * pn;
        if (err.size() > 0) {
          const Vector4<double> ep = err.template segment<4>(ip);
          const Vector4<double> ev = err.template segment<4>(iv);
          err.template segment<4>(ip) = ep - pn.dot(ep) * pn;
          err.template segment<4>(iv) = ev - pn.dot(ev) * pn;
        }
      }
    });
  }

  /// Total number of chart switches (re-centerings and MRP shadow switches).
  [[nodiscard]] long chart_switches() const {
    long n = 0;
    for_each_entry([&](const auto& e) { n += e.switches; });
    return n;
  }
  template <class Body> [[nodiscard]] long chart_switches(BodyId<Body> b) const {
    return entry(b).switches;
  }

  // --- physical quantities of a state ---------------------------------------------------------
  /// R of body b in state y (chart base included).
  template <class Body, class Y>
  [[nodiscard]] Matrix3<double> rotation(BodyId<Body> b, const Y& y) const {
    const Entry<Body>& e = entry(b);
    const Matrix3<double> r = Body::Param::rotation(theta_of(e, y));
    return e.has_base ? Matrix3<double>(e.base * r) : r;
  }
  /// omega of body b, body components.
  template <class Body, class Y>
  [[nodiscard]] Vector3<double> omega(BodyId<Body> b, const Y& y) const {
    const Entry<Body>& e = entry(b);
    return Body::Param::G(theta_of(e, y)) * thetadot_of(e, y);
  }
  template <class Body, class Y>
  [[nodiscard]] Vector3<double> position(BodyId<Body> b, const Y& y) const {
    return y.template segment<3>(entry(b).offset);
  }
  template <class Body, class Y>
  [[nodiscard]] Vector3<double> velocity(BodyId<Body> b, const Y& y) const {
    return y.template segment<3>(entry(b).offset + Body::nq);
  }
  template <class Body, class Y>
  [[nodiscard]] Vector3<double> centroid_position(BodyId<Body> b, const Y& y) const {
    return position(b, y) + rotation(b, y) * entry(b).body.mass_properties().centroid();
  }
  /// Set the velocity and angular velocity of body b in y (for event actions: impulses).
  template <class Body, class Y>
  void set_velocity(BodyId<Body> b, Y&& y, const Vector3<double>& v,
                    const Vector3<double>& omega_body) const {
    const Entry<Body>& e = entry(b);
    y.template segment<3>(e.offset + Body::nq) = v;
    y.template segment<Body::n_theta>(e.offset + Body::nq + 3) =
        Body::Param::thetadot(theta_of(e, y), omega_body);
  }

  /// Sum of the kinetic energies, J.
  template <class Y> [[nodiscard]] double kinetic_energy(const Y& y) const {
    double t = 0;
    for_each_entry([&](const auto& e) {
      const Vector3<double> vg = centroid_velocity(e, y);
      const Vector3<double> w = omega_of(e, y);
      const auto& mp = e.body.mass_properties();
      t += 0.5 * (mp.mass() * vg.squaredNorm() + w.dot(mp.inertia_centroid() * w));
    });
    return t;
  }
  /// Sum of the potential energies of the loads that have one (gravity, springs), J. User loads
  /// have none.
  template <class Y> [[nodiscard]] double potential_energy(const Y& y) {
    rhs_kinematics_only(y);
    double v = 0;
    (accumulate_potential<L>(v), ...);
    return v;
  }
  /// T + V.
  template <class Y> [[nodiscard]] double energy(const Y& y) {
    return kinetic_energy(y) + potential_energy(y);
  }
  /// Total linear momentum, inertial components.
  template <class Y> [[nodiscard]] Vector3<double> linear_momentum(const Y& y) const {
    Vector3<double> p = Vector3<double>::Zero();
    for_each_entry(
        [&](const auto& e) { p += e.body.mass_properties().mass() * centroid_velocity(e, y); });
    return p;
  }
  /// Total angular momentum about the inertial origin, inertial components.
  template <class Y> [[nodiscard]] Vector3<double> angular_momentum(const Y& y) const {
    Vector3<double> h = Vector3<double>::Zero();
    for_each_entry([&](const auto& e) {
      const auto& mp = e.body.mass_properties();
      const Matrix3<double> r = full_rotation(e, y);
      const Vector3<double> rg = y.template segment<3>(e.offset) + r * mp.centroid();
      h += rg.cross(mp.mass() * centroid_velocity(e, y)) +
           r * (mp.inertia_centroid() * omega_of(e, y));
    });
    return h;
  }
  /// The largest violation of |p| = 1 and p.pdot = 0 over the Euler-parameter bodies.
  template <class Y> [[nodiscard]] double constraint_drift(const Y& y) const {
    double d = 0;
    for_each_entry([&](const auto& e) {
      using Body = std::remove_cvref_t<decltype(e.body)>;
      if constexpr (Body::Param::has_constraint) {
        const Vector4<double> p = y.template segment<4>(e.offset + 3);
        const Vector4<double> pd = y.template segment<4>(e.offset + Body::nq + 3);
        d = std::max({d, std::abs(p.norm() - 1.0), std::abs(p.dot(pd))});
      }
    });
    return d;
  }

  /// Visit every body entry (for diagnostics and tests).
  template <class F> void for_each_entry(F&& f) {
    std::apply([&](auto&... group) { (for_each_in(group, f), ...); }, groups_);
  }
  template <class F> void for_each_entry(F&& f) const {
    std::apply([&](const auto&... group) { (for_each_in(group, f), ...); }, groups_);
  }

 private:
  template <class G, class F> static void for_each_in(G& group, F& f) {
    for (auto& e : group) {
      f(e);
    }
  }

  template <class Body> Entry<Body>& entry(BodyId<Body> b) {
    auto& group = std::get<std::vector<Entry<Body>>>(groups_);
    if (b.local < 0 || b.local >= static_cast<int>(group.size()) || group[b.local].id != b.id) {
      throw std::invalid_argument("tumble::Scene: the body handle " + std::to_string(b.id) +
                                  " does not refer to a body of this scene");
    }
    return group[b.local];
  }
  template <class Body> const Entry<Body>& entry(BodyId<Body> b) const {
    return const_cast<Scene*>(this)->entry(b);
  }

  static void check_initial_state(const InitialState& s) {
    if (!detail::all_finite(s.position) || !detail::all_finite(s.rotation) ||
        !detail::all_finite(s.velocity) || !detail::all_finite(s.omega)) {
      throw std::invalid_argument("tumble::Scene::add: the initial state has a non-finite entry");
    }
    const double orth =
        (s.rotation.transpose() * s.rotation - Matrix3<double>::Identity()).cwiseAbs().maxCoeff();
    if (orth > 1e-9 || s.rotation.determinant() < 0) {
      throw std::invalid_argument("tumble::Scene::add: the initial rotation is not a proper "
                                  "rotation matrix (|R^T R - I| = " +
                                  std::to_string(orth) + ")");
    }
  }

  template <class Body, class Y>
  static typename Body::Theta theta_of(const Entry<Body>& e, const Y& y) {
    return y.template segment<Body::n_theta>(e.offset + 3);
  }
  template <class Body, class Y>
  static typename Body::Theta thetadot_of(const Entry<Body>& e, const Y& y) {
    return y.template segment<Body::n_theta>(e.offset + Body::nq + 3);
  }
  template <class Body, class Y> static Vector3<double> omega_of(const Entry<Body>& e, const Y& y) {
    return Body::Param::G(theta_of(e, y)) * thetadot_of(e, y);
  }
  template <class Body, class Y>
  static Matrix3<double> full_rotation(const Entry<Body>& e, const Y& y) {
    const Matrix3<double> r = Body::Param::rotation(theta_of(e, y));
    return e.has_base ? Matrix3<double>(e.base * r) : r;
  }
  template <class Body, class Y>
  static Vector3<double> centroid_velocity(const Entry<Body>& e, const Y& y) {
    const Vector3<double> v = y.template segment<3>(e.offset + Body::nq);
    if constexpr (Body::at_centroid) {
      return v;
    } else {
      return v + full_rotation(e, y) * omega_of(e, y).cross(e.body.mass_properties().centroid());
    }
  }

  /// The kinematics loads read, Eqs. (1.1), (1.4)-(1.5): r_oc, rdot_oc, omega = G thetadot and,
  /// when with_rotation, R = R0 R(theta) with the chart base R0, from body e's coordinates q and
  /// rates qd in any scalar (double in rhs(), Jet<N> in jacobian()). Forced inline: GCC 12 left
  /// it out of line in rhs(), which cost 35% of an offset Euler-parameter right-hand side
  /// (scene_rhs/EulerParameters/offset 150 -> 202 ns; 151 ns inlined).
  template <class Body, class Q, class Qd, class S>
  [[gnu::always_inline]] static void kinematics_of(const Entry<Body>& e, const Q& q, const Qd& qd,
                                                   bool with_rotation,
                                                   BodyKinematics<S, Body::reference>& k) {
    using P = typename Body::Param;
    const typename P::template Coords<S> th = q.template tail<Body::n_theta>();
    const typename P::template Coords<S> thd = qd.template tail<Body::n_theta>();
    k.position = q.template head<3>();
    k.velocity = qd.template head<3>();
    k.omega = P::G(th) * thd;
    if (with_rotation) {
      k.rotation = P::rotation(th);
      if (e.has_base) {
        k.rotation = (e.base.template cast<S>() * k.rotation).eval();
      }
    }
  }

  template <class Body, class Y> void evaluate_kinematics(Entry<Body>& e, const Y& y) {
    constexpr int nq = Body::nq;
    kinematics_of(e, y.template segment<nq>(e.offset), y.template segment<nq>(e.offset + nq),
                  e.needs_rotation, e.kin);
  }

  template <class Load> void apply_load_type(double t) {
    for (const Attached<Load>& a : std::get<std::vector<Attached<Load>>>(loads_)) {
      if constexpr (CouplingElement<Load>) {
        a.load.apply(t, *views_[a.a], *views_[a.b], wrench_[a.a], wrench_[a.b]);
      } else {
        apply_on(a.load, t, a.a);
      }
    }
  }
  void apply_loads([[maybe_unused]] double t) { (apply_load_type<L>(t), ...); }

  /// A one-body load on the body with global index id, with its typed kinematics.
  template <class Load> void apply_on(const Load& load, double t, int id) {
    const Location loc = locations_[id];
    visit_group(loc.group, [&](auto& entries) {
      auto& e = entries[loc.local];
      load.apply(t, e.kin, wrench_[id]);
    });
  }
  template <class F, std::size_t I = 0> void visit_group(std::size_t g, F&& f) {
    if constexpr (I < sizeof...(B)) {
      if (g == I) {
        f(std::get<I>(groups_));
      } else {
        visit_group<F, I + 1>(g, std::forward<F>(f));
      }
    }
  }

  template <class Body, class Y, class Ydot>
  void write_derivative(const Entry<Body>& e, const Y& y, Ydot& ydot) const {
    constexpr int nq = Body::nq;
    const typename Body::Coords q = y.template segment<nq>(e.offset);
    const typename Body::Coords qd = y.template segment<nq>(e.offset + nq);
    ydot.template segment<nq>(e.offset) = qd;
    ydot.template segment<nq>(e.offset + nq) =
        accelerations_of(e.body, q, qd, e.kin, wrench_[e.id]);
  }

  /// qddot of `body` (the scene's body, or the same in Jet scalars), with the constraint
  /// stabilization of Euler parameters when it is on.
  template <class JBody>
  Vector<typename JBody::Scalar, JBody::nq> accelerations_of(
      const JBody& body, const typename JBody::Coords& q, const typename JBody::Coords& qd,
      const typename JBody::Kinematics& k, const Wrench<typename JBody::Scalar>& w) const {
    using S = typename JBody::Scalar;
    typename JBody::Coords qdd = body.accelerations(q, qd, k, w);
    if constexpr (JBody::Param::has_constraint) {
      if (stabilize_) {
        // Baumgarte: p.pddot = -|pdot|^2 - 2 g (p.pdot) - g^2 (|p|^2 - 1)/2, g = |omega|. The
        // body imposed p.pddot = -|pdot|^2 assuming |p| = 1; add the difference along p.
        using std::sqrt;
        const Vector4<S> p = q.template tail<4>();
        const Vector4<S> pd = qd.template tail<4>();
        const S pp = p.squaredNorm();
        const S g2 = k.omega.squaredNorm();
        // g = |omega| is not differentiable at omega = 0, where its jet would be 0/0: take the
        // one-sided derivative 0 there (the term 2 g (p.pdot) vanishes on the manifold anyway).
        S g = S(0);
        if (detail::value(g2) > 0) {
          g = sqrt(g2);
        }
        const S nu = -(pd.squaredNorm() + S(2) * g * p.dot(pd) + S(0.5) * g2 * (pp - S(1))) / pp;
        qdd.template tail<4>() += (nu + pd.squaredNorm()) * p;
      }
    }
    return qdd;
  }

  // --- pieces of the Jacobian (see jacobian()) ------------------------------------------------
  template <class Body, class Y, class Jac>
  void body_block(const Entry<Body>& e, double t, const Y& y, Jac& jac) {
    constexpr int nq = Body::nq;
    detail::add_block(jac, e.offset, e.offset + nq, Matrix<double, nq, nq>::Identity());
    if constexpr (has_couplings) {
      if (coupled_[e.id] != 0) {
        body_block_in<2 * nq + 6>(e, t, y, jac);
        return;
      }
    }
    body_block_in<2 * nq>(e, t, y, jac);
  }

  /// Body e's block in Jet<N>: its own state seeded along directions [0, 2 nq), and when
  /// N = 2 nq + 6 the wrench along [2 nq, 2 nq + 6), giving B = d qddot / dW for its couplings.
  template <int N, class Body, class Y, class Jac>
  void body_block_in(const Entry<Body>& e, double t, const Y& y, Jac& jac) {
    constexpr int nq = Body::nq;
    using J = Jet<N>;
    const RigidBody<typename Body::Param, Body::reference, J> body(e.body);
    const Vector<J, nq> q = detail::seed<N>(y.template segment<nq>(e.offset), 0);
    const Vector<J, nq> qd = detail::seed<N>(y.template segment<nq>(e.offset + nq), nq);
    BodyKinematics<J, Body::reference> k;
    k.mass_properties = &body.mass_properties();
    kinematics_of(e, q, qd, e.needs_rotation, k);
    Wrench<J> w;
    const J tj(t);
    apply_one_body_loads(e.id, tj, k, w, std::index_sequence_for<L...>{});
    if constexpr (N > 2 * nq) {
      w.force += detail::seed<N>(wrench_[e.id].force, 2 * nq);
      w.moment += detail::seed<N>(wrench_[e.id].moment, 2 * nq + 3);
    }
    const Matrix<double, nq, N> d = detail::derivatives(accelerations_of(body, q, qd, k, w));
    detail::add_block(jac, e.offset + nq, e.offset, d.template leftCols<2 * nq>());
    if constexpr (N > 2 * nq) {
      gain_[e.id].template topRows<nq>() = d.template rightCols<6>();
    }
  }

  template <class S, class K, std::size_t... I>
  void apply_one_body_loads([[maybe_unused]] int id, [[maybe_unused]] const S& t,
                            [[maybe_unused]] const K& k, [[maybe_unused]] Wrench<S>& w,
                            std::index_sequence<I...>) const {
    (
        [&] {
          using Load = std::tuple_element_t<I, std::tuple<L...>>;
          if constexpr (ForceElement<Load>) {
            const auto& list = std::get<I>(loads_);
            const LoadIndex& index = by_body_[I];
            for (int j = index.start[id]; j < index.start[id + 1]; ++j) {
              list[index.items[j]].load.apply(t, k, w);
            }
          }
        }(),
        ...);
  }

  template <class Load> void apply_coupling_type(double t) {
    if constexpr (CouplingElement<Load>) {
      for (const Attached<Load>& a : std::get<std::vector<Attached<Load>>>(loads_)) {
        a.load.apply(t, *views_[a.a], *views_[a.b], wrench_[a.a], wrench_[a.b]);
      }
    }
  }

  /// The blocks of every coupling of type Load: dW/d(y_a, y_b) in Jet<2 nq_a + 2 nq_b>, times the
  /// gains B_a and B_b of the body blocks.
  template <class Load, class Y, class Jac> void coupling_blocks(double t, const Y& y, Jac& jac) {
    if constexpr (CouplingElement<Load>) {
      for (const Attached<Load>& at : std::get<std::vector<Attached<Load>>>(loads_)) {
        const Location la = locations_[at.a], lb = locations_[at.b];
        visit_group(la.group, [&](const auto& ga) {
          visit_group(lb.group, [&](const auto& gb) {
            coupling_block(at.load, ga[la.local], gb[lb.local], t, y, jac);
          });
        });
      }
    }
  }

  template <class Load, class BodyA, class BodyB, class Y, class Jac>
  void coupling_block(const Load& load, const Entry<BodyA>& ea, const Entry<BodyB>& eb, double t,
                      const Y& y, Jac& jac) const {
    constexpr int na = BodyA::nq, nb = BodyB::nq, N = 2 * na + 2 * nb;
    using J = Jet<N>;
    const RigidBody<typename BodyA::Param, BodyA::reference, J> ba(ea.body);
    const RigidBody<typename BodyB::Param, BodyB::reference, J> bb(eb.body);
    BodyKinematics<J, BodyA::reference> ka;
    BodyKinematics<J, BodyB::reference> kb;
    ka.mass_properties = &ba.mass_properties();
    kb.mass_properties = &bb.mass_properties();
    kinematics_of(ea, Vector<J, na>(detail::seed<N>(y.template segment<na>(ea.offset), 0)),
                  Vector<J, na>(detail::seed<N>(y.template segment<na>(ea.offset + na), na)), true,
                  ka);
    kinematics_of(
        eb, Vector<J, nb>(detail::seed<N>(y.template segment<nb>(eb.offset), 2 * na)),
        Vector<J, nb>(detail::seed<N>(y.template segment<nb>(eb.offset + nb), 2 * na + nb)), true,
        kb);
    Wrench<J> wa, wb;
    load.apply(J(t), static_cast<const KinematicsView<J>&>(ka),
               static_cast<const KinematicsView<J>&>(kb), wa, wb);
    add_coupling_rows<na>(ea.id, ea.offset, wa, ea.offset, eb.offset, na, jac);
    add_coupling_rows<nb>(eb.id, eb.offset, wb, ea.offset, eb.offset, na, jac);
  }

  /// Rows of qddot of the body (id, offset) += B dW/d(y_a, y_b) for a wrench W in jets whose
  /// directions are [y_a (2 na); y_b].
  template <int n, class J, class Jac>
  void add_coupling_rows(int id, int offset, const Wrench<J>& w, int offset_a, int offset_b, int na,
                         Jac& jac) const {
    constexpr int N = J::DerType::RowsAtCompileTime;
    Matrix<double, 6, N> dw;
    dw.template topRows<3>() = detail::derivatives(w.force);
    dw.template bottomRows<3>() = detail::derivatives(w.moment);
    const Matrix<double, n, N> rows = gain_[id].template topRows<n>() * dw;
    detail::add_block(jac, offset + n, offset_a, rows.leftCols(2 * na));
    detail::add_block(jac, offset + n, offset_b, rows.rightCols(N - 2 * na));
  }

  /// One block of the preconditioner: J_kk and the LU factors of I - gamma J_kk.
  template <class Body> struct DiagonalBlock {
    static constexpr int m = 2 * Body::nq;
    Matrix<double, m, m> j = Matrix<double, m, m>::Zero();
    Eigen::PartialPivLU<Matrix<double, m, m>> lu;
  };

  /// A Jacobian "matrix" that keeps the diagonal blocks only (jacobian() writes through
  /// detail::add_block): the block of body k receives what falls in its rows and its columns.
  struct DiagonalSink {
    Scene* scene;
    template <class Derived>
    void add_block(Eigen::Index r0, Eigen::Index c0, const Eigen::MatrixBase<Derived>& b) const {
      const int k = scene->owner_[r0];
      if (scene->owner_[c0] != k) {
        return;
      }
      const int o = scene->block_start_[k], m = scene->block_size_[k];
      Eigen::Map<Eigen::MatrixXd> jk(scene->block_data_[k], m, m);
      jk.block(r0 - o, c0 - o, b.rows(), b.cols()) += b;
    }
  };

  template <class F> void for_each_group_with_blocks(F&& f) {
    for_each_group_with_blocks_impl(f, std::index_sequence_for<B...>{});
  }
  template <class F, std::size_t... I>
  void for_each_group_with_blocks_impl(F& f, std::index_sequence<I...>) {
    (f(std::get<I>(groups_), std::get<I>(blocks_)), ...);
  }

  /// For each one-body load type, the loads on each body (a compressed index: the loads of body
  /// k are items[start[k] .. start[k + 1])), so that a body's block visits only its own loads.
  struct LoadIndex {
    std::vector<int> start;
    std::vector<int> items;
  };
  template <std::size_t... I> void index_loads(std::index_sequence<I...>) {
    const int n = body_count();
    (
        [&] {
          const auto& list = std::get<I>(loads_);
          LoadIndex& index = by_body_[I];
          index.start.assign(n + 1, 0);
          index.items.assign(list.size(), 0);
          for (const auto& a : list) {
            ++index.start[a.a + 1];
          }
          for (int k = 0; k < n; ++k) {
            index.start[k + 1] += index.start[k];
          }
          std::vector<int> next(index.start.begin(), index.start.end() - 1);
          for (std::size_t j = 0; j < list.size(); ++j) {
            index.items[next[list[j].a]++] = static_cast<int>(j);
          }
        }(),
        ...);
    coupled_.assign(n, 0);
    (
        [&] {
          for (const auto& a : std::get<I>(loads_)) {
            if (a.b >= 0) {
              coupled_[a.a] = coupled_[a.b] = 1;
            }
          }
        }(),
        ...);
    if constexpr (has_couplings) {
      gain_.assign(n, Matrix<double, 7, 6>::Zero());
    }
  }

  template <class Body, class Y> void leave_chart(Entry<Body>& e, Y& y) {
    using P = typename Body::Param;
    const typename Body::Theta th = theta_of(e, y);
    const Vector3<double> w = omega_of(e, y);
    typename Body::Theta th_new;
    if constexpr (Chart<P>::uses_shadow_set) {
      th_new = P::shadow(th);
    } else {
      const typename Body::Theta c = Chart<P>::center();
      Matrix3<double> base = full_rotation(e, y) * P::rotation(c).transpose();
      // Re-orthonormalize through the quaternion so rounding does not accumulate over switches.
      base = EulerParameters::rotation(EulerParameters::from_rotation(base));
      e.base = base;
      e.has_base = true;
      th_new = c;
    }
    y.template segment<Body::n_theta>(e.offset + 3) = th_new;
    y.template segment<Body::n_theta>(e.offset + Body::nq + 3) = P::thetadot(th_new, w);
    ++e.switches;
  }

  template <class Y> void rhs_kinematics_only(const Y& y) {
    if (!prepared_) {
      prepare();
    }
    for_each_entry([&](auto& e) {
      const bool saved = e.needs_rotation;
      e.needs_rotation = true;
      evaluate_kinematics(e, y);
      e.needs_rotation = saved;
    });
  }

  template <class Load> void accumulate_potential(double& v) {
    for (const Attached<Load>& a : std::get<std::vector<Attached<Load>>>(loads_)) {
      if constexpr (CouplingElement<Load>) {
        if constexpr (requires { a.load.potential_energy(*views_[a.a], *views_[a.b]); }) {
          v += a.load.potential_energy(*views_[a.a], *views_[a.b]);
        }
      } else {
        const Location loc = locations_[a.a];
        visit_group(loc.group, [&](auto& entries) {
          const auto& k = entries[loc.local].kin;
          if constexpr (requires { a.load.potential_energy(k); }) {
            v += a.load.potential_energy(k);
          }
        });
      }
    }
  }

  struct Location {
    std::size_t group;
    int local;
  };

  std::tuple<std::vector<Entry<B>>...> groups_;
  std::tuple<std::vector<Attached<L>>...> loads_;
  std::vector<Location> locations_;
  std::vector<Event> events_;
  std::vector<Wrench<double>> wrench_;
  std::vector<const KinematicsView<double>*> views_;
  std::vector<int> chart_bodies_;
  std::vector<int> directions_;
  std::array<LoadIndex, sizeof...(L)> by_body_;
  std::vector<char> coupled_;               ///< per body: 1 when a coupling acts on it
  std::vector<Matrix<double, 7, 6>> gain_;  ///< per body: B = d qddot / dW (jacobian())
  std::tuple<std::vector<DiagonalBlock<B>>...> blocks_;  ///< the block preconditioner
  std::vector<int> owner_;                               ///< per state entry: its body
  std::vector<double*> block_data_;                      ///< per body: its J_kk
  std::vector<int> block_start_;
  std::vector<int> block_size_;
  bool preconditioner_ready_ = false;
  State y0_;
  int size_ = 0;
  bool prepared_ = false;
  bool stabilize_ = true;
};

}  // namespace tumble
