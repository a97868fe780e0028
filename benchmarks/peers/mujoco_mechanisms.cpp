// tumble_bench, study (e): MuJoCo's fixed-step RK4 (mj_step with integrator="RK4") on the IFToMM
// mechanisms, when MuJoCo is installed (`pip install mujoco`; found by peers/peers.cmake, and
// main/tumble_bench.cmake defines TUMBLE_BENCH_HAVE_MUJOCO for this file only). Without it the
// functions below return no rows.
//
// Each problem is an MJCF model written as a MuJoCo user writes it: bodies with an <inertial>
// element and no geoms (no collision work), an open tree of hinge joints (MuJoCo's joint
// coordinates), and, where the mechanism has closed loops, <connect> equality constraints that
// close them. MuJoCo's equality constraints are soft by design (solref, solimp: a spring-damper
// in constraint space, solved with the rest of the constraint forces); each closed loop runs
// twice, with MuJoCo's defaults and with the stiffest setting MuJoCo allows at the step h,
// solref = (2 h, 1) and solimp = (0.9999, 0.9999, ...) (Softness below). The models:
//   A01  one hinge about z at the origin, the bob a 1 kg body at (1, 0, 0) with a negligible
//        rotational inertia (1e-12 kg m^2: a point mass, as the reference is; tumble's ball of
//        4e-5 kg m^2 hangs on a bar with spherical ends and does not turn, while a hinge would
//        turn it and add its inertia to the bar's, 8.7e-4 m off the closed form after 10 s);
//   A04  built from the example's scene by mechanisms/bricard.cpp (SpatialLinkage), as the
//        chain below: the five hinges from the ground along the cube's edges its tree, and the
//        sixth hinge, at P5, closed by two <connect>s (P5 and a point 1 m along its axis: a
//        hinge is two points of its axis);
//   A05  an open tree (shaft, slider, two rods with their balls), the spring-dampers spatial
//        tendons (stiffness, damping, springlength), run with RK4 and with implicitfast;
//   A03  the links as a tree from the ground, built from the example's data by
//        mechanisms/andrews.cpp (PlanarLinkage), the three hinges at E that close its loops as
//        <connect>s, the spring a spatial tendon (stiffness, springlength), the motor a <motor>
//        actuator whose ctrl, the constant torque, a keyframe sets;
//   A02  the same construction from mechanisms/four_bar.cpp's PlanarLinkage: the cranks hinged
//        to the ground, each coupler hanging from its crank's tip, the hinge at the next crank's
//        tip a <connect>; gravity, no spring or motor, and the starting velocity the keyframe's
//        qvel (each hinge's rate relative to its parent: -1 rad/s on the cranks, +1 on the
//        couplers, which translate).
//   chain the open spatial chain (mechanisms/chain.cpp, SpatialLinkage): a tree of hinges, no
//        equality constraint; each body framed at its centroid parallel to the world's (qpos = 0
//        is the start), its inertia turned into world axes (fullinertia), the hinges' rates at
//        the start a keyframe's qvel.
// The step is swept as the single-body peer sweeps it (peers/mujoco_work_precision.cpp): a fixed
// number of steps per output interval. A run is timed as that peer times it (common/bench.hpp):
// the model's compilation and mj_makeData are not timed, mj_resetData is not; the steps and, at
// each output, mj_kinematics and reading what the problem measures are. After the run, the
// largest equality-constraint violation (mj_fwdPosition, |efc_pos|) is the row's |C|. A run in
// which MuJoCo found a bad state (and reset itself, its warning mjWARN_BADQACC) fails.

#include <functional>
#include <string>
#include <vector>

#include "common/bench.hpp"
#include "mechanisms/mechanisms.hpp"

#if defined(TUMBLE_BENCH_HAVE_MUJOCO) && TUMBLE_BENCH_HAVE_MUJOCO

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <exception>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <utility>

#include <Eigen/Core>
#include <mujoco/mujoco.h>

#include "common/format.hpp"
#include "mechanisms/track.hpp"
#include "peers/mujoco_handles.hpp"

namespace tumble::bench {
namespace {

std::unique_ptr<mjModel, ModelDeleter> load(const std::string& mjcf) {
  std::array<char, 1000> error{};
  const std::unique_ptr<mjSpec, SpecDeleter> spec(
      mj_parseXMLString(mjcf.c_str(), nullptr, error.data(), int(error.size())));
  std::unique_ptr<mjModel, ModelDeleter> model;
  if (spec) {
    model.reset(mj_compile(spec.get(), nullptr));
    if (!model) {
      throw std::runtime_error(std::string("MuJoCo could not compile the model: ") +
                               mjs_getError(spec.get()));
    }
  }
  if (!model) {
    throw std::runtime_error(std::string("MuJoCo could not load the model: ") + error.data());
  }
  return model;
}

/// The soft constraints' setting of a sweep: MuJoCo's defaults (solref = (0.02 s, 1), solimp =
/// (0.9, 0.95, 0.001, 0.5, 2)), or the stiffest MuJoCo allows at the step h: the time constant at
/// the smallest value its documentation calls stable, 2 h (below it, MuJoCo's refsafe raises it
/// to 2 h anyway), critical damping, and the impedance at its largest value, 0.9999 (mjMAXIMP),
/// over the whole width (dmin = dmax).
enum class Softness { defaults, stiffest };

/// A constraint's solref and solimp attributes for `softness` at the step h ("": the defaults).
std::string soft(Softness softness, double h) {
  if (softness == Softness::defaults) {
    return "";
  }
  std::ostringstream os;
  os.precision(17);
  os << " solref=\"" << 2 * h << " 1\" solimp=\"0.9999 0.9999 0.001 0.5 2\"";
  return os.str();
}

const char* label(Softness softness) {
  return softness == Softness::defaults ? "MuJoCo RK4 (defaults)" : "MuJoCo RK4 (stiffest)";
}

/// One timed run of `model` over `times`, `substeps` steps per output interval; record(k, model,
/// data) at the k-th output.
template <class Record>
void timed_run(mjModel& model, const std::vector<double>& times, int substeps, const Timing& timing,
               Record& record, Run& run) {
  std::vector<double> seconds;
  try {
    const std::unique_ptr<mjData, DataDeleter> data(mj_makeData(&model));
    mjData* d = data.get();
    do {
      if (model.nkey > 0) {
        mj_resetDataKeyframe(&model, d, 0);
      } else {
        mj_resetData(&model, d);
      }
      const Stopwatch watch;
      double t = 0;
      long steps = 0;
      for (std::size_t k = 0; k < times.size(); ++k) {
        model.opt.timestep = (times[k] - t) / substeps;
        for (int i = 0; i < substeps; ++i) {
          mj_step(&model, d);
        }
        steps += substeps;
        t = times[k];
        mj_kinematics(&model, d);  // mj_step leaves the kinematics of its last stage
        record(k, model, *d);
      }
      record_time(run, seconds, watch, timing);
      if (d->warning[mjWARN_BADQACC].number > 0 || d->warning[mjWARN_BADQVEL].number > 0 ||
          d->warning[mjWARN_BADQPOS].number > 0 ||
          std::abs(d->time - times.back()) > 1e-6 * times.back()) {
        throw std::runtime_error("unstable: MuJoCo found a bad state and reset the simulation");
      }
      run.steps = steps;  // RK4: four forward dynamics per step; Euler, implicitfast: one
      run.rhs_evals = (model.opt.integrator == mjINT_RK4 ? 4 : 1) * steps;
      mj_fwdPosition(&model, d);
      run.constraint_drift = 0;
      for (int i = 0; i < d->nefc; ++i) {
        if (d->efc_type[i] == mjCNSTR_EQUALITY) {
          run.constraint_drift = std::max(run.constraint_drift, std::abs(d->efc_pos[i]));
        }
      }
    } while (another_rep(timing, seconds));
  } catch (const std::exception& e) {
    run.ok = false;
    run.error = e.what();
  }
  finish_timing(run, seconds);
}

/// The sweep: for each number of steps per output interval in `ladder`, the model mjcf(h) (h the
/// step of the first interval), one timed run, and its error by `measure()`. The models of a
/// sweep differ in solref only: `record` may keep the ids it looked up in the first.
template <class Model, class Record, class Measure>
std::vector<MechanismRow> rk4_sweep(const std::string& method, const Model& mjcf,
                                    const std::vector<double>& times,
                                    const std::vector<int>& ladder, const Timing& timing,
                                    Record record, Measure measure) {
  std::vector<MechanismRow> rows;
  for (const int substeps : ladder) {
    const double h = times.front() / substeps;
    MechanismRow r;
    r.method = method;
    r.tol = std::numeric_limits<double>::quiet_NaN();  // a fixed step, no tolerance
    r.note = "h = " + sci(h) + " s, " + std::to_string(substeps) + " steps per output";
    try {
      const auto model = load(mjcf(h));
      timed_run(*model, times, substeps, timing, record, r.run);
    } catch (const std::exception& e) {
      r.run.ok = false;
      r.run.error = e.what();
    }
    const double error = measure();  // also clears what a failed run recorded
    if (r.run.ok) {
      r.error = error;
    }
    rows.push_back(std::move(r));
  }
  return rows;
}

/// Steps per output interval, doubling from `from` to `to`.
std::vector<int> doubling(int from, int to) {
  std::vector<int> ladder;
  for (int n = from; n <= to; n *= 2) {
    ladder.push_back(n);
  }
  return ladder;
}

/// Records the world position of the site named "track" into `track` at each output.
auto site_recorder(PointTrackError& track) {
  return [&track, site = -1](std::size_t k, const mjModel& m, const mjData& d) mutable {
    if (site < 0) {
      site = mj_name2id(&m, mjOBJ_SITE, "track");
    }
    const mjtNum* p = d.site_xpos + 3 * site;
    track.record(k, Eigen::Vector3d(p[0], p[1], p[2]));
  };
}

std::string vec(double x, double y, double z) {
  std::ostringstream os;
  os.precision(17);
  os << x << ' ' << y << ' ' << z;
  return os.str();
}

}  // namespace

std::vector<MechanismRow> mujoco_a01_rows(const std::vector<double>& times, PointTrackError& bob,
                                          const Timing& timing) {
  const auto mjcf = [](double) {
    return std::string(
        "<mujoco model=\"A01\"><option integrator=\"RK4\" gravity=\"0 -9.81 0\"/><worldbody>"
        "<body name=\"bob\" pos=\"1 0 0\"><joint type=\"hinge\" pos=\"-1 0 0\" axis=\"0 0 1\"/>"
        "<inertial pos=\"0 0 0\" mass=\"1\" diaginertia=\"1e-12 1e-12 1e-12\"/>"
        "<site name=\"track\"/></body></worldbody></mujoco>");
  };
  return rk4_sweep("MuJoCo RK4", mjcf, times, doubling(2, 1024), timing, site_recorder(bob),
                   [&] { return bob.measure(); });
}

std::vector<MechanismRow> mujoco_planar_rows(const std::string& id, const PlanarLinkage& m,
                                             const std::vector<double>& times,
                                             const PlanarMeasure& measure, const Timing& timing) {
  const std::size_t n = m.links.size();
  std::string model_name = id;
  std::transform(model_name.begin(), model_name.end(), model_name.begin(),
                 [](unsigned char c) { return char(std::toupper(c)); });
  const bool spring = m.stiffness != 0, motor = m.torque != 0;
  const bool moving = std::any_of(m.links.begin(), m.links.end(),
                                  [](const PlanarLinkage::Link& l) { return l.rate != 0; });
  // Each link's body frame sits at its hinge to its parent, parallel to the world's (qpos = 0 is
  // the starting configuration); its absolute angle is its starting angle plus the hinge angles
  // on its path from the ground, and its hinge's rate (qvel) is its absolute rate less its
  // parent's.
  const auto mjcf = [&](Softness softness, double h) {
    std::ostringstream os;
    os.precision(17);
    os << "<mujoco model=\"" << model_name << "\"><option integrator=\"RK4\" gravity=\""
       << vec(m.gravity.x(), m.gravity.y(), 0) << "\"/><worldbody>";
    if (spring) {
      os << "<site name=\"ground_end\" pos=\""
         << vec(m.spring_on_ground.x(), m.spring_on_ground.y(), 0) << "\"/>";
    }
    std::vector<int> order;  // the links in MuJoCo's order of bodies, hence of its hinges' dofs
    const std::function<void(int)> body = [&](int i) {
      order.push_back(i);
      const PlanarLinkage::Link& link = m.links[std::size_t(i)];
      const Eigen::Vector2d at =
          link.hinge -
          (link.parent < 0 ? Eigen::Vector2d::Zero() : m.links[std::size_t(link.parent)].hinge);
      const Eigen::Vector2d c = link.centroid - link.hinge;
      os << "<body name=\"link" << i << "\" pos=\"" << vec(at.x(), at.y(), 0)
         << "\"><joint name=\"hinge" << i << "\" type=\"hinge\" axis=\"0 0 1\"/><inertial pos=\""
         << vec(c.x(), c.y(), 0) << "\" mass=\"" << link.mass << "\" diaginertia=\""
         << vec(link.inertia, link.inertia, link.inertia) << "\"/>";
      if (spring && i == m.spring_link) {
        const Eigen::Vector2d p = m.spring_on_link - link.hinge;
        os << "<site name=\"link_end\" pos=\"" << vec(p.x(), p.y(), 0) << "\"/>";
      }
      for (std::size_t k = 0; k < n; ++k) {
        if (m.links[k].parent == i) {
          body(int(k));
        }
      }
      os << "</body>";
    };
    for (std::size_t k = 0; k < n; ++k) {
      if (m.links[k].parent < 0) {
        body(int(k));
      }
    }
    os << "</worldbody><equality>";
    for (const PlanarLinkage::Loop& loop : m.loops) {
      const Eigen::Vector2d p = loop.at - m.links[std::size_t(loop.a)].hinge;
      os << "<connect body1=\"link" << loop.a << "\" body2=\""
         << (loop.b < 0 ? std::string("world") : "link" + std::to_string(loop.b)) << "\" anchor=\""
         << vec(p.x(), p.y(), 0) << "\"" << soft(softness, h) << "/>";
    }
    os << "</equality>";
    if (spring) {
      os << "<tendon><spatial stiffness=\"" << m.stiffness << "\" springlength=\"" << m.rest_length
         << "\"><site site=\"link_end\"/><site site=\"ground_end\"/></spatial>"
         << "</tendon>";
    }
    if (motor) {
      os << "<actuator><motor name=\"motor\" joint=\"hinge" << m.motor_link
         << "\" gear=\"1\"/></actuator>";
    }
    if (motor || moving) {  // the starting state: the motor's ctrl, the hinges' rates
      os << "<keyframe><key";
      if (motor) {
        os << " ctrl=\"" << m.torque << "\"";
      }
      if (moving) {
        os << " qvel=\"";
        for (std::size_t j = 0; j < order.size(); ++j) {
          const PlanarLinkage::Link& link = m.links[std::size_t(order[j])];
          os << (j ? " " : "")
             << link.rate - (link.parent < 0 ? 0.0 : m.links[std::size_t(link.parent)].rate);
        }
        os << "\"";
      }
      os << "/></keyframe>";
    }
    os << "</mujoco>";
    return os.str();
  };
  // The links' absolute angles at every output (NaN: not reached), kept for `measure`.
  const std::vector<double> unset(n, std::numeric_limits<double>::quiet_NaN());
  std::vector<std::vector<double>> angles(times.size(), unset);
  auto record = [&, qpos = std::vector<int>()](std::size_t k, const mjModel& model,
                                               const mjData& d) mutable {
    if (qpos.empty()) {
      for (std::size_t i = 0; i < n; ++i) {
        const std::string name = "hinge" + std::to_string(i);
        qpos.push_back(model.jnt_qposadr[mj_name2id(&model, mjOBJ_JOINT, name.c_str())]);
      }
    }
    for (std::size_t i = 0; i < n; ++i) {
      double& a = angles[k][i];
      a = m.links[i].angle;
      for (int j = int(i); j >= 0; j = m.links[std::size_t(j)].parent) {
        a += d.qpos[qpos[std::size_t(j)]];
      }
    }
  };
  auto measure_run = [&] {
    const bool reached = std::none_of(angles.begin(), angles.end(), [](const auto& at) {
      return std::any_of(at.begin(), at.end(), [](double a) { return std::isnan(a); });
    });
    const double e = reached ? measure(angles) : std::numeric_limits<double>::quiet_NaN();
    std::fill(angles.begin(), angles.end(), unset);
    return e;
  };
  std::vector<MechanismRow> rows;
  for (const Softness softness : {Softness::defaults, Softness::stiffest}) {
    auto mine = rk4_sweep(
        label(softness), [&](double h) { return mjcf(softness, h); }, times, doubling(1, 512),
        timing, record, measure_run);
    rows.insert(rows.end(), mine.begin(), mine.end());
  }
  return rows;
}

std::vector<MechanismRow> mujoco_a05_rows(const FlyballGovernor& g,
                                          const std::vector<double>& times, PointTrackError& slider,
                                          const Timing& timing) {
  // An open tree, no equality constraint: the shaft's hinge about z, the slider's slide along it
  // and each rod's hinge about y (rod 1's frame turned half a turn about z, so that both rods
  // point outward along their own +x and turn down by +beta). The spring-dampers are spatial
  // tendons; the keyframe sets qpos = (0, s0, alpha, alpha) and the spin. With RK4 the dampers
  // bound the step (explicit); implicitfast, which MuJoCo recommends for stiff damping, takes
  // their forces implicitly (and leaves out only the Coriolis and centripetal derivatives).
  const auto mjcf = [&](const char* integrator) {
    std::ostringstream os;
    os.precision(17);
    os << "<mujoco model=\"A05\"><option integrator=\"" << integrator << "\" gravity=\""
       << vec(0, 0, -g.gravity) << "\"/><worldbody><body name=\"shaft\">"
       << "<joint name=\"spin\" type=\"hinge\" axis=\"0 0 1\"/><inertial pos=\""
       << vec(0, 0, 0.5 * g.shaft_length) << "\" mass=\"" << g.shaft_mass << "\" diaginertia=\""
       << vec(g.shaft_inertia.x(), g.shaft_inertia.y(), g.shaft_inertia.z()) << "\"/>"
       << "<body name=\"slider\"><joint name=\"s\" type=\"slide\" axis=\"0 0 1\"/>"
       << "<inertial pos=\"0 0 0\" mass=\"" << g.slider_mass << "\" diaginertia=\""
       << vec(g.slider_inertia, g.slider_inertia, g.slider_inertia) << "\"/>"
       << "<site name=\"slider0\" pos=\"" << vec(g.offset, 0, 0)
       << "\"/><site name=\"slider1\" pos=\"" << vec(-g.offset, 0, 0) << "\"/></body>";
    for (int k = 0; k < 2; ++k) {
      os << "<body name=\"rod" << k << "\" pos=\"" << vec(k == 0 ? g.offset : -g.offset, 0, g.top)
         << "\" euler=\"0 0 " << 180 * k << "\"><joint type=\"hinge\" axis=\"0 1 0\"/>"
         << "<inertial pos=\"" << vec(g.rod_centroid, 0, 0) << "\" mass=\"" << g.rod_mass
         << "\" diaginertia=\"" << vec(g.rod_axial, g.rod_transverse, g.rod_transverse) << "\"/>"
         << "<site name=\"rod" << k << "\" pos=\"" << vec(0.5 * g.rod_length, 0, 0)
         << "\"/></body>";
    }
    os << "</body></worldbody><tendon>";
    for (int k = 0; k < 2; ++k) {
      os << "<spatial stiffness=\"" << g.stiffness << "\" damping=\"" << g.damping
         << "\" springlength=\"" << g.rest_length << "\"><site site=\"rod" << k
         << "\"/><site site=\"slider" << k << "\"/></spatial>";
    }
    os << "</tendon><keyframe><key qpos=\"0 " << g.s0 << ' ' << g.alpha << ' ' << g.alpha
       << "\" qvel=\"" << g.spin << " 0 0 0\"/></keyframe></mujoco>";
    return os.str();
  };
  auto record = [&slider, s = -1](std::size_t k, const mjModel& m, const mjData& d) mutable {
    if (s < 0) {
      s = m.jnt_qposadr[mj_name2id(&m, mjOBJ_JOINT, "s")];
    }
    slider.record(k, Eigen::Vector3d(d.qpos[s], 0, 0));
  };
  const auto measure = [&] { return slider.measure(); };
  // RK4 is unstable above h of about 1e-4 s here (the dampers: C / m of the slider is 1.3e4 /s);
  // the ladders start where a step still ends, so that the rows show where accuracy begins.
  std::vector<MechanismRow> rows = rk4_sweep(
      "MuJoCo RK4", [&](double) { return mjcf("RK4"); }, times, doubling(64, 4096), timing, record,
      measure);
  auto implicit = rk4_sweep(
      "MuJoCo implicitfast", [&](double) { return mjcf("implicitfast"); }, times,
      doubling(4, 16384), timing, record, measure);
  rows.insert(rows.end(), implicit.begin(), implicit.end());
  return rows;
}

std::vector<MechanismRow> mujoco_spatial_rows(const SpatialLinkage& l,
                                              const std::vector<double>& times,
                                              PointTrackError& track, const Timing& timing) {
  const std::size_t n = l.bodies.size();
  if (l.hinges.size() < n) {
    throw std::invalid_argument("MuJoCo's spatial linkage: a hinge per body at least");
  }
  for (std::size_t k = 0; k < l.hinges.size(); ++k) {
    const SpatialLinkage::Hinge& h = l.hinges[k];
    if (k < n ? h.a != int(k) || h.b >= int(k) : h.a < 0 || h.a >= int(n) || h.b >= int(n)) {
      throw std::invalid_argument("MuJoCo's spatial linkage: hinge i < n must hold body i to a "
                                  "parent < i, a further hinge two bodies of the linkage");
    }
  }
  const bool loops = l.hinges.size() > n;
  const Eigen::Vector3d& g = l.gravity;
  const auto model = [&](const std::string& softness) {
    std::ostringstream os;
    os.precision(17);
    os << "<mujoco model=\"spatial\"><option integrator=\"RK4\" gravity=\""
       << vec(g.x(), g.y(), g.z()) << "\"/><worldbody>";
    // Body i, then the bodies hinged to it, inside it (MJCF nests a tree); its position relative
    // to its parent's centroid (the world's origin for the ground), both frames world-parallel.
    const std::function<void(int)> body = [&](int i) {
      const auto ui = static_cast<std::size_t>(i);
      const SpatialLinkage::Body& b = l.bodies[ui];
      const SpatialLinkage::Hinge& h = l.hinges[ui];
      const Eigen::Vector3d from =
          h.b < 0 ? Eigen::Vector3d::Zero() : l.bodies[static_cast<std::size_t>(h.b)].centroid;
      const Eigen::Vector3d pos = b.centroid - from, at = h.at - b.centroid;
      const Eigen::Matrix3d j = b.rotation * b.inertia * b.rotation.transpose();
      os << "<body name=\"body" << i << "\" pos=\"" << vec(pos.x(), pos.y(), pos.z())
         << "\"><joint type=\"hinge\" pos=\"" << vec(at.x(), at.y(), at.z()) << "\" axis=\""
         << vec(h.axis.x(), h.axis.y(), h.axis.z()) << "\"/><inertial pos=\"0 0 0\" mass=\""
         << b.mass << "\" fullinertia=\"" << vec(j(0, 0), j(1, 1), j(2, 2)) << ' '
         << vec(j(0, 1), j(0, 2), j(1, 2)) << "\"/>";
      if (i == l.track_body) {
        const Eigen::Vector3d p = b.rotation * l.track_point;
        os << "<site name=\"track\" pos=\"" << vec(p.x(), p.y(), p.z()) << "\"/>";
      }
      for (std::size_t k = 0; k < n; ++k) {
        if (l.hinges[k].b == i) {
          body(int(k));
        }
      }
      os << "</body>";
    };
    for (std::size_t k = 0; k < n; ++k) {
      if (l.hinges[k].b < 0) {
        body(int(k));
      }
    }
    os << "</worldbody>";
    if (loops) {
      // A hinge that closes a loop holds two points of its axis together: its point and one 1 m
      // along the axis, each a <connect> anchored in body a's frame (world-parallel, at its
      // centroid); MuJoCo takes the other body's point from the starting configuration.
      os << "<equality>";
      for (std::size_t k = n; k < l.hinges.size(); ++k) {
        const SpatialLinkage::Hinge& h = l.hinges[k];
        const Eigen::Vector3d c = l.bodies[static_cast<std::size_t>(h.a)].centroid;
        for (const Eigen::Vector3d& p :
             {Eigen::Vector3d(h.at - c), Eigen::Vector3d(h.at - c + h.axis)}) {
          os << "<connect body1=\"body" << h.a << "\" body2=\""
             << (h.b < 0 ? std::string("world") : "body" + std::to_string(h.b)) << "\" anchor=\""
             << vec(p.x(), p.y(), p.z()) << "\"" << softness << "/>";
        }
      }
      os << "</equality>";
    }
    os << "<keyframe><key qvel=\"";
    for (std::size_t k = 0; k < n; ++k) {
      os << (k ? " " : "") << l.hinges[k].rate;
    }
    os << "\"/></keyframe></mujoco>";
    return os.str();
  };
  if (!loops) {
    // To 512 steps per output (h = 9.8e-5 s on the chain), where RK4's error (7e-13 m when
    // measured) nears the reference's own: a finer step would not be resolved.
    const std::string mjcf = model("");
    return rk4_sweep(
        "MuJoCo RK4", [&](double) { return mjcf; }, times, doubling(1, 512), timing,
        site_recorder(track), [&] { return track.measure(); });
  }
  std::vector<MechanismRow> rows;
  for (const Softness softness : {Softness::defaults, Softness::stiffest}) {
    auto mine = rk4_sweep(
        label(softness), [&](double h) { return model(soft(softness, h)); }, times,
        doubling(4, 1024), timing, site_recorder(track), [&] { return track.measure(); });
    rows.insert(rows.end(), mine.begin(), mine.end());
  }
  return rows;
}

}  // namespace tumble::bench

#else

namespace tumble::bench {

std::vector<MechanismRow> mujoco_a01_rows(const std::vector<double>& /*times*/,
                                          PointTrackError& /*bob*/, const Timing& /*timing*/) {
  return {};
}
std::vector<MechanismRow> mujoco_planar_rows(const std::string& /*id*/, const PlanarLinkage& /*m*/,
                                             const std::vector<double>& /*times*/,
                                             const PlanarMeasure& /*measure*/,
                                             const Timing& /*timing*/) {
  return {};
}
std::vector<MechanismRow> mujoco_a05_rows(const FlyballGovernor& /*g*/,
                                          const std::vector<double>& /*times*/,
                                          PointTrackError& /*slider*/, const Timing& /*timing*/) {
  return {};
}
std::vector<MechanismRow> mujoco_spatial_rows(const SpatialLinkage& /*l*/,
                                              const std::vector<double>& /*times*/,
                                              PointTrackError& /*track*/,
                                              const Timing& /*timing*/) {
  return {};
}

}  // namespace tumble::bench

#endif
