// Ensembles of mechanisms work as ensembles of free bodies do: pendulums released from 41 angles
// between 0.5 and 2.5 rad, on 2 threads, each against its closed form (Jacobi's sn), and the
// results the same bits as the serial integrate() of each run.

#include "tumble/ensemble/ensemble.hpp"

#include <cmath>
#include <cstddef>
#include <vector>

#include <Eigen/Geometry>

#include "support/catch.hpp"
#include "support/torque_free.hpp"
#include "tumble/integrate.hpp"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using namespace tumble;

using Rod = RigidBody<EulerParameters>;
using SceneT = Mechanism<Bodies<Rod>, Joints<Revolute>, Loads<UniformGravity>>;
constexpr double kLength = 1.2, kMass = 2.0, kG = 9.81;

/// The pendulum of pendulum.test.cpp (a rod hinged at its top end about y) released from theta0.
SceneT pendulum(double theta0) {
  SceneT scene;
  const Vector3d top(0, 0, 0.5 * kLength);
  const Matrix3d r0 = Eigen::AngleAxisd(theta0, Vector3d::UnitY()).toRotationMatrix();
  const double s = 0.05, l = kLength, m = kMass;
  const auto id =
      scene.add(Rod(MassProperties<>::about_centroid(
                    m, Vector3d(m * (l * l + s * s) / 12, m * (l * l + s * s) / 12, m * s * s / 6)
                           .asDiagonal())),
                {.position = -r0 * top, .rotation = r0});
  scene.add_load(id, UniformGravity(Vector3d(0, 0, -kG)));
  scene.add_joint(id, ground,
                  Revolute(top, Vector3d::UnitY(), Vector3d::Zero(), Vector3d::UnitY()));
  return scene;
}

double theta0_of(std::size_t i) { return 0.5 + 0.05 * static_cast<double>(i); }

}  // namespace

TEST_CASE("ensemble of mechanisms: pendulums on 2 threads, each on its closed form and on its "
          "serial run",
          "[joint][ensemble]") {
  const SceneT scene = pendulum(1.0);
  const double s = 0.05, l = kLength;
  const double io = kMass * (l * l + s * s) / 12 + kMass * 0.25 * l * l;
  const double w0 = std::sqrt(kMass * kG * 0.5 * l / io);
  OdeintOptions opt;
  opt.rtol = 1e-12;
  opt.atol = 1e-12;
  const auto make = [&](const SceneT& sc, double t0, const SceneState& y0) {
    return OdeintIntegrator<SceneT>(sc, t0, y0, opt);
  };
  const auto initial = [](std::size_t i) { return pendulum(theta0_of(i)).initial_state(); };
  const std::vector<double> times{1.0, 5.0};
  const auto angle = [&](const SceneState& x) {
    const Matrix3d r = rotation(scene, BodyId<Rod>{0, 0}, x);
    return std::atan2(r(0, 2), r(0, 0));
  };
  const Ensemble ensemble(scene, make, {.threads = 2});
  const auto runs = ensemble.integrate<std::vector<double>>(
      41, initial, 0.0, times,
      [&](std::vector<double>& out, std::size_t, double, const SceneState& x, const SceneT&) {
        out.push_back(angle(x));
      });
  REQUIRE(failures(runs).empty());
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const std::vector<double>& got = runs[i].value();
    REQUIRE(got.size() == times.size());
    const double k = std::sin(0.5 * theta0_of(i)), kk = std::comp_ellint_1(k);
    std::vector<double> serial;
    auto integrator = make(scene, 0.0, initial(i));
    integrator.integrate(times, [&](double, const SceneState& x) { serial.push_back(angle(x)); });
    for (std::size_t j = 0; j < times.size(); ++j) {
      const double exact =
          2.0 * std::asin(k * tumble::test::jacobi_sn_cn_dn(kk - w0 * times[j], k * k).sn);
      INFO("run " << i << " (theta0 = " << theta0_of(i) << ") at t = " << times[j]);
      CHECK(std::abs(got[j] - exact) <= 5e-9);
      CHECK(got[j] == serial[j]);  // the same bits as the serial run
    }
  }
}
