// Tests of tumble::Chart (include/tumble/scene/chart.hpp) and of how a scene's state leaves a
// chart (recenter_charts, chart_roots, leave_charts in include/tumble/scene/charts.hpp).
//
// Expectations come from the geometry of each parameterization's singular set, independently of
// the code: Tait-Bryan angles are singular at theta2 = +-pi/2, proper Euler angles at theta2 in
// {0, pi}, the Gibbs vector at phi = pi, MRP and the rotation vector at phi = 2 pi. The chart's
// center is the point farthest from that set and the scene leaves a chart at half the center's
// distance: 45 deg from gimbal lock, phi = 90 deg (Gibbs), phi = 180 deg (rotation vector, MRP).
// Leaving a chart must not change the attitude R nor the angular velocity omega.

// Must precede every Eigen include (see integrate/alloc_counter.hpp).
#define EIGEN_RUNTIME_NO_MALLOC

#include "tumble/scene/chart.hpp"

#include <cmath>
#include <numbers>
#include <span>
#include <type_traits>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "support/catch.hpp"
#include "support/parameterizations.hpp"
#include "support/random.hpp"
#include "tumble/body/rigid_body.hpp"
#include "tumble/scene/charts.hpp"
#include "tumble/scene/observables.hpp"
#include "tumble/scene/scene.hpp"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using Eigen::VectorXd;
using tumble::Chart;
using tumble::test::AllParameterizations;

constexpr double pi = std::numbers::pi;

enum class Kind { constrained, tait_bryan, proper_euler, gibbs, mrp, rotation_vector };

template <class P> constexpr Kind kind() {
  if constexpr (std::is_same_v<P, tumble::EulerParameters>) {
    return Kind::constrained;
  } else if constexpr (requires { P::is_tait_bryan; }) {
    return P::is_tait_bryan ? Kind::tait_bryan : Kind::proper_euler;
  } else if constexpr (std::is_same_v<P, tumble::RodriguesParameters>) {
    return Kind::gibbs;
  } else if constexpr (std::is_same_v<P, tumble::ModifiedRodriguesParameters>) {
    return Kind::mrp;
  } else {
    static_assert(std::is_same_v<P, tumble::RotationVector>, "a parameterization unknown here");
    return Kind::rotation_vector;
  }
}

/// The center of the chart and its distance to the singular set, from the geometry.
template <class P> Vector3d expected_center() {
  return kind<P>() == Kind::proper_euler ? Vector3d(0, pi / 2, 0) : Vector3d::Zero();
}
template <class P> double expected_center_distance() {
  switch (kind<P>()) {
    case Kind::tait_bryan:
    case Kind::proper_euler:
      return pi / 2;  // theta2 = 0 to +-pi/2, or theta2 = pi/2 to 0 and pi
    case Kind::gibbs:
      return pi;  // phi = 0 to phi = pi
    default:
      return 2 * pi;  // phi = 0 to phi = 2 pi
  }
}

/// Coordinates inside the switch zone (closer to the singularity than half the center's
/// distance), and that distance.
template <class P> Vector3d near_singular(double& distance) {
  const Vector3d n = Vector3d(1, -2, 2).normalized();
  switch (kind<P>()) {
    case Kind::tait_bryan:
      distance = 0.3;
      return Vector3d(0.4, pi / 2 - 0.3, -0.7);
    case Kind::proper_euler:
      distance = 0.2;
      return Vector3d(0.4, pi - 0.2, -0.7);
    case Kind::gibbs:
      distance = pi - 2.5;
      return std::tan(2.5 / 2) * n;  // g = n tan(phi/2), phi = 2.5
    case Kind::mrp:
      distance = 2 * pi - 4.5;
      return std::tan(4.5 / 4) * n;  // sigma = n tan(phi/4), phi = 4.5
    default:
      distance = 2 * pi - 4.5;
      return 4.5 * n;  // phi n
  }
}

double max_abs(const Eigen::Ref<const Eigen::MatrixXd>& m) { return m.cwiseAbs().maxCoeff(); }

}  // namespace

TEMPLATE_LIST_TEST_CASE("Chart: center and switch distance from the singular set", "[scene][chart]",
                        AllParameterizations) {
  using P = TestType;
  using C = Chart<P>;
  if constexpr (kind<P>() == Kind::constrained) {
    CHECK_FALSE(C::has_singularity);
    CHECK_FALSE(C::uses_shadow_set);
    CHECK(C::switch_distance() == 0.0);
  } else {
    CHECK(C::has_singularity);
    CHECK(C::uses_shadow_set == (kind<P>() == Kind::mrp));
    const typename C::Coords c = C::center();
    CHECK(max_abs(c - expected_center<P>()) < 1e-15);
    CHECK(std::abs(P::singularity_distance(c) - expected_center_distance<P>()) < 1e-14);
    // The rule: leave at half the center's distance (45 deg from gimbal lock, phi = 90 deg for
    // Gibbs, phi = 180 deg for MRP and the rotation vector).
    CHECK(std::abs(C::switch_distance() - expected_center_distance<P>() / 2) < 1e-14);

    // No attitude is farther from the singular set than the center.
    tumble::test::Random random(11);
    double farthest = 0.0;
    for (int i = 0; i < 500; ++i) {
      const typename C::Coords th = P::from_rotation(random.rotation());
      farthest = std::max(farthest, P::singularity_distance(th));
    }
    CHECK(farthest <= P::singularity_distance(c) + 1e-12);
    CHECK(farthest > 0.5 * P::singularity_distance(c));  // the sample reaches across the chart
  }
}

TEMPLATE_LIST_TEST_CASE("leaving a chart keeps R and omega", "[scene][chart]",
                        AllParameterizations) {
  using P = TestType;
  if constexpr (Chart<P>::has_singularity) {
    using Body = tumble::RigidBody<P>;
    using C = Chart<P>;
    // [q; qdot], where a switch must also carry thetadot over (the quasi form stores omega as is).
    tumble::Scene<tumble::Bodies<Body>, tumble::Loads<>, tumble::StateForm::generalized> scene;
    const auto mp = tumble::MassProperties<double>::about_centroid(
        2.0, Eigen::Vector3d(0.5, 0.7, 0.9).asDiagonal());
    // Started far from the singular set: the chart has no base yet.
    const Matrix3d start =
        Eigen::AngleAxisd(0.2, Vector3d(0, 0, 1)).toRotationMatrix() * P::rotation(C::center());
    const auto h = scene.add(Body(mp), {.rotation = start});
    REQUIRE(scene.root_count() == 1);
    CHECK(scene.root_directions() == std::vector<int>{-1});

    // Write coordinates inside the switch zone.
    double distance = 0.0;
    const Vector3d th = near_singular<P>(distance);
    REQUIRE(std::abs(P::singularity_distance(th) - distance) < 1e-12);
    REQUIRE(distance < C::switch_distance());
    const Vector3d w(1.5, -0.8, 2.2);
    tumble::SceneState y = scene.initial_state();
    REQUIRE(y.base[0] == Matrix3d::Identity());
    y.y.segment<3>(3) = th;
    y.y.segment<3>(9) = P::thetadot(th, w);
    const std::span<Matrix3d> base(y.base);
    long switches = 0;
    const auto count = [&](int id) {
      CHECK(id == h.id);
      ++switches;
    };
    const Matrix3d r = P::rotation(th);

    // The root function is the distance minus the switch distance: negative here.
    VectorXd g(1);
    tumble::chart_roots(scene, y.y, g);
    CHECK(std::abs(g[0] - (distance - expected_center_distance<P>() / 2)) < 1e-12);

    CHECK(tumble::recenter_charts(scene, y.y, base, count) == 1);
    CHECK(switches == 1);
    CHECK(max_abs(tumble::rotation(scene, h, y) - r) < 1e-14);
    CHECK(max_abs(tumble::omega(scene, h, y) - w) < 1e-13 * w.norm());
    const Vector3d th1 = y.y.segment<3>(3);
    if constexpr (C::uses_shadow_set) {
      // The shadow set -sigma/|sigma|^2: the same attitude the other way round (phi' = 2 pi - phi).
      CHECK(max_abs(th1 + th / th.squaredNorm()) < 1e-15);
      CHECK(std::abs(P::singularity_distance(th1) - (2 * pi - distance)) < 1e-12);
    } else {
      CHECK(max_abs(th1 - expected_center<P>()) < 1e-15);  // back at the center
    }
    if constexpr (C::uses_shadow_set) {
      CHECK(y.base[0] == Matrix3d::Identity());  // the shadow set keeps the base
    } else {
      CHECK(max_abs(y.base[0] * P::rotation(th1) - r) < 1e-14);  // the base took the attitude
    }
    tumble::chart_roots(scene, y.y, g);
    CHECK(g[0] > 0.0);  // out of the switch zone
    // Nothing more to do: a second call changes nothing.
    const tumble::SceneState y1 = y;
    CHECK(tumble::recenter_charts(scene, y) == 0);
    CHECK(y.y == y1.y);
    CHECK(y.base == y1.base);
    CHECK(switches == 1);

    // At a root the integrator calls on_root(): the chart is left again (for MRP, back to the
    // first set), the attitude composed with the chart base stays the same.
    const Matrix3d r1 = tumble::rotation(scene, h, y);
    const int which[1] = {1};
    CHECK(tumble::leave_charts(scene, y.y, base, which, count) == 1);
    CHECK(switches == 2);
    CHECK(max_abs(tumble::rotation(scene, h, y) - r1) < 1e-14);
    CHECK(max_abs(tumble::omega(scene, h, y) - w) < 1e-13 * w.norm());
    const int none[1] = {0};
    const tumble::SceneState y2 = y;
    CHECK(tumble::leave_charts(scene, y.y, base, none, count) == 0);
    CHECK(y.y == y2.y);
    CHECK(y.base == y2.base);

    // Many switches in a row do not accumulate rounding in the attitude (the chart base is
    // re-orthonormalized).
    for (int i = 0; i < 200; ++i) {
      tumble::leave_charts(scene, y.y, base, which, count);
    }
    CHECK(switches == 202);
    const Matrix3d r2 = tumble::rotation(scene, h, y);
    CHECK(max_abs(r2 - r1) < 1e-13);
    CHECK(max_abs(r2.transpose() * r2 - Matrix3d::Identity()) < 1e-15);
    CHECK(max_abs(tumble::omega(scene, h, y) - w) < 1e-12 * w.norm());
  } else {
    SUCCEED("Euler parameters have no singular attitude: no chart to leave");
  }
}

// tumble::quaternion() reads the attitude from the parameters (and the chart base), not through
// R: its rotation matrix must be R, from tumble::rotation(), with w >= 0 and |q| = 1, on a chart
// without a base and after a switch that gave the chart one.
TEMPLATE_LIST_TEST_CASE("quaternion(): R's unit quaternion with w >= 0, chart base included",
                        "[scene][chart]", AllParameterizations) {
  using P = TestType;
  using Body = tumble::RigidBody<P>;
  tumble::Scene<tumble::Bodies<Body>> scene;
  const auto mp = tumble::MassProperties<double>::about_centroid(
      2.0, Eigen::Vector3d(0.5, 0.7, 0.9).asDiagonal());
  // A rotation of about 3 rad: w of its quaternion is about 0.07, and one sign is w < 0.
  const Matrix3d start = Eigen::AngleAxisd(3.0, Vector3d(2, -1, 2).normalized()).toRotationMatrix();
  const auto h = scene.add(Body(mp), {.rotation = start});
  tumble::SceneState y = scene.initial_state();
  const auto check = [&](const char* where) {
    INFO(where);
    const Eigen::Quaterniond q = tumble::quaternion(scene, h, y);
    CHECK(q.w() >= 0.0);
    CHECK(std::abs(q.norm() - 1.0) < 4e-16);
    CHECK(max_abs(q.toRotationMatrix() - tumble::rotation(scene, h, y)) < 1e-14);
  };
  check("the initial state");
  CHECK(max_abs(tumble::rotation(scene, h, y) - start) < 1e-14);
  if constexpr (Chart<P>::has_singularity) {
    double distance = 0.0;
    y.y.segment<3>(3) = near_singular<P>(distance);
    CHECK(tumble::recenter_charts(scene, y) == 1);
    if constexpr (!Chart<P>::uses_shadow_set) {
      REQUIRE(!y.base[0].isIdentity(0.0));
    }
    check("after a switch");
  } else {
    // |p| off 1 (between projections): q is p / |p|, a unit quaternion (R(p) is |p|^2 times a
    // rotation there).
    const Eigen::Vector4d p = y.y.segment<4>(3);
    y.y.segment<4>(3) *= 1.0 + 1e-9;
    const Eigen::Quaterniond q = tumble::quaternion(scene, h, y);
    CHECK(std::abs(q.norm() - 1.0) < 4e-16);
    const double sign = p(0) >= 0 ? 1.0 : -1.0;
    CHECK((Eigen::Vector4d(q.w(), q.x(), q.y(), q.z()) - sign * p).cwiseAbs().maxCoeff() < 4e-16);
  }
}

TEST_CASE("a body added near its singular set starts on a re-centered chart", "[scene][chart]") {
  // A Gibbs body at phi = 170 deg (10 deg from its singularity) and a proper Euler ZXZ body at
  // the identity (theta2 = 0: exactly singular) start at their chart centers with a base.
  using G = tumble::RigidBody<tumble::RodriguesParameters>;
  using Z = tumble::RigidBody<tumble::EulerZXZ>;
  tumble::Scene<tumble::Bodies<G, Z>> scene;
  const auto mp =
      tumble::MassProperties<double>::about_centroid(1.0, Eigen::Vector3d(1, 2, 2.5).asDiagonal());
  const Matrix3d r =
      Eigen::AngleAxisd(170.0 * pi / 180, Vector3d(1, 1, 0).normalized()).toRotationMatrix();
  const auto g = scene.add(G(mp), {.rotation = r, .omega = Vector3d(0, 0, 3)});
  const auto z = scene.add(Z(mp), {.omega = Vector3d(1, 2, 3)});
  const tumble::SceneState& st = scene.initial_state();
  const VectorXd& y = st.y;
  CHECK(y.segment<3>(scene.offset(g) + 3).norm() == 0.0);
  CHECK(max_abs(y.segment<3>(scene.offset(z) + 3) - Vector3d(0, pi / 2, 0)) < 1e-15);
  CHECK(max_abs(tumble::rotation(scene, g, st) - r) < 1e-14);
  CHECK(max_abs(tumble::rotation(scene, z, st) - Matrix3d::Identity()) < 1e-15);
  CHECK(max_abs(tumble::omega(scene, g, st) - Vector3d(0, 0, 3)) < 1e-14);
  CHECK(max_abs(tumble::omega(scene, z, st) - Vector3d(1, 2, 3)) < 1e-14);
  CHECK(y.allFinite());
  // The attitude lives in the chart bases: the Gibbs body's is R itself (theta = 0), the ZXZ
  // body's R R(theta_c)^T.
  CHECK(max_abs(st.base[g.id] - r) < 1e-14);
  CHECK(max_abs(st.base[z.id] * tumble::EulerZXZ::rotation(Vector3d(0, pi / 2, 0)) -
                Matrix3d::Identity()) < 1e-15);
}
