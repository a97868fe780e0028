#pragma once
// CompiledScene (scene_api.hpp) for the scenes of parameterization P (SceneKind: any scene, with
// or without a Python load, or one body without loads): included by the generated scene sources
// only (python/src/scene_of.cpp.in), one (P, kind) per translation unit, each 20-80 s and up to
// 2.9 GB of g++ -O3.

#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include <Eigen/Geometry>

#include "scene_api.hpp"
#include "tumble/ensemble/ensemble.hpp"
#include "tumble/integrate.hpp"
#include "tumble/scene/accelerations.hpp"
#include "tumble/scene/observables.hpp"
#include "tumble/scene/rhs.hpp"
#include "tumble/scene/workspace.hpp"

namespace tumble::python::detail {

template <class P, ReferencePoint Ref> using RB = RigidBody<P, Ref>;

/// The scene types the module compiles per parameterization P: `standard` and `with_python`
/// take any scene (the three body types, every load type); the three lean kinds take one body
/// of one reference point and no loads, the scene type a C++ user writes for a tumbling body.
/// A scene type that lists load types runs an unloaded scene about 9 % slower than the lean one
/// (GCC 12 compiles the stage for the loaded path too), and one that lists the three body types
/// without loads 27 % slower (its stage calls the parameterization's functions out of line;
/// docs/benchmarks/python.md), so build_scene() picks a lean kind of one body type where it
/// can. Same arithmetic, same results.
enum class SceneKind { standard, with_python, centroid, offset, fixed_point };

template <class P>
using AnyBodies = tumble::Bodies<RB<P, ReferencePoint::centroid>, RB<P, ReferencePoint::offset>,
                                 RB<P, ReferencePoint::fixed_point>>;
using StandardLoads =
    tumble::Loads<UniformGravity, PointForce, BodyMoment, SpringDamper, SpringDamperBetween>;

template <class P, SceneKind K> struct SceneTypes {
  static constexpr ReferencePoint kRef = K == SceneKind::centroid ? ReferencePoint::centroid
                                         : K == SceneKind::offset ? ReferencePoint::offset
                                                                  : ReferencePoint::fixed_point;
  using BodyList = tumble::Bodies<RB<P, kRef>>;
  using Type = Scene<BodyList, tumble::Loads<>>;
};
template <class P> struct SceneTypes<P, SceneKind::standard> {
  using BodyList = AnyBodies<P>;
  using Type = Scene<BodyList, StandardLoads>;
};
template <class P> struct SceneTypes<P, SceneKind::with_python> {
  using BodyList = AnyBodies<P>;
  using Type = Scene<BodyList, tumble::Loads<UniformGravity, PointForce, BodyMoment, SpringDamper,
                                             SpringDamperBetween, UserForce<PythonLoad>>>;
};

inline std::string method_name(AutoMethod m) { return name(m); }

template <class T, class Tuple> struct TupleHas;
template <class T, class... X>
struct TupleHas<T, std::tuple<X...>> : std::bool_constant<tumble::detail::contains<T, X...>> {};

template <class P, class SceneT, class BodyList> class SceneOfBodies;

template <class P, SceneKind K>
using SceneOf =
    SceneOfBodies<P, typename SceneTypes<P, K>::Type, typename SceneTypes<P, K>::BodyList>;

/// CompiledScene of SceneT, whose body types are B... (RigidBody<P, Ref>).
template <class P, class SceneT, class... B>
class SceneOfBodies<P, SceneT, tumble::Bodies<B...>> final : public CompiledScene {
  using Id = std::variant<BodyId<B>...>;
  template <class T>
  static constexpr bool kHasLoad = TupleHas<T, typename SceneT::LoadTypes>::value;
  template <ReferencePoint Ref> static constexpr bool kHasBody = ((B::reference == Ref) || ...);
  static constexpr bool kLean =
      sizeof...(B) == 1 && std::tuple_size_v<typename SceneT::LoadTypes> == 0;
  /// The state size of a lean scene's one body.
  static constexpr int kOneBody = state_size<SceneT, B...>;

 public:
  SceneOfBodies(const std::vector<BodyRecord>& bodies, const std::vector<LoadRecord>& loads,
                const std::vector<PythonEvent>& events) {
    if (kLean && bodies.size() != 1) {
      throw std::logic_error("tumble: a lean scene of more than one body");
    }
    for (const BodyRecord& r : bodies) {
      const void* native = r.body->rigid_body();
      const auto add = [&]<class Body>() {  // r's body, if its type is Body
        if (r.body->reference() != Body::reference) {
          return false;
        }
        ids_.emplace_back(scene_.add(*static_cast<const Body*>(native), r.initial));
        return true;
      };
      const bool added = (add.template operator()<B>() || ...);
      if (!added) {
        throw std::logic_error("tumble: a body's reference point not in the compiled scene");
      }
    }
    for (const LoadRecord& l : loads) {
      std::visit(
          [&](const auto& load) {
            using L = std::decay_t<decltype(load)>;
            if constexpr (std::is_same_v<L, PythonLoad>) {
              if constexpr (kHasLoad<UserForce<PythonLoad>>) {
                std::visit([&](auto a) { scene_.add_load(a, UserForce<PythonLoad>(load)); },
                           ids_.at(l.a));
              } else {
                throw std::logic_error("tumble: a Python load in a scene compiled without one");
              }
            } else if constexpr (!kHasLoad<L>) {
              throw std::logic_error("tumble: a load in a scene compiled without loads");
            } else if constexpr (std::is_same_v<L, SpringDamperBetween>) {
              std::visit([&](auto a, auto b) { scene_.add_load(a, b, load); }, ids_.at(l.a),
                         ids_.at(l.b));
            } else {
              std::visit([&](auto a) { scene_.add_load(a, load); }, ids_.at(l.a));
            }
          },
          l.load);
    }
    // The events read the state through this scene (its per-body records): it is built in place
    // and never moved (build_scene's unique_ptr), so `this` outlives them.
    for (const PythonEvent& e : events) {
      Event ev;
      ev.function = [e, this](double t, const SceneStateView& s) { return e.value(t, s, *this); };
      ev.direction = e.direction();
      if (e.has_action()) {
        ev.action = [e, this](double t, SceneState& s) { e.act(t, s, *this); };
      }
      scene_.add_event(std::move(ev));
    }
  }

  [[nodiscard]] int size() const override { return scene_.size(); }
  [[nodiscard]] int body_count() const override { return static_cast<int>(ids_.size()); }
  [[nodiscard]] const SceneState& initial_state() const override { return scene_.initial_state(); }
  [[nodiscard]] std::pair<int, int> layout(int id) const override {
    return std::visit(
        [&](auto b) {
          const auto& e = scene_.entry(b);
          return std::pair<int, int>(e.offset, e.rates);
        },
        ids_.at(id));
  }

  [[nodiscard]] double kinetic_energy(const SceneState& s) const override {
    return tumble::kinetic_energy(scene_, s);
  }
  [[nodiscard]] double potential_energy(const SceneState& s) const override {
    return tumble::potential_energy(scene_, s);
  }
  [[nodiscard]] Eigen::Vector3d linear_momentum(const SceneState& s) const override {
    return tumble::linear_momentum(scene_, s);
  }
  [[nodiscard]] Eigen::Vector3d angular_momentum(const SceneState& s) const override {
    return tumble::angular_momentum(scene_, s);
  }
  [[nodiscard]] double constraint_drift(const SceneState& s) const override {
    return tumble::constraint_drift(scene_, s);
  }
  [[nodiscard]] Eigen::Matrix3d rotation(int id, const SceneState& s) const override {
    return std::visit([&](auto b) { return tumble::rotation(scene_, b, s); }, ids_.at(id));
  }
  [[nodiscard]] Eigen::Vector3d omega(int id, const SceneState& s) const override {
    return std::visit([&](auto b) { return tumble::omega(scene_, b, s); }, ids_.at(id));
  }
  [[nodiscard]] Eigen::Vector3d position(int id, const SceneState& s) const override {
    return std::visit([&](auto b) { return tumble::position(scene_, b, s); }, ids_.at(id));
  }
  [[nodiscard]] Eigen::Vector3d velocity(int id, const SceneState& s) const override {
    return std::visit([&](auto b) { return tumble::velocity(scene_, b, s); }, ids_.at(id));
  }
  [[nodiscard]] Eigen::Vector3d reaction_force(int id, const SceneState& s,
                                               double t) const override {
    using Fixed = RB<P, ReferencePoint::fixed_point>;
    if constexpr (kHasBody<ReferencePoint::fixed_point>) {
      if (const auto* b = std::get_if<BodyId<Fixed>>(&ids_.at(id))) {
        return tumble::reaction_force(scene_, *b, s, t);
      }
    }
    throw std::invalid_argument("tumble.Scene.reaction_force: body " + std::to_string(id) +
                                " is not held at a fixed point");
  }
  [[nodiscard]] Eigen::VectorXd rhs(double t, const SceneState& s) const override {
    SceneWorkspace<SceneT> ws(scene_);
    Eigen::VectorXd ydot(scene_.size());
    tumble::rhs(scene_, ws, t, s, ydot);
    return ydot;
  }

  [[nodiscard]] RawTrajectory integrate(double t0, const SceneState& s0,
                                        const std::vector<double>& times,
                                        const RunOptions& o) const override {
    RawTrajectory out;
    const auto observe = [&](double t, const SceneState& s) {
      out.t.push_back(t);
      out.y.insert(out.y.end(), s.y.data(), s.y.data() + s.y.size());
      for (const Eigen::Matrix3d& b : s.base) {
        for (int i = 0; i < 3; ++i) {
          for (int j = 0; j < 3; ++j) {
            out.bases.push_back(b(i, j));  // row-major, as NumPy prints it
          }
        }
      }
      record(s, out.bodies);
      out.energy.push_back(tumble::energy(scene_, s));
    };
    with_integrator(o, t0, s0, [&](auto& integrator, const std::string& method) {
      integrator.integrate(times, observe);
      out.statistics = statistics(integrator, method);
    });
    return out;
  }

  [[nodiscard]] RawEnsemble ensemble(double t0, const std::vector<double>& y0, std::size_t runs,
                                     const std::vector<double>& times, const RunOptions& o,
                                     int threads) const override {
    const auto n = static_cast<std::size_t>(scene_.size());
    const std::size_t per_time = n + ids_.size() * kRecordPerBody + 1;
    const auto initial = [&](std::size_t i) {
      SceneState s = scene_.initial_state();
      s.y = Eigen::Map<const Eigen::VectorXd>(y0.data() + i * n, static_cast<Eigen::Index>(n));
      return s;
    };
    const auto observe = [&](std::vector<double>& r, std::size_t, double, const SceneState& s) {
      r.insert(r.end(), s.y.data(), s.y.data() + s.y.size());
      record(s, r);
      r.push_back(tumble::energy(scene_, s));
    };
    RawEnsemble out;
    const auto run = [&](auto make) {
      const Ensemble ensemble(scene_, make, {.threads = threads});
      const auto outcomes =
          ensemble.template integrate<std::vector<double>>(runs, initial, t0, times, observe);
      out.threads = ensemble.statistics().threads;
      const std::size_t body_values = ids_.size() * kRecordPerBody;
      const double nan = std::numeric_limits<double>::quiet_NaN();
      out.y.assign(runs * times.size() * n, nan);
      out.bodies.assign(runs * times.size() * body_values, nan);
      out.energy.assign(runs * times.size(), nan);
      for (std::size_t i = 0; i < runs; ++i) {
        if (outcomes[i].failed()) {
          out.errors.emplace_back(i, outcomes[i].error().message);
          continue;
        }
        const std::vector<double>& r = outcomes[i].value();
        for (std::size_t k = 0; k < times.size(); ++k) {
          const double* at = r.data() + k * per_time;
          std::copy(at, at + n,
                    out.y.begin() + static_cast<std::ptrdiff_t>((i * times.size() + k) * n));
          std::copy(at + n, at + n + body_values,
                    out.bodies.begin() +
                        static_cast<std::ptrdiff_t>((i * times.size() + k) * body_values));
          out.energy[i * times.size() + k] = at[n + body_values];
        }
      }
    };
    with_factory(o, [&](auto make, const std::string&) { run(make); });
    return out;
  }

  void record(const SceneStateView& s, std::vector<double>& out) const override {
    for (const Id& id : ids_) {
      std::visit(
          [&](auto b) {
            const Eigen::Vector3d r = tumble::position(scene_, b, s);
            const Eigen::Quaterniond q = tumble::quaternion(scene_, b, s);  // w >= 0
            const Eigen::Vector3d v = tumble::velocity(scene_, b, s);
            const Eigen::Vector3d w = tumble::omega(scene_, b, s);
            out.insert(out.end(), {r(0), r(1), r(2), q.w(), q.x(), q.y(), q.z(), v(0), v(1), v(2),
                                   w(0), w(1), w(2)});
          },
          id);
    }
  }

 private:
  template <class O> static O shared(const RunOptions& o) {
    O opt;
    opt.rtol = o.rtol;
    opt.atol = o.atol;
    opt.max_steps = o.max_steps;
    opt.initial_step = o.initial_step;
    if (o.max_step > 0) {
      opt.max_step = o.max_step;
    }
    return opt;
  }
  static AutoOptions auto_options(const RunOptions& o) { return shared<AutoOptions>(o); }
  static SceneIntegratorOptions cvode_options(const RunOptions& o) {
    auto opt = shared<SceneIntegratorOptions>(o);
    opt.method = o.method == "adams" ? CvodeMethod::adams : CvodeMethod::bdf;
    return opt;
  }
  static OdeintOptions odeint_options(const RunOptions& o) {
    auto opt = shared<OdeintOptions>(o);
    if (o.method == "fehlberg78") {
      opt.method = OdeintMethod::fehlberg78;
    } else if (o.method == "dopri5") {
      opt.method = OdeintMethod::dopri5;
    } else if (o.method == "cash_karp54") {
      opt.method = OdeintMethod::cash_karp54;
    } else {
      throw std::invalid_argument("tumble: unknown method '" + o.method +
                                  "'; known: auto, fehlberg78, dopri5, cash_karp54, bdf, adams");
    }
    return opt;
  }

  /// The state sizes of a scene of one body: free ([r; theta; v; omega]) or held at a fixed point
  /// ([theta; omega]).
  static constexpr int kFree = state_size<SceneT, RB<P, ReferencePoint::centroid>>;
  static constexpr int kHeld = state_size<SceneT, RB<P, ReferencePoint::fixed_point>>;
  static_assert(kFree != kHeld && state_size<SceneT, RB<P, ReferencePoint::offset>> == kFree);

  /// Calls f(make, method name) with make(scene, t0, s0) constructing the integrator the options
  /// name (the method's name empty for the front door, whose statistics say what ran). The one
  /// place where the method's name chooses an integrator: single runs and ensembles share it.
  /// Odeint's integrator of a scene of one body's size (kFree or kHeld) has the size at compile
  /// time, as the C++ ensemble study's: a std::array state, whose stage loops (Odeint's
  /// array_algebra) run about half the instructions of the std::vector's (range_algebra): the
  /// free MRP body's run, 12 states, 0.77x the instructions and 0.9x the time
  /// (docs/benchmarks/python.md). Any other size: Eigen::Dynamic. The same method, steps and
  /// stage arithmetic; the initial step's estimate (a mean over the entries) may round otherwise.
  template <class F> void with_factory(const RunOptions& o, F&& f) const {
    const int size = scene_.size();
    if (o.method == "auto") {
      // A lean scene's one body fixes the explicit path's size: the same steps and results as
      // Eigen::Dynamic, and in this unit half the time (the tumbling body held, 1e-8, 101 outputs:
      // 159 -> 79 us from Python).
      constexpr int n = kLean ? kOneBody : Eigen::Dynamic;
      f(
          [opt = auto_options(o)](const SceneT& s, double t, const SceneState& y) {
            return AutoIntegrator<SceneT, n>(s, t, y, opt);
          },
          std::string());
    } else if (o.method == "bdf" || o.method == "adams") {
      f(
          [opt = cvode_options(o)](const SceneT& s, double t, const SceneState& y) {
            return SceneIntegrator<SceneT>(s, t, y, opt);
          },
          o.method == "bdf" ? std::string("BDF (SceneIntegrator, CVODE)")
                            : std::string("Adams (SceneIntegrator, CVODE)"));
    } else {
      const auto odeint = [&]<int N>() {
        f(
            [opt = odeint_options(o)](const SceneT& s, double t, const SceneState& y) {
              return OdeintIntegrator<SceneT, N>(s, t, y, opt);
            },
            o.method + " (OdeintIntegrator)");
      };
      if constexpr (kLean) {  // one body (the constructor checked): its size only
        odeint.template operator()<kOneBody>();
      } else if (size == kFree) {
        odeint.template operator()<kFree>();
      } else if (size == kHeld) {
        odeint.template operator()<kHeld>();
      } else {
        odeint.template operator()<Eigen::Dynamic>();
      }
    }
  }

  /// Calls f(integrator, method name) with the integrator the options name, from (t0, s0).
  template <class F>
  void with_integrator(const RunOptions& o, double t0, const SceneState& s0, F&& f) const {
    with_factory(o, [&](auto make, const std::string& method) {
      auto integrator = make(scene_, t0, s0);
      f(integrator, method);
    });
  }

  template <class Integrator>
  static RunStatistics statistics(const Integrator& integrator, const std::string& method) {
    const auto st = integrator.statistics();
    RunStatistics r;
    r.steps = st.steps;
    r.rejected_steps = st.rejected_steps;
    r.rhs_evals = st.rhs_evals;
    r.chart_switches = st.chart_switches;
    r.projections = st.projections;
    r.events = st.events;
    if constexpr (std::is_same_v<std::decay_t<decltype(st)>, AutoStatistics>) {
      for (const MethodChoice& c : st.choices) {
        r.choices.emplace_back(name(c.method), c.from, c.why);
      }
      r.method = name(st.method());
    } else {
      r.method = method;
      r.choices.emplace_back(method, 0.0, "asked for");
    }
    return r;
  }

  SceneT scene_;
  std::vector<Id> ids_;
};

}  // namespace tumble::python::detail
