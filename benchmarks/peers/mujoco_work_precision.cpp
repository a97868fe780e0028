// tumble_bench: MuJoCo's fixed-step RK4 (mj_step with integrator="RK4") on the problems with a
// closed form, when MuJoCo is installed (`pip install mujoco`; found by peers/peers.cmake, and
// main/tumble_bench.cmake defines TUMBLE_BENCH_HAVE_MUJOCO for this file only). Without it the
// functions below say so and do nothing.
//
// The model is what a MuJoCo user writes: one body with an <inertial> element (the mass, the
// centroid at the reference point's offset, the principal inertia), no geoms (no collision work),
// and
//  - for the torque-free problems a ball joint: the attitude only (qpos = the quaternion
//    (w, x, y, z), body -> world; qvel = omega in the body frame), as the hand-written floors
//    [p; omega] and tumble's attitude-only scene;
//  - for the thrown body a free joint at the reference point (qpos = [r_oc; quaternion], qvel =
//    [rdot_oc (world); omega (body)]) under the problem's gravity.
// The step is swept as for the hand-written RK4 (MethodSetting::substeps per output interval);
// MuJoCo normalizes the quaternion after each step. Building the model is not timed (as building
// a tumble scene is not).

#include <string>
#include <vector>

#include "common/bench.hpp"

#if defined(TUMBLE_BENCH_HAVE_MUJOCO) && TUMBLE_BENCH_HAVE_MUJOCO

#include <array>
#include <cmath>
#include <memory>
#include <sstream>
#include <stdexcept>

#include <Eigen/Geometry>
#include <mujoco/mujoco.h>

#include "peers/mujoco_handles.hpp"

namespace tumble::bench {
namespace {

std::string mjcf(const Problem& p) {
  std::ostringstream os;
  os.precision(17);
  os << "<mujoco><option integrator=\"RK4\" gravity=\"" << p.gravity(0) << " " << p.gravity(1)
     << " " << p.gravity(2) << "\"/><worldbody><body name=\"b\">"
     << (torque_free(p) ? "<joint type=\"ball\"/>" : "<freejoint/>") << "<inertial pos=\""
     << p.centroid(0) << " " << p.centroid(1) << " " << p.centroid(2) << "\" mass=\"" << p.mass
     << "\" diaginertia=\"" << p.inertia(0) << " " << p.inertia(1) << " " << p.inertia(2)
     << "\"/></body></worldbody></mujoco>";
  return os.str();
}

std::unique_ptr<mjModel, ModelDeleter> load(const Problem& p) {
  std::array<char, 1000> error{};
  const std::unique_ptr<mjSpec, SpecDeleter> spec(
      mj_parseXMLString(mjcf(p).c_str(), nullptr, error.data(), int(error.size())));
  std::unique_ptr<mjModel, ModelDeleter> model;
  if (spec) {
    model.reset(mj_compile(spec.get(), nullptr));
  }
  if (!model) {
    throw std::runtime_error(std::string("MuJoCo could not load the model: ") + error.data());
  }
  return model;
}

}  // namespace

bool mujoco_available() { return true; }

Run run_mujoco(const Problem& p, const MethodSetting& c, const Timing& timing) {
  Run run;
  run.samples.resize(p.times.size());
  const bool ball = torque_free(p);
  const Eigen::Quaterniond q0(p.r0);
  std::vector<double> times;
  try {
    const auto model = load(p);
    const std::unique_ptr<mjData, DataDeleter> data(mj_makeData(model.get()));
    const int at = ball ? 0 : 3;  // the quaternion's place in qpos, omega's in qvel
    do {
      mj_resetData(model.get(), data.get());
      if (!ball) {
        for (int k = 0; k < 3; ++k) {
          data->qpos[k] = p.position0(k);
          data->qvel[k] = p.velocity0(k);
        }
      }
      data->qpos[at] = q0.w(), data->qpos[at + 1] = q0.x();
      data->qpos[at + 2] = q0.y(), data->qpos[at + 3] = q0.z();
      for (int k = 0; k < 3; ++k) {
        data->qvel[at + k] = p.omega0(k);
      }
      const Stopwatch watch;
      double t = 0;
      long steps = 0;
      for (std::size_t k = 0; k < p.times.size(); ++k) {
        model->opt.timestep = (p.times[k] - t) / c.substeps;
        for (int i = 0; i < c.substeps; ++i) {
          mj_step(model.get(), data.get());
        }
        steps += c.substeps;
        t = p.times[k];
        Sample& s = run.samples[k];
        const mjtNum* q = data->qpos + (ball ? 0 : 3);
        s.rotation = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
        s.omega = Eigen::Vector3d(data->qvel[at], data->qvel[at + 1], data->qvel[at + 2]);
        s.position =
            ball ? p.position0 : Eigen::Vector3d(data->qpos[0], data->qpos[1], data->qpos[2]);
        s.velocity =
            ball ? p.velocity0 : Eigen::Vector3d(data->qvel[0], data->qvel[1], data->qvel[2]);
      }
      record_time(run, times, watch, timing);
      run.steps = steps;
      run.rhs_evals = 4 * steps;  // RK4: four forward dynamics per step
    } while (another_rep(timing, times));
  } catch (const std::exception& e) {
    run.ok = false;
    run.error = e.what();
  }
  finish_timing(run, times);
  return run;
}

}  // namespace tumble::bench

#else

namespace tumble::bench {

bool mujoco_available() { return false; }

Run run_mujoco(const Problem& /*p*/, const MethodSetting& /*c*/, const Timing& /*timing*/) {
  Run run;
  run.ok = false;
  run.error = "MuJoCo is not installed (pip install mujoco)";
  return run;
}

}  // namespace tumble::bench

#endif
