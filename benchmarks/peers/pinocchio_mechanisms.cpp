// tumble_bench, study (e): Pinocchio's articulated-body algorithm on the open spatial chain, when
// Pinocchio's headers are found (`pip install pin`; peers/peers.cmake, and main/tumble_bench.cmake
// defines TUMBLE_BENCH_HAVE_PINOCCHIO for this file only). Without it: no rows.
//
// The model, as a Pinocchio user builds a chain of hinges: one JointModelRevoluteUnaligned per
// hinge of the SpatialLinkage, its parent the joint of the hinge's body b (the universe for the
// ground), every joint frame parallel to the world's at q = 0 and placed at the hinge's point, so
// the placements are the differences of those points and each axis is the hinge's world axis; each
// body's inertia appended to its joint with its centroid's lever and its inertia turned into world
// axes (R I R^T). q = 0 is the linkage's start and v its hinges' rates. Gravity is the linkage's.
//
// The integration, as a Pinocchio user integrates an open chain: the first-order system
// y = (q, v), q' = v, v' = aba(q, v, tau = 0), in Boost.Odeint's controlled Fehlberg 7(8)
// (runge_kutta_fehlberg78, rtol = atol = tol) through integrate_times over the output times, a
// std::vector state viewed by Eigen::Map. A run is timed as tumble's rows are (mechanisms/run.hpp:
// best of Timing::reps; the model and Data are built outside the timing, as a tumble scene is):
// the stepper's construction, the integration and, at each output, the tracked point by
// forwardKinematics, which tumble's rows also compute inside the timing. Counters: the steps
// integrate_times reports and the calls of aba. |C|: 0, joint coordinates close no loop.

#include <string>
#include <vector>

#include "common/bench.hpp"
#include "mechanisms/mechanisms.hpp"

#if defined(TUMBLE_BENCH_HAVE_PINOCCHIO) && TUMBLE_BENCH_HAVE_PINOCCHIO

#include <cstddef>
#include <exception>
#include <functional>
#include <stdexcept>
#include <utility>

#include <Eigen/Core>
#include <boost/numeric/odeint.hpp>
#include <pinocchio/algorithm/aba.hpp>
#include <pinocchio/algorithm/kinematics.hpp>
#include <pinocchio/multibody.hpp>

#include "mechanisms/track.hpp"

namespace tumble::bench {
namespace {

/// The chain in Pinocchio, its Data and the tracked point, with the right-hand side for Odeint.
struct PinocchioChain {
  using State = std::vector<double>;
  pinocchio::Model model;
  pinocchio::Data data;
  pinocchio::JointIndex track_joint = 0;
  Eigen::Vector3d track_point;  // in track_joint's frame (m)
  Eigen::VectorXd tau;          // no actuation
  long calls = 0;               // of aba

  explicit PinocchioChain(const SpatialLinkage& l) {
    model.gravity.linear(l.gravity);
    model.gravity.angular(Eigen::Vector3d::Zero());
    std::vector<pinocchio::JointIndex> joint_of;  // body i's joint
    for (std::size_t i = 0; i < l.hinges.size(); ++i) {
      const SpatialLinkage::Hinge& h = l.hinges[i];
      if (h.a != static_cast<int>(i) || h.b >= h.a) {
        throw std::invalid_argument("Pinocchio's chain: hinge i must hold body i to a parent < i");
      }
      const bool from_ground = h.b < 0;
      const Eigen::Vector3d parent_at =
          from_ground ? Eigen::Vector3d::Zero() : l.hinges[static_cast<std::size_t>(h.b)].at;
      const pinocchio::JointIndex parent =
          from_ground ? 0 : joint_of[static_cast<std::size_t>(h.b)];
      const pinocchio::JointIndex j =
          model.addJoint(parent, pinocchio::JointModelRevoluteUnaligned(h.axis),
                         pinocchio::SE3(Eigen::Matrix3d::Identity(), h.at - parent_at),
                         "hinge" + std::to_string(i));
      const SpatialLinkage::Body& b = l.bodies[i];
      const Eigen::Matrix3d inertia = b.rotation * b.inertia * b.rotation.transpose();
      model.appendBodyToJoint(j, pinocchio::Inertia(b.mass, b.centroid - h.at, inertia),
                              pinocchio::SE3::Identity());
      joint_of.push_back(j);
    }
    const auto k = static_cast<std::size_t>(l.track_body);
    track_joint = joint_of.at(k);
    track_point = l.bodies[k].centroid + l.bodies[k].rotation * l.track_point - l.hinges[k].at;
    tau = Eigen::VectorXd::Zero(model.nv);
    data = pinocchio::Data(model);
  }

  [[nodiscard]] State start(const SpatialLinkage& l) const {
    State y(static_cast<std::size_t>(model.nq + model.nv), 0.0);
    for (std::size_t i = 0; i < l.hinges.size(); ++i) {
      y[static_cast<std::size_t>(model.nq) + i] = l.hinges[i].rate;
    }
    return y;
  }

  void operator()(const State& y, State& dy, double /*t*/) {
    const Eigen::Map<const Eigen::VectorXd> q(y.data(), model.nq), v(y.data() + model.nq, model.nv);
    pinocchio::aba(model, data, q, v, tau);
    ++calls;
    Eigen::Map<Eigen::VectorXd>(dy.data(), model.nq) = v;
    Eigen::Map<Eigen::VectorXd>(dy.data() + model.nq, model.nv) = data.ddq;
  }

  /// The tracked point at the configuration of y (m).
  Eigen::Vector3d tip(const State& y) {
    pinocchio::forwardKinematics(model, data,
                                 Eigen::Map<const Eigen::VectorXd>(y.data(), model.nq));
    return data.oMi[track_joint].act(track_point);
  }
};

}  // namespace

std::vector<MechanismRow> pinocchio_chain_rows(const SpatialLinkage& l,
                                               const std::vector<double>& times,
                                               const std::vector<double>& tolerances,
                                               PointTrackError& tip, const Timing& timing) {
  namespace odeint = boost::numeric::odeint;
  using State = PinocchioChain::State;
  std::vector<MechanismRow> rows;
  std::vector<double> from_zero{0.0};  // integrate_times observes its first time: the start
  from_zero.insert(from_zero.end(), times.begin(), times.end());
  for (const double tol : tolerances) {
    MechanismRow r;
    r.method = "Pinocchio aba + Odeint F78";
    r.tol = tol;
    std::vector<double> seconds;
    try {
      PinocchioChain chain(l);  // the model and Data: not timed, like building a tumble scene
      const State y0 = chain.start(l);
      do {
        State y = y0;
        chain.calls = 0;
        std::size_t k = 0;  // the output observed next: 0 the start, k the k-th of `times`
        const Stopwatch watch;
        const std::size_t steps = odeint::integrate_times(
            odeint::make_controlled(tol, tol, odeint::runge_kutta_fehlberg78<State>()),
            std::ref(chain), y, from_zero.begin(), from_zero.end(), times.front() / 10,
            [&](const State& x, double) {
              if (k > 0) {
                tip.record(k - 1, chain.tip(x));
              }
              ++k;
            });
        record_time(r.run, seconds, watch, timing);
        r.run.steps = static_cast<long>(steps);
        r.run.rhs_evals = chain.calls;
        r.run.constraint_drift = 0;  // joint coordinates: no constraint to drift from
      } while (another_rep(timing, seconds));
    } catch (const std::exception& e) {
      r.run.ok = false;
      r.run.error = e.what();
    }
    finish_timing(r.run, seconds);
    const double error = tip.measure();  // also clears what a failed run recorded
    if (r.run.ok) {
      r.error = error;
    }
    const bool failed = !r.run.ok;
    rows.push_back(std::move(r));
    if (failed) {
      break;  // as tumble's ladders: the tighter tolerances are not tried
    }
  }
  return rows;
}

}  // namespace tumble::bench

#else

namespace tumble::bench {

std::vector<MechanismRow> pinocchio_chain_rows(const SpatialLinkage& /*l*/,
                                               const std::vector<double>& /*times*/,
                                               const std::vector<double>& /*tolerances*/,
                                               PointTrackError& /*tip*/, const Timing& /*timing*/) {
  return {};
}

}  // namespace tumble::bench

#endif
