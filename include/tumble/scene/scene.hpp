#pragma once
// A scene: the model of any number of rigid bodies, each with its own parameterization and
// reference point, the loads on them, the couplings between them and user events.
//
// The scene is built once (add, add_load, add_event) and then only read: it holds no state of a
// run, so it is copyable and may be shared read-only between integrators and threads. What
// changes during a run lives elsewhere, as in Pinocchio's Model and Data:
// - the state (state.hpp): the continuous vector y and each body's chart base;
// - per-evaluation scratch (workspace.hpp), owned by whoever evaluates;
// - the algorithms on a scene and a state, one per header: the right-hand side (rhs.hpp), its
//   Jacobian (jacobian.hpp), the block preconditioner (preconditioner.hpp), chart switching
//   (charts.hpp), the projection onto the quaternion constraint (projection.hpp) and the
//   observables (observables.hpp).
//
// Types are resolved at compile time: `Scene<Bodies<B...>, Loads<L...>, Form>` lists the body
// types and the load types the scene may hold, and the layout of its state (StateForm, state.hpp:
// [q; qdot] or [q; v; omega] per body; every algorithm dispatches on it with `if constexpr`), so
// that the algorithms loop over each body type and each load type with the concrete type known (a
// centroidal body never computes coupling terms, a body whose loads need no rotation matrix never
// forms R, ...).

#include <algorithm>
#include <array>
#include <cstddef>
#include <functional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "tumble/body/rigid_body.hpp"
#include "tumble/core/cache_line.hpp"
#include "tumble/core/jet.hpp"
#include "tumble/core/math.hpp"
#include "tumble/force/concept.hpp"
#include "tumble/force/coupling.hpp"
#include "tumble/joint/concept.hpp"
#include "tumble/scene/chart.hpp"
#include "tumble/scene/state.hpp"

namespace tumble {

template <class... B> struct Bodies {};
template <class... L> struct Loads {};
/// The joint types a scene may hold (joint/): a scene with joints is a mechanism.
template <class... J> struct Joints {};

/// A typed handle to a joint of a scene.
template <class Joint> struct JointId {
  int id = -1;     ///< global index (order of addition)
  int local = -1;  ///< index among the joints of the same type
};

/// The ground, as the second body of a joint (Scene::add_joint(a, ground, joint)).
struct Ground {};
inline constexpr Ground ground{};

/// A typed handle to a body of a scene.
template <class Body> struct BodyId {
  int id = -1;     ///< global index (order of addition)
  int local = -1;  ///< index among the bodies of the same type
};

/// A user event: a root function g(t, state) whose zero crossing (in `direction`: +1 rising, -1
/// falling, 0 both) triggers `action(t, state)`, which may change the continuous state (an
/// impulse, ...). Charts near their singularity are re-centered after an action.
struct Event {
  std::function<double(double, const SceneStateView&)> function;
  int direction = 0;
  std::function<void(double, SceneState&)> action;
};

namespace detail {

/// The functions of theta that a body's rates in the state form Form use again (rhs.hpp): in
/// [q; qdot] those omega used (P::Precomputed), which thetaddot (Eq. 1.10) reads instead of
/// evaluating them twice; in [q; v; omega], where no thetaddot is formed, none.
struct NoThetaFunctions {};
template <class Body, StateForm Form>
using ThetaFunctions =
    std::conditional_t<Form == StateForm::generalized,
                       typename Body::Param::template Precomputed<double>, NoThetaFunctions>;

/// A body's kinematics as the right-hand side keeps them between its passes: what its loads read,
/// and the functions of theta its rates use again.
template <class Body, StateForm Form>
struct EntryKinematics : BodyKinematics<double, Body::reference> {
  [[no_unique_address]] ThetaFunctions<Body, Form> theta_functions;
};

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

/// A load the scene can evaluate in Jet scalars, so that its Jacobian is exact (jacobian.hpp):
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

/// A joint the scene can evaluate in Jet scalars (its evaluate() is a template over the scalar
/// type, as every tumble joint is; a UserJoint over a function of double is not).
template <class J>
concept DifferentiableJoint = requires(const J& j, const KinematicsView<Jet<2>>& a,
                                       const KinematicsView<Jet<2>>& b,
                                       ConstraintRows<Jet<2>, J::size>& rows) {
  j.evaluate(a, b, rows);
};

/// One body of a scene, as the model keeps it, for a state of form Form.
template <class Body, StateForm Form> struct SceneEntry {
  static constexpr StateForm form = Form;
  static constexpr bool quasi = Form == StateForm::quasi_velocities;
  /// The length of the body's rates in y: qdot (nq), or the quasi-velocities (nv: [v; omega], or
  /// omega alone for a body held at a fixed point).
  static constexpr int rate_size = quasi ? Body::nv : Body::nq;
  /// The length of the body's block in y: [q; qdot] (2 nq) or [q; v; omega] (nq + nv).
  static constexpr int block_size = Body::nq + rate_size;
  /// Where theta starts in the block, and omega (or thetadot) in the rates: after r_oc (and v),
  /// which a body held at a fixed point does not have.
  static constexpr int theta_at = Body::n_r;

  Body body;
  int id;      ///< global index
  int local;   ///< index among the bodies of its type
  int offset;  ///< first entry of its block (q first) in y
  int rates;   ///< first entry of its rates in y: offset + nq
  /// Some load (or the offset frame) reads R.
  bool needs_rotation = Body::reference == ReferencePoint::offset;
  double switch_distance = Chart<typename Body::Param>::switch_distance();
};

/// A load attached to one body (b = -1) or between bodies a and b.
template <class Load> struct Attached {
  Load load;
  int a;
  int b;
};

/// A joint between bodies a and b (b = -1: the ground); its rows start at `row` of the scene's
/// constraint vector.
template <class Joint> struct AttachedJoint {
  Joint joint;
  int a;
  int b;
  int row;
  int id;  ///< global joint index (order of addition)
};
}  // namespace detail

template <class BodyList, class LoadList = Loads<>, StateForm Form = StateForm::quasi_velocities,
          class JointList = Joints<>>
class Scene;

/// A scene with joints, the joint list second: Mechanism<Bodies<Link>, Joints<Revolute>,
/// Loads<UniformGravity>>.
template <class BodyList, class JointList, class LoadList = Loads<>,
          StateForm Form = StateForm::quasi_velocities>
using Mechanism = Scene<BodyList, LoadList, Form, JointList>;

template <class... B, class... L, StateForm Form, class... J>
class Scene<Bodies<B...>, Loads<L...>, Form, Joints<J...>> {
  static_assert(sizeof...(B) > 0, "a Scene needs at least one body type");
  static_assert((std::is_same_v<typename B::Scalar, double> && ...),
                "bodies integrated in time use the scalar type double");
  static_assert(((detail::count<B, B...>() == 1) && ...), "list each body type once");
  static_assert(((detail::count<L, L...>() == 1) && ...), "list each load type once");
  static_assert(((ForceElement<L> || CouplingElement<L>)&&...),
                "each load type must be a ForceElement (one body) or a CouplingElement (two)");
  static_assert(((detail::count<J, J...>() == 1) && ...), "list each joint type once");
  static_assert((JointElement<J> && ...), "each joint type must be a JointElement (joint/)");

 public:
  /// The layout of the state: [q; qdot] or [q; v; omega] per body (state.hpp).
  static constexpr StateForm form = Form;
  template <class Body> using Entry = detail::SceneEntry<Body, Form>;
  template <class Load> using Attached = detail::Attached<Load>;
  using LoadTypes = std::tuple<L...>;
  using JointTypes = std::tuple<J...>;
  template <class Joint> using AttachedJoint = detail::AttachedJoint<Joint>;
  /// Per body type, the kinematics its loads read and, in [q; qdot], the functions of theta the
  /// accelerations use again (detail::EntryKinematics: the layout of a workspace), in cache lines
  /// of their own (written at every evaluation, by one thread: core/cache_line.hpp).
  using KinematicsStorage = std::tuple<CacheLineVector<detail::EntryKinematics<B, Form>>...>;
  /// The index of a body type in Bodies<B...> (its group).
  template <class Body> static constexpr std::size_t group_of = detail::index_of<Body, B...>();

  /// True when every load type (and every joint type) can be evaluated in Jet scalars: then the
  /// exact Jacobian (jacobian.hpp) is available. A mechanism is differentiated in the
  /// quasi-velocity form; in [q; qdot] its Jacobian is CVODE's difference quotients.
  static constexpr bool differentiable =
      (detail::DifferentiableLoad<L> && ...) &&
      (sizeof...(J) == 0 ||
       (Form == StateForm::quasi_velocities && (detail::DifferentiableJoint<J> && ...)));
  /// True when the scene's type lists load types (Loads<>: none, known at compile time).
  static constexpr bool has_loads = sizeof...(L) > 0;
  /// True when the scene may hold joints (a mechanism: scene/joints.hpp).
  static constexpr bool has_joints = sizeof...(J) > 0;
  /// True when some load type acts between two bodies.
  static constexpr bool has_couplings = (CouplingElement<L> || ...);
  /// True if the scene has constrained coordinates (Euler parameters).
  static constexpr bool has_constraints = (B::Param::has_constraint || ...);
  /// True if some body type has a singular chart (three-parameter sets).
  static constexpr bool has_charts = (Chart<typename B::Param>::has_singularity || ...);

  // --- building -------------------------------------------------------------------------------
  /// Add a body with its physical initial state. Returns its handle. A body held at a fixed point
  /// (ReferencePoint::fixed_point) has no translational state: its position is the fixed point
  /// the body was made with, so leave s.position at its default (or repeat the point: it must
  /// agree to 1e-12 relative) and s.velocity at zero.
  /// \throws std::invalid_argument for a non-finite or non-orthonormal initial state, or a fixed
  ///         body whose s.position or s.velocity contradict its fixed point.
  template <class Body> BodyId<Body> add(Body body, const InitialState& s = {}) {
    static_assert(detail::contains<Body, B...>, "this body type is not in the scene's Bodies<...>");
    check_initial_state(s, body_count());
    if constexpr (Body::fixed) {
      check_fixed_point(s, body.fixed_point(), body_count());
    }
    using P = typename Body::Param;
    constexpr int nq = Body::nq, nr = Body::n_r;
    auto& group = std::get<std::vector<Entry<Body>>>(groups_);
    const int id = body_count();
    const int local = static_cast<int>(group.size());
    constexpr int block = Entry<Body>::block_size;
    Entry<Body> e{std::move(body), id, local, size_, size_ + nq};
    // The initial chart: theta of R itself, unless R is near the chart's singularity; then the
    // chart is centered there (R0 = R R(theta_c)^T, theta = theta_c).
    Matrix3<double> base = Matrix3<double>::Identity();
    typename P::template Coords<double> theta = P::from_rotation(s.rotation);
    if constexpr (Chart<P>::has_singularity) {
      if (P::singularity_distance(theta) < e.switch_distance) {
        const auto c = Chart<P>::center();
        base = s.rotation * P::rotation(c).transpose();
        theta = c;
      }
      chart_bodies_.push_back(id);
    }
    y0_.y.conservativeResize(size_ + block);
    if constexpr (nr > 0) {
      y0_.y.template segment<3>(size_) = s.position;
      y0_.y.template segment<3>(size_ + nq) = s.velocity;
    }
    y0_.y.template segment<Body::n_theta>(size_ + nr) = theta;
    if constexpr (Entry<Body>::quasi) {
      y0_.y.template segment<3>(size_ + nq + nr) = s.omega;
    } else {
      y0_.y.template segment<Body::n_theta>(size_ + nq + nr) = P::thetadot(theta, s.omega);
    }
    y0_.base.push_back(base);
    group.push_back(std::move(e));
    size_ += block;
    locations_.push_back({detail::index_of<Body, B...>(), local});
    for (auto& per_body : loads_on_) {
      per_body.emplace_back();
    }
    coupled_.push_back(0);
    return BodyId<Body>{id, local};
  }

  /// Attach a one-body load.
  template <class Body, class Load> void add_load(BodyId<Body> body, Load load) {
    static_assert(detail::contains<Load, L...>, "this load type is not in the scene's Loads<...>");
    static_assert(ForceElement<Load>, "a two-body load needs two bodies");
    Entry<Body>& e = entry(body);
    if constexpr (Load::needs_rotation(Body::reference)) {
      e.needs_rotation = true;
    }
    auto& list = std::get<std::vector<Attached<Load>>>(loads_);
    loads_on_[detail::index_of<Load, L...>()][body.id].push_back(static_cast<int>(list.size()));
    list.push_back({std::move(load), body.id, -1});
    ++load_count_;
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
    coupled_[a.id] = coupled_[b.id] = 1;
    std::get<std::vector<Attached<Load>>>(loads_).push_back({std::move(load), a.id, b.id});
    ++load_count_;
  }

  /// Join bodies a and b by a joint (its points and axes given in each body's components).
  /// \throws std::invalid_argument for a handle not of this scene, or a = b.
  template <class BodyA, class BodyB, class Joint>
  JointId<Joint> add_joint(BodyId<BodyA> a, BodyId<BodyB> b, Joint joint) {
    static_assert(detail::contains<Joint, J...>,
                  "this joint type is not in the scene's Joints<...>");
    if (a.id == b.id) {
      throw std::invalid_argument(std::string("tumble::Scene::add_joint: a ") + Joint::name +
                                  " joint needs two different bodies (body " +
                                  std::to_string(a.id) +
                                  " twice); join a body to the ground "
                                  "with add_joint(body, tumble::ground, joint)");
    }
    entry(a).needs_rotation = true;
    entry(b).needs_rotation = true;
    return attach_joint(a.id, b.id, std::move(joint));
  }
  /// Join body a to the ground (the joint's data for side b in inertial components).
  template <class BodyA, class Joint>
  JointId<Joint> add_joint(BodyId<BodyA> a, Ground /*ground*/, Joint joint) {
    static_assert(detail::contains<Joint, J...>,
                  "this joint type is not in the scene's Joints<...>");
    entry(a).needs_rotation = true;
    return attach_joint(a.id, -1, std::move(joint));
  }

  /// Add a user event (see Event).
  void add_event(Event event) {
    if (!event.function) {
      throw std::invalid_argument("tumble::Scene::add_event: the event has no root function");
    }
    events_.push_back(std::move(event));
  }

  // --- what the model is ----------------------------------------------------------------------
  /// The length of the continuous state y.
  [[nodiscard]] int size() const { return size_; }
  [[nodiscard]] int body_count() const { return static_cast<int>(locations_.size()); }
  /// The initial state assembled from the bodies' InitialState.
  [[nodiscard]] const SceneState& initial_state() const { return y0_; }
  template <class Body> [[nodiscard]] int offset(BodyId<Body> b) const { return entry(b).offset; }
  template <class Body> [[nodiscard]] const Body& body(BodyId<Body> b) const {
    return entry(b).body;
  }
  template <class Body> [[nodiscard]] const Entry<Body>& entry(BodyId<Body> b) const {
    const auto& group = std::get<std::vector<Entry<Body>>>(groups_);
    if (b.local < 0 || b.local >= static_cast<int>(group.size()) || group[b.local].id != b.id)
        [[unlikely]] {
      bad_handle("body", b.id);
    }
    return group[b.local];
  }

  /// The number of joints and of constraint equations (the length of lambda).
  [[nodiscard]] int joint_count() const { return joint_count_; }
  [[nodiscard]] int constraint_count() const { return constraint_count_; }
  /// The joints of one type, in the order they were added.
  template <class Joint> [[nodiscard]] const std::vector<AttachedJoint<Joint>>& joints() const {
    return std::get<std::vector<AttachedJoint<Joint>>>(joints_);
  }
  template <class Joint> [[nodiscard]] const AttachedJoint<Joint>& joint(JointId<Joint> j) const {
    const auto& list = joints<Joint>();
    if (j.local < 0 || j.local >= static_cast<int>(list.size()) || list[j.local].id != j.id)
        [[unlikely]] {
      bad_handle("joint", j.id);
    }
    return list[j.local];
  }

  /// The bodies with a singular chart (three-parameter sets), in id order: one root function
  /// each (charts.hpp).
  [[nodiscard]] const std::vector<int>& chart_bodies() const { return chart_bodies_; }
  [[nodiscard]] const std::vector<Event>& events() const { return events_; }
  /// Number of root functions: one per body with a singular chart, then the user events.
  [[nodiscard]] int root_count() const {
    return static_cast<int>(chart_bodies_.size() + events_.size());
  }
  /// The direction of each root function: -1 (falling distance) for charts, the events' own.
  [[nodiscard]] std::vector<int> root_directions() const {
    std::vector<int> d(chart_bodies_.size(), -1);
    for (const Event& e : events_) {
      d.push_back(e.direction);
    }
    return d;
  }

  /// The number of loads attached, of every type.
  [[nodiscard]] int load_count() const { return load_count_; }
  /// The loads of one type, in the order they were attached.
  template <class Load> [[nodiscard]] const std::vector<Attached<Load>>& loads() const {
    return std::get<std::vector<Attached<Load>>>(loads_);
  }
  /// The indices into loads<Load>() of the one-body loads of type index I on body `id`.
  template <std::size_t I> [[nodiscard]] const std::vector<int>& loads_on(int id) const {
    return loads_on_[I][id];
  }
  /// True when a coupling acts on body `id`.
  [[nodiscard]] bool coupled(int id) const { return coupled_[id] != 0; }

  /// The half-bandwidth of the Jacobian df/dy in the scene's state ordering: a body's block
  /// ([q; qdot] or [q; v; omega]) is dense, and a coupling between bodies a and b links their two
  /// blocks. For a chain of bodies added in order this stays constant as the chain grows, so
  /// CVODE's band solver costs O(N) per Jacobian and per solve.
  [[nodiscard]] int half_bandwidth() const {
    std::vector<std::pair<int, int>> block(locations_.size());  // [first, last] index per body
    for_each_entry([&](const auto& e) { block[e.id] = {e.offset, e.offset + e.block_size - 1}; });
    int bw = 0;
    for (const auto& [first, last] : block) {
      bw = std::max(bw, last - first);
    }
    const auto link = [&](int a, int b) {
      if (b >= 0) {
        bw = std::max({bw, block[b].second - block[a].first, block[a].second - block[b].first});
      }
    };
    for_each_load([&](const auto& at) { link(at.a, at.b); });
    // A joint's multipliers make each of its bodies' accelerations depend on both: a coupling
    // too. (Through a chain of joints the solve couples every body with every other: a band
    // Jacobian of a mechanism is the difference quotients' band; the exact one is dense.)
    for_each_joint([&](const auto& at) { link(at.a, at.b); });
    return bw;
  }

  // --- visiting -------------------------------------------------------------------------------
  /// f(entry) for every body, grouped by type (each call sees the concrete body type).
  template <class F> void for_each_entry(F&& f) const {
    std::apply([&](const auto&... group) { (for_each_in(group, f), ...); }, groups_);
  }
  /// f(entry) for the body with global index id, with its concrete type.
  template <class F> void visit_entry(int id, F&& f) const {
    const Location loc = locations_[id];
    visit_group(loc.group, [&](const auto& group) { f(group[loc.local]); });
  }
  /// f(attached) for every load of every type.
  template <class F> void for_each_load(F&& f) const {
    std::apply([&](const auto&... lists) { (for_each_in(lists, f), ...); }, loads_);
  }
  /// f(attached joint) for every joint of every type (each call sees the concrete joint type).
  template <class F> void for_each_joint(F&& f) const {
    std::apply([&](const auto&... lists) { (for_each_in(lists, f), ...); }, joints_);
  }

 private:
  /// The error of a handle (a BodyId or JointId) that names nothing in this scene, out of line:
  /// entry() and joint(), which every observable calls, stay a few instructions inline.
  [[noreturn, gnu::cold, gnu::noinline]] static void bad_handle(const char* what, int id) {
    throw std::invalid_argument(std::string("tumble::Scene: the ") + what + " handle " +
                                std::to_string(id) + " does not refer to a " + what +
                                " of this scene");
  }

  struct Location {
    std::size_t group;
    int local;
  };

  template <class G, class F> static void for_each_in(const G& group, F& f) {
    for (const auto& e : group) {
      f(e);
    }
  }
  template <class F, std::size_t I = 0> void visit_group(std::size_t g, F&& f) const {
    if constexpr (I < sizeof...(B)) {
      if (g == I) {
        f(std::get<I>(groups_));
      } else {
        visit_group<F, I + 1>(g, std::forward<F>(f));
      }
    }
  }
  template <class Body> Entry<Body>& entry(BodyId<Body> b) {
    return const_cast<Entry<Body>&>(std::as_const(*this).entry(b));
  }

  template <class Joint> JointId<Joint> attach_joint(int a, int b, Joint joint) {
    auto& list = std::get<std::vector<AttachedJoint<Joint>>>(joints_);
    const JointId<Joint> handle{joint_count_, static_cast<int>(list.size())};
    list.push_back({std::move(joint), a, b, constraint_count_, joint_count_});
    constraint_count_ += Joint::size;
    ++joint_count_;
    return handle;
  }

  /// Names the first non-finite field of an initial state and its value, and rejects a rotation
  /// that is not proper.
  static void check_initial_state(const InitialState& s, int id) {
    auto fail = [id](const char* field, const auto& v) {
      std::ostringstream os;
      os.precision(10);
      os << "tumble::Scene::add: body " << id << ": the initial " << field << " is not finite: (";
      for (Eigen::Index i = 0; i < v.size(); ++i) {
        os << (i > 0 ? ", " : "") << v(i);
      }
      os << ")";
      throw std::invalid_argument(os.str());
    };
    if (!detail::all_finite(s.position)) {
      fail("position", s.position);
    }
    if (!detail::all_finite(s.rotation)) {
      // Row by row, copied entry by entry: a transposed temporary made GCC 12 at -O3 warn of an
      // uninitialized read when the rotation was built in the caller's initializer.
      Eigen::Matrix<double, 9, 1> rows;
      for (int i = 0; i < 9; ++i) {
        rows(i) = s.rotation(i / 3, i % 3);
      }
      fail("rotation (row by row)", rows);
    }
    if (!detail::all_finite(s.velocity)) {
      fail("velocity", s.velocity);
    }
    if (!detail::all_finite(s.omega)) {
      fail("omega", s.omega);
    }
    const double orth =
        (s.rotation.transpose() * s.rotation - Matrix3<double>::Identity()).cwiseAbs().maxCoeff();
    if (orth > 1e-9 || s.rotation.determinant() < 0) {
      throw std::invalid_argument("tumble::Scene::add: the initial rotation is not a proper "
                                  "rotation matrix (|R^T R - I| = " +
                                  std::to_string(orth) + ")");
    }
  }

  /// A body held at a fixed point starts there, at rest. Its position is given once, to the
  /// body: s.position may be left at its default (zero), which means "at the fixed point", or
  /// repeat the point to within kFixedPointTolerance (relative to its distance from the origin,
  /// at least 1 m); s.velocity must be zero to within kFixedPointTolerance m/s.
  static void check_fixed_point(const InitialState& s, const Vector3<double>& fixed_point, int id) {
    const double scale = std::max(1.0, fixed_point.norm());
    const bool at_point =
        s.position.isZero(0) || (s.position - fixed_point).norm() <= kFixedPointTolerance * scale;
    const bool at_rest = s.velocity.norm() <= kFixedPointTolerance;
    if (!at_point || !at_rest) {
      std::ostringstream os;
      os.precision(17);
      const auto vec = [&os](const Vector3<double>& v) {
        os << "(" << v(0) << ", " << v(1) << ", " << v(2) << ")";
      };
      os << "tumble::Scene::add: body " << id << " is held at its fixed point ";
      vec(fixed_point);
      os << ", which the body gives: leave InitialState::position at zero, or repeat that point "
            "(to "
         << kFixedPointTolerance << " relative; got ";
      vec(s.position);
      os << ", " << (s.position - fixed_point).norm()
         << " m from it), and leave the velocity zero (got ";
      vec(s.velocity);
      os << ")";
      throw std::invalid_argument(os.str());
    }
  }
  static constexpr double kFixedPointTolerance = 1e-12;

  std::tuple<std::vector<Entry<B>>...> groups_;
  std::tuple<std::vector<Attached<L>>...> loads_;
  int load_count_ = 0;
  std::tuple<std::vector<AttachedJoint<J>>...> joints_;
  int joint_count_ = 0;
  int constraint_count_ = 0;
  std::vector<Location> locations_;
  /// Per one-body load type, per body: the indices of its loads of that type.
  std::array<std::vector<std::vector<int>>, sizeof...(L)> loads_on_;
  std::vector<char> coupled_;  ///< per body: 1 when a coupling acts on it
  std::vector<int> chart_bodies_;
  std::vector<Event> events_;
  SceneState y0_;
  int size_ = 0;
};

/// The length of the state y of a scene of type SceneT holding one body of each of the types
/// Body... (a type listed twice: two such bodies), known at compile time: the fixed size N of an
/// integrator's state (OdeintIntegrator<SceneT, state_size<SceneT, Body...>>), worked out from the
/// types instead of by hand. The integrator checks it against Scene::size() when it is made.
template <class SceneT, class... Body>
inline constexpr int state_size = (SceneT::template Entry<Body>::block_size + ... + 0);

}  // namespace tumble
