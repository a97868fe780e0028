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

#include "tumble/body/rigid_body.hpp"
#include "tumble/core/errors.hpp"
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

  template <class Body, class Y> void evaluate_kinematics(Entry<Body>& e, const Y& y) {
    using P = typename Body::Param;
    const typename Body::Theta th = theta_of(e, y);
    e.kin.position = y.template segment<3>(e.offset);
    e.kin.velocity = y.template segment<3>(e.offset + Body::nq);
    e.kin.omega = P::G(th) * thetadot_of(e, y);
    if (e.needs_rotation) {
      e.kin.rotation = P::rotation(th);
      if (e.has_base) {
        e.kin.rotation = e.base * e.kin.rotation;
      }
    }
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
    using P = typename Body::Param;
    constexpr int nq = Body::nq;
    const typename Body::Coords q = y.template segment<nq>(e.offset);
    const typename Body::Coords qd = y.template segment<nq>(e.offset + nq);
    typename Body::Coords qdd = e.body.accelerations(q, qd, e.kin, wrench_[e.id]);
    if constexpr (P::has_constraint) {
      if (stabilize_) {
        // Baumgarte: p.pddot = -|pdot|^2 - 2 g (p.pdot) - g^2 (|p|^2 - 1)/2, g = |omega|. The
        // body imposed p.pddot = -|pdot|^2 assuming |p| = 1; add the difference along p.
        const Vector4<double> p = q.template tail<4>();
        const Vector4<double> pd = qd.template tail<4>();
        const double pp = p.squaredNorm();
        const double g2 = e.kin.omega.squaredNorm();
        const double g = std::sqrt(g2);
        const double nu = -(pd.squaredNorm() + 2.0 * g * p.dot(pd) + 0.5 * g2 * (pp - 1.0)) / pp;
        qdd.template tail<4>() += (nu + pd.squaredNorm()) * p;
      }
    }
    ydot.template segment<nq>(e.offset) = qd;
    ydot.template segment<nq>(e.offset + nq) = qdd;
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
  State y0_;
  int size_ = 0;
  bool prepared_ = false;
  bool stabilize_ = true;
};

}  // namespace tumble
