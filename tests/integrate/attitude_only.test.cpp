// The attitude-only form (scene/attitude_only.hpp) against the full scene it came from: a body
// under gravity, a body-fixed moment and a constant force at a point, free (13 states) and held
// at its centroid (7), through the front door; their attitudes agree to the integrators'
// tolerance, which is what Eq. (1.33) says (at the centroid the rotation does not feel the
// translation). A body already held at a point keeps its point.

#include "tumble/scene/attitude_only.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Geometry>

#include "support/catch.hpp"
#include "support/random.hpp"
#include "tumble/integrate.hpp"

TEST_CASE("attitude_only: the same attitude from 7 states as from 13", "[integrate][attitude]") {
  using namespace tumble;
  using Free = RigidBody<EulerParameters>;
  using Held = RigidBody<RotationVector, ReferencePoint::fixed_point>;
  using SceneT = Scene<Bodies<Free, Held>, Loads<UniformGravity, BodyMoment, PointForce>>;
  SceneT scene;
  const auto a = scene.add(
      Free(MassProperties<>::about_centroid(2.0, Eigen::Vector3d(0.3, 0.5, 0.7).asDiagonal())),
      {.position = {1, 2, 3},
       .rotation = Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 2).normalized()).toRotationMatrix(),
       .velocity = {0.5, -1, 2},
       .omega = {1.0, -0.4, 2.5}});
  const auto top = scene.add(
      Held(MassProperties<>::about_centroid(1.0, Eigen::Vector3d(0.02, 0.02, 0.01).asDiagonal(),
                                            Eigen::Vector3d(0, 0, 0.1)),
           Eigen::Vector3d(0, 0, 1)),
      {.rotation = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()).toRotationMatrix(),
       .omega = {0, 0, 40}});
  scene.add_load(a, UniformGravity({0, 0, -9.81}));
  scene.add_load(a, BodyMoment({0.01, 0.02, -0.01}));
  scene.add_load(a, PointForce({0.1, 0, 0}, {0, 0.3, 0}));
  scene.add_load(top, UniformGravity({0, 0, -9.81}));

  const auto att = attitude_only(scene);
  CHECK(scene.size() == 13 + 6);  // [r; p; v; omega] and the held top's [theta; omega]
  CHECK(att.size() == 7 + 6);
  const auto a2 = attitude_id(a);
  const auto top2 = attitude_id(top);
  CHECK(position(att, a2, att.initial_state()) == position(scene, a, scene.initial_state()));
  CHECK(position(att, top2, att.initial_state()) == Eigen::Vector3d(0, 0, 1));

  std::vector<double> times;
  for (int k = 0; k <= 40; ++k) {
    times.push_back(0.5 * k);
  }
  std::vector<Eigen::Matrix3d> ra, rt;
  const AutoOptions opt{.rtol = 1e-11, .atol = 1e-11};
  const AutoStatistics full = integrate(
      scene, 0.0, times,
      [&](double, const SceneState& s) {
        ra.push_back(rotation(scene, a, s));
        rt.push_back(rotation(scene, top, s));
      },
      opt);
  double worst = 0.0;
  std::size_t k = 0;
  const AutoStatistics reduced = integrate(
      att, 0.0, times,
      [&](double, const SceneState& s) {
        worst = std::max({worst, tumble::test::rotation_angle_between(rotation(att, a2, s), ra[k]),
                          tumble::test::rotation_angle_between(rotation(att, top2, s), rt[k])});
        ++k;
      },
      opt);
  INFO("largest attitude difference over 20 s: " << worst << " rad; steps " << full.steps
                                                 << " (13 + 6 states) and " << reduced.steps
                                                 << " (7 + 6)");
  CHECK(k == times.size());
  CHECK(worst <= 1e-8);
}
