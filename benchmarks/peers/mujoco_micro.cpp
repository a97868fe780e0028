// tumble_micro's MuJoCo peer (built when CMake finds libmujoco; TUMBLE_BENCH_MUJOCO).
//
// The same body as tumble's benchmarks (micro/common.hpp) as an MJCF model: one body with a free
// joint at the reference point c and an <inertial> element with the body's mass, the centroid at
// r_g (zero for ReferencePoint::centroid) and its full inertia about the centroid; no geoms (so
// no collision work), zero gravity, and the applied wrench as qfrc_applied = [F; M_c] (F world,
// M_c body, the duals of the free joint's velocities), the same wrench qddot/<P>/<ref> is given:
//   mujoco_forward/<ref>   mj_forward (the full forward dynamics: kinematics, inertia, mass
//                          matrix factorization, bias forces, qacc)
// The accelerations are checked against tumble's before the benchmarks run.

#include <array>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <mujoco/mujoco.h>

#include "micro/common.hpp"
#include "peers/mujoco_handles.hpp"

namespace tumble::bench {
namespace {

using Vector6 = Eigen::Matrix<double, 6, 1>;

template <ReferencePoint Ref> std::string mjcf() {
  const Vector3<double> c =
      Ref == ReferencePoint::centroid ? Vector3<double>::Zero() : body_centroid_offset();
  const Matrix3<double> i = body_inertia();
  std::ostringstream os;
  os.precision(17);
  os << "<mujoco><option gravity=\"0 0 0\"/><worldbody><body name=\"b\"><freejoint/>"
     << "<inertial pos=\"" << c(0) << " " << c(1) << " " << c(2) << "\" mass=\"" << body_mass()
     << "\" fullinertia=\"" << i(0, 0) << " " << i(1, 1) << " " << i(2, 2) << " " << i(0, 1) << " "
     << i(0, 2) << " " << i(1, 2) << "\"/></body></worldbody></mujoco>";
  return os.str();
}

template <ReferencePoint Ref> struct MujocoCase {
  std::unique_ptr<mjModel, ModelDeleter> model;
  std::vector<std::array<double, 7>> qpos;
  std::vector<std::array<double, 6>> qvel, qfrc;

  MujocoCase() {
    std::array<char, 1000> error{};
    std::unique_ptr<mjSpec, SpecDeleter> spec(
        mj_parseXMLString(mjcf<Ref>().c_str(), nullptr, error.data(), int(error.size())));
    if (spec) {
      model.reset(mj_compile(spec.get(), nullptr));
    }
    if (!model) {
      std::fprintf(stderr, "tumble_micro: MuJoCo could not load the model: %s\n", error.data());
      std::exit(2);
    }
    for (const auto& s : raw_states()) {
      qpos.push_back({s.position(0), s.position(1), s.position(2), s.attitude.w(), s.attitude.x(),
                      s.attitude.y(), s.attitude.z()});
      qvel.push_back(
          {s.velocity(0), s.velocity(1), s.velocity(2), s.omega(0), s.omega(1), s.omega(2)});
      qfrc.push_back({s.wrench.force(0), s.wrench.force(1), s.wrench.force(2), s.wrench.moment(0),
                      s.wrench.moment(1), s.wrench.moment(2)});
    }
  }

  void set_state(mjData* d, std::size_t i) const {
    for (int k = 0; k < 7; ++k) d->qpos[k] = qpos[i][std::size_t(k)];
    for (int k = 0; k < 6; ++k) d->qvel[k] = qvel[i][std::size_t(k)];
    for (int k = 0; k < 6; ++k) d->qfrc_applied[k] = qfrc[i][std::size_t(k)];
  }

  /// mj_forward's qacc = [rddot (world); alpha (body)] against tumble's (alpha = 2 L(p) pddot).
  void check() const {
    using Body = RigidBody<EulerParameters, Ref, double>;
    const States<Body> s;
    const Body body(mass_properties<Ref>());
    std::unique_ptr<mjData, DataDeleter> data(mj_makeData(model.get()));
    for (std::size_t i = 0; i < kStates; ++i) {
      set_state(data.get(), i);
      mj_forward(model.get(), data.get());
      const Vector6 a = Eigen::Map<const Vector6>(data->qacc);
      const auto qdd = body.accelerations(s.q[i], s.qdot[i], s.wrench[i]);
      const Vector4<double> p = s.q[i].template tail<4>();
      const Vector3<double> alpha = EulerParameters::G(p) * qdd.template tail<4>();
      const double err =
          (alpha - a.tail<3>()).norm() + (qdd.template head<3>() - a.head<3>()).norm();
      if (!(err <= 1e-8 * (1.0 + qdd.norm()))) {
        std::fprintf(stderr, "tumble_micro: MuJoCo and tumble disagree (%s, state %zu, %g)\n",
                     ref_name(Ref), i, err);
        std::exit(2);
      }
    }
  }
};

template <ReferencePoint Ref> void register_ref() {
  MujocoCase<Ref>().check();
  add(std::string("mujoco_forward/") + ref_name(Ref), [](benchmark::State& st) {
    static const MujocoCase<Ref> c;
    std::unique_ptr<mjData, DataDeleter> data(mj_makeData(c.model.get()));
    run_cycling(st, [&](std::size_t i) {
      c.set_state(data.get(), i);
      mj_forward(c.model.get(), data.get());
      return Vector6(Eigen::Map<const Vector6>(data->qacc));
    });
  });
}

}  // namespace

void register_mujoco() {
  register_ref<ReferencePoint::centroid>();
  register_ref<ReferencePoint::offset>();
}

}  // namespace tumble::bench
