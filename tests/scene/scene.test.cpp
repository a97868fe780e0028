// Tests of tumble::Scene (include/tumble/scene/scene.hpp): the state layout of mixed body types,
// the initial state, the rejection of bad input, the right-hand side against each body's own
// accelerations (tumble::accelerations of force/loads.hpp with the same loads, the two-body load
// replaced by the equal and opposite point forces the test computes itself), the Baumgarte
// constraint acceleration of Euler parameters against its formula, the physical quantities
// (energy, momenta, centroid) against the test's own sums, the projection onto the quaternion
// constraint, and the absence of heap allocations in the right-hand side.
//
// Reference: the reference chapter (Chapter 1, "Rigid body"), Eqs. 1.1, 1.4, 1.6.

// Must precede every Eigen include (see integrate/alloc_counter.hpp).
#define EIGEN_RUNTIME_NO_MALLOC

#include "tumble/scene/scene.hpp"

#include <cmath>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "integrate/alloc_counter.hpp"
#include "support/catch.hpp"
#include "support/parameterizations.hpp"
#include "support/random.hpp"
#include "tumble/body/rigid_body.hpp"
#include "tumble/force/coupling.hpp"
#include "tumble/force/gravity.hpp"
#include "tumble/force/loads.hpp"
#include "tumble/force/point_force.hpp"
#include "tumble/force/spring_damper.hpp"
#include "tumble/force/user_force.hpp"
#include "tumble/scene/charts.hpp"
#include "tumble/scene/observables.hpp"
#include "tumble/scene/projection.hpp"
#include "tumble/scene/rhs.hpp"
#include "tumble/scene/workspace.hpp"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using Eigen::Vector4d;
using Eigen::VectorXd;
using tumble::Bodies;
using tumble::BodyId;
using tumble::EulerParameters;
using tumble::EulerZYX;
using tumble::InitialState;
using tumble::Loads;
using tumble::MassProperties;
using tumble::ReferencePoint;
using tumble::RigidBody;
using tumble::RotationVector;
// This file tests the chapter's form, [q; qdot] per body (StateForm::generalized); the default,
// quasi-velocities, has its own tests (quasi_velocities.test.cpp).
template <class B, class L = tumble::Loads<>>
using Scene = tumble::Scene<B, L, tumble::StateForm::generalized>;
using tumble::SceneState;
using tumble::SceneWorkspace;

using EP = RigidBody<EulerParameters>;
using EPOff = RigidBody<EulerParameters, ReferencePoint::offset>;
using ZYXOff = RigidBody<EulerZYX, ReferencePoint::offset>;
using RV = RigidBody<RotationVector>;

Matrix3d rot(double angle, const Vector3d& axis) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

/// A full (non-diagonal) inertia: principal moments `m` about axes turned by R.
Matrix3d inertia(const Vector3d& m, const Matrix3d& r) {
  return r * m.asDiagonal() * r.transpose();
}

EP ep_body() {
  return EP(MassProperties<double>::about_centroid(
      2.0, inertia(Vector3d(0.3, 0.5, 0.7), rot(0.4, Vector3d(1, 2, 3)))));
}
const Vector3d kCentroid(0.2, -0.1, 0.3);
ZYXOff zyx_body() {
  return ZYXOff(MassProperties<double>::about_centroid(
      1.5, inertia(Vector3d(0.2, 0.25, 0.3), rot(-0.7, Vector3d(0, 1, 1))), kCentroid));
}
EPOff ep_off_body() {
  return EPOff(MassProperties<double>::about_centroid(
      1.5, inertia(Vector3d(0.2, 0.25, 0.3), rot(-0.7, Vector3d(0, 1, 1))), kCentroid));
}
RV rv_body() {
  return RV(MassProperties<double>::about_centroid(0.8, Vector3d(0.1, 0.1, 0.15).asDiagonal()));
}

/// A user load reading only velocities: F = -c v + (sin t, 0, 0), M = -c_m omega.
struct Drag {
  double c = 0.3;
  double cm = 0.05;
  template <class S, ReferencePoint Ref>
  tumble::Wrench<S> operator()(const S& t, const tumble::BodyKinematics<S, Ref>& k) const {
    using std::sin;
    tumble::Wrench<S> w;
    w.force = -S(c) * k.velocity + tumble::Vector3<S>(sin(t), S(0), S(0));
    w.moment = -S(cm) * k.omega;
    return w;
  }
};
using DragForce = tumble::UserForce<Drag, false>;

/// Writes the physical state (reference point r, velocity v, attitude R, omega) of body h into y
/// in the body's own coordinates, for a body whose chart has no base.
template <class SceneT, class Body>
void put(const SceneT& scene, BodyId<Body> h, VectorXd& y, const Vector3d& r, const Matrix3d& rr,
         const Vector3d& v, const Vector3d& w) {
  using P = typename Body::Param;
  const int o = scene.offset(h);
  const typename P::template Coords<double> th = P::from_rotation(rr);
  y.template segment<3>(o) = r;
  y.template segment<Body::n_theta>(o + 3) = th;
  y.template segment<3>(o + Body::nq) = v;
  y.template segment<Body::n_theta>(o + Body::nq + 3) = P::thetadot(th, w);
}

template <class Body> typename Body::Coords q_of(const VectorXd& y, int offset) {
  return y.segment<Body::nq>(offset);
}
template <class Body> typename Body::Coords qdot_of(const VectorXd& y, int offset) {
  return y.segment<Body::nq>(offset + Body::nq);
}

double max_abs(const Eigen::Ref<const Eigen::MatrixXd>& m) { return m.cwiseAbs().maxCoeff(); }

}  // namespace

// ---- layout and initial state ----------------------------------------------------------------

TEST_CASE("state layout: [q; qdot] of each body in the order of addition", "[scene][scene]") {
  Scene<Bodies<EP, ZYXOff, RV>> scene;
  const auto a = scene.add(ep_body());
  const auto b = scene.add(zyx_body());
  const auto c = scene.add(rv_body());
  const auto d = scene.add(ep_body());

  // nq = 3 + 4 (Euler parameters) or 3 + 3; each body holds [q; qdot], 2 nq entries.
  CHECK(scene.body_count() == 4);
  CHECK(scene.size() == 14 + 12 + 12 + 14);
  CHECK(scene.initial_state().y.size() == 52);
  CHECK(scene.initial_state().base.size() == 4);  // one chart base per body
  CHECK(scene.offset(a) == 0);
  CHECK(scene.offset(b) == 14);
  CHECK(scene.offset(c) == 26);
  CHECK(scene.offset(d) == 38);
  // Handles: global index in the order of addition, local index among the bodies of one type.
  CHECK((a.id == 0 && a.local == 0));
  CHECK((b.id == 1 && b.local == 0));
  CHECK((c.id == 2 && c.local == 0));
  CHECK((d.id == 3 && d.local == 1));

  // One root function per body with a singular chart (Euler angles, rotation vector); all watch
  // a decreasing distance.
  CHECK(scene.root_count() == 2);
  CHECK(scene.chart_bodies() == std::vector<int>{1, 2});
  CHECK(scene.root_directions() == std::vector<int>{-1, -1});
  CHECK(Scene<Bodies<EP, ZYXOff, RV>>::has_constraints);
  CHECK_FALSE(Scene<Bodies<ZYXOff, RV>>::has_constraints);
}

TEST_CASE("the initial state gives back what was added", "[scene][scene]") {
  Scene<Bodies<EP, ZYXOff, RV>> scene;
  tumble::test::Random random(7);
  const InitialState sa{Vector3d(1, -2, 3), random.rotation(), Vector3d(0.1, 0.2, -0.3),
                        Vector3d(0.5, -1.5, 2.5)};
  // ZYX angles (0.4, 1.4, -0.3): 0.17 rad from gimbal lock, inside the switch distance of 45 deg,
  // so the scene starts this body on a re-centered chart (theta = 0 and a chart base).
  const Matrix3d near_lock =
      rot(0.4, Vector3d::UnitZ()) * rot(1.4, Vector3d::UnitY()) * rot(-0.3, Vector3d::UnitX());
  const InitialState sb{Vector3d(-1, 0.5, 0), near_lock, Vector3d(0, 0, 4), Vector3d(3, 0, -1)};
  const InitialState sc{Vector3d(0, 0, 0), rot(2.5, Vector3d(1, 1, 0)), Vector3d(-1, -1, -1),
                        Vector3d(0, 7, 0)};
  const auto a = scene.add(ep_body(), sa);
  const auto b = scene.add(zyx_body(), sb);
  const auto c = scene.add(rv_body(), sc);
  const SceneState& st = scene.initial_state();
  const VectorXd& y = st.y;

  auto check_round_trip = [&](auto h, const InitialState& s) {
    CHECK(tumble::position(scene, h, st) == s.position);
    CHECK(tumble::velocity(scene, h, st) == s.velocity);
    CHECK(max_abs(tumble::rotation(scene, h, st) - s.rotation) < 1e-14);
    CHECK(max_abs(tumble::omega(scene, h, st) - s.omega) < 1e-14 * s.omega.norm());
  };
  check_round_trip(a, sa);
  check_round_trip(b, sb);
  check_round_trip(c, sc);

  // The raw layout: r_oc at the offset, rdot_oc at offset + nq.
  CHECK(y.segment<3>(scene.offset(a)) == sa.position);
  CHECK(y.segment<3>(scene.offset(a) + 7) == sa.velocity);
  CHECK(y.segment<3>(scene.offset(b) + 6) == sb.velocity);
  // Euler parameters start on their constraint manifold: |p| = 1 and p.pdot = 0.
  const Vector4d p = y.segment<4>(scene.offset(a) + 3);
  const Vector4d pd = y.segment<4>(scene.offset(a) + 10);
  CHECK(std::abs(p.norm() - 1.0) < 1e-15);
  CHECK(std::abs(p.dot(pd)) < 1e-15);
  CHECK(max_abs(EulerParameters::rotation(p) - sa.rotation) < 1e-14);
  // The rotation vector of a 2.5 rad rotation is far from its singularity: no chart base.
  const Vector3d v = y.segment<3>(scene.offset(c) + 3);
  CHECK(std::abs(v.norm() - 2.5) < 1e-14);
  // The body near gimbal lock starts at the chart's center theta = 0.
  CHECK(y.segment<3>(scene.offset(b) + 3).norm() == 0.0);
  // Its chart base is part of the state: R = R0 R(0) = R0. The others have none.
  CHECK(max_abs(st.base[b.id] - near_lock) < 1e-14);
  CHECK(st.base[a.id] == Matrix3d::Identity());
  CHECK(st.base[c.id] == Matrix3d::Identity());

  // Centroid of the body framed off its centroid: r_oc + R r_g (Eq. 1.1).
  CHECK(max_abs(tumble::centroid_position(scene, b, st) - (sb.position + near_lock * kCentroid)) <
        1e-14);
  CHECK(max_abs(tumble::centroid_position(scene, a, st) - sa.position) == 0.0);
}

TEST_CASE("set_velocity writes v and omega in the body's coordinates", "[scene][scene]") {
  Scene<Bodies<EP, ZYXOff>> scene;
  const auto a = scene.add(ep_body(), {.rotation = rot(0.3, Vector3d(1, 0, 1))});
  const auto b = scene.add(zyx_body(), {.rotation = rot(1.3, Vector3d(0, 1, 0))});
  SceneState y = scene.initial_state();
  const Matrix3d ra = tumble::rotation(scene, a, y), rb = tumble::rotation(scene, b, y);
  tumble::set_velocity(scene, a, y, Vector3d(1, 2, 3), Vector3d(-4, 5, 6));
  tumble::set_velocity(scene, b, y, Vector3d(0, 0, -1), Vector3d(0.5, 0, 0));
  CHECK(tumble::velocity(scene, a, y) == Vector3d(1, 2, 3));
  CHECK(max_abs(tumble::omega(scene, a, y) - Vector3d(-4, 5, 6)) < 1e-14);
  CHECK(tumble::velocity(scene, b, y) == Vector3d(0, 0, -1));
  CHECK(max_abs(tumble::omega(scene, b, y) - Vector3d(0.5, 0, 0)) < 1e-15);
  // The attitude and the position are untouched.
  CHECK(tumble::rotation(scene, a, y) == ra);
  CHECK(tumble::rotation(scene, b, y) == rb);
  CHECK(tumble::position(scene, a, y) == Vector3d::Zero());
}

// ---- bad input -------------------------------------------------------------------------------

TEST_CASE("bad input is rejected with std::invalid_argument", "[scene][scene]") {
  using SceneT = Scene<Bodies<EP, RV>, Loads<tumble::SpringDamperBetween, tumble::UniformGravity>>;
  SceneT scene;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();

  SECTION("a non-finite initial state") {
    InitialState s;
    s.position.x() = nan;
    REQUIRE_THROWS_AS(scene.add(ep_body(), s), std::invalid_argument);
    REQUIRE_THROWS_WITH(scene.add(ep_body(), s),
                        TUMBLE_CONTAINS("body 0: the initial position is not finite: (nan, 0, 0)"));
    s = {};
    s.velocity.z() = inf;
    REQUIRE_THROWS_WITH(scene.add(rv_body(), s),
                        TUMBLE_CONTAINS("the initial velocity is not finite: (0, 0, inf)"));
    s = {};
    s.omega.y() = -inf;
    REQUIRE_THROWS_WITH(scene.add(rv_body(), s),
                        TUMBLE_CONTAINS("the initial omega is not finite: (0, -inf, 0)"));
    s = {};
    s.rotation(1, 2) = nan;
    REQUIRE_THROWS_WITH(scene.add(ep_body(), s),
                        TUMBLE_CONTAINS("the initial rotation (row by row) is not finite: "
                                        "(1, 0, 0, 0, 1, nan, 0, 0, 1)"));
    CHECK(scene.body_count() == 0);  // nothing was added
    CHECK(scene.size() == 0);
  }
  SECTION("an initial rotation that is not a proper rotation matrix") {
    const char* what = "the initial rotation is not a proper rotation matrix";
    InitialState s;
    s.rotation = 1.01 * rot(0.3, Vector3d(1, 2, 3));  // scaled
    REQUIRE_THROWS_AS(scene.add(ep_body(), s), std::invalid_argument);
    REQUIRE_THROWS_WITH(scene.add(ep_body(), s), TUMBLE_CONTAINS(what));
    s.rotation = Matrix3d::Identity();
    s.rotation(0, 1) = 1e-6;  // sheared
    REQUIRE_THROWS_WITH(scene.add(rv_body(), s), TUMBLE_CONTAINS(what));
    s.rotation = Vector3d(1, 1, -1).asDiagonal();  // a reflection: orthogonal, det = -1
    REQUIRE_THROWS_WITH(scene.add(rv_body(), s), TUMBLE_CONTAINS(what));
    s.rotation = -Matrix3d::Identity();  // the point reflection
    REQUIRE_THROWS_WITH(scene.add(ep_body(), s), TUMBLE_CONTAINS(what));
    CHECK(scene.body_count() == 0);
    // A rotation accurate to rounding is accepted.
    s.rotation = rot(0.3, Vector3d(1, 2, 3));
    s.rotation(2, 2) += 1e-15;
    CHECK_NOTHROW(scene.add(ep_body(), s));
  }
  SECTION("a handle that does not refer to a body of this scene") {
    const auto mine = scene.add(ep_body());
    scene.add(rv_body());
    const SceneState y = scene.initial_state();
    const char* what = "does not refer to a body of this scene";
    // The default handle, and one out of range.
    REQUIRE_THROWS_AS(scene.offset(BodyId<EP>{}), std::invalid_argument);
    REQUIRE_THROWS_WITH(scene.offset(BodyId<EP>{}), TUMBLE_CONTAINS(what));
    REQUIRE_THROWS_WITH(tumble::rotation(scene, BodyId<RV>{5, 5}, y), TUMBLE_CONTAINS(what));
    REQUIRE_THROWS_WITH(tumble::omega(scene, BodyId<EP>{0, 1}, y), TUMBLE_CONTAINS(what));
    // A handle of another scene whose global index differs from this scene's body.
    SceneT other;
    other.add(rv_body());
    const auto foreign = other.add(ep_body());  // id 1, local 0
    REQUIRE_THROWS_WITH(scene.offset(foreign), TUMBLE_CONTAINS(what));
    REQUIRE_THROWS_WITH(scene.add_load(foreign, tumble::UniformGravity(Vector3d(0, 0, -9.81))),
                        TUMBLE_CONTAINS(what));
    REQUIRE_THROWS_WITH(scene.add_load(mine, foreign,
                                       tumble::SpringDamperBetween(Vector3d::Zero(),
                                                                   Vector3d::Zero(), {1.0, 0, 0})),
                        TUMBLE_CONTAINS(what));
    CHECK(scene.offset(mine) == 0);
  }
  SECTION("a coupling of a body with itself") {
    const auto a = scene.add(ep_body());
    REQUIRE_THROWS_AS(
        scene.add_load(a, a, tumble::SpringDamperBetween(Vector3d::Zero(), Vector3d(1, 0, 0), {})),
        std::invalid_argument);
    REQUIRE_THROWS_WITH(
        scene.add_load(a, a, tumble::SpringDamperBetween(Vector3d::Zero(), Vector3d(1, 0, 0), {})),
        TUMBLE_CONTAINS("a coupling needs two different bodies"));
  }
  SECTION("an empty scene") {
    REQUIRE_THROWS_AS(SceneWorkspace<SceneT>(scene), std::invalid_argument);
    REQUIRE_THROWS_WITH(SceneWorkspace<SceneT>(scene), TUMBLE_CONTAINS("the scene has no bodies"));
  }
  SECTION("an event without a root function") {
    REQUIRE_THROWS_AS(scene.add_event(tumble::Event{}), std::invalid_argument);
    REQUIRE_THROWS_WITH(scene.add_event(tumble::Event{}),
                        TUMBLE_CONTAINS("the event has no root function"));
  }
}

// ---- the right-hand side -----------------------------------------------------------------------

namespace {

using FullScene = Scene<Bodies<EP, ZYXOff, RV>, Loads<tumble::UniformGravity, tumble::SpringDamper,
                                                      DragForce, tumble::SpringDamperBetween>>;

struct FullSetup {
  FullScene scene;
  BodyId<EP> a;
  BodyId<ZYXOff> b;
  BodyId<RV> c;
  tumble::UniformGravity gravity{Vector3d(0.3, -0.2, -9.81)};
  tumble::SpringDamper spring{Vector3d(0.1, 0.2, -0.3),
                              Vector3d(1, 1, 2),
                              {.stiffness = 40.0, .damping = 1.5, .rest_length = 0.4}};
  DragForce drag{Drag{}};
  Vector3d point_a{0.3, 0.0, 0.1};
  Vector3d point_b{-0.2, 0.1, 0.0};
  tumble::SpringDamperParameters coupling{.stiffness = 25.0, .damping = 0.7, .rest_length = 0.3};

  FullSetup() {
    a = scene.add(ep_body());
    b = scene.add(zyx_body());
    c = scene.add(rv_body());
    scene.add_load(a, gravity);
    scene.add_load(b, gravity);
    scene.add_load(c, gravity);
    scene.add_load(b, spring);
    scene.add_load(a, drag);
    scene.add_load(c, drag);
    scene.add_load(a, b, tumble::SpringDamperBetween(point_a, point_b, coupling));
  }

  /// A state with every body moving and turning, no chart near its singularity (and so no chart
  /// base: the bases are the identity).
  [[nodiscard]] SceneState state() const {
    SceneState st{VectorXd(scene.size()), tumble::ChartBases(3, Matrix3d::Identity())};
    VectorXd& y = st.y;
    put(scene, a, y, Vector3d(0.1, 0.2, 0.3), rot(0.8, Vector3d(1, -2, 0.5)), Vector3d(1, 0, -1),
        Vector3d(0.7, -1.1, 2.0));
    put(scene, b, y, Vector3d(0.9, -0.4, 0.5), rot(0.6, Vector3d(0.3, 1, -1)),
        Vector3d(-0.5, 0.4, 0.2), Vector3d(-2.0, 0.5, 1.2));
    put(scene, c, y, Vector3d(-1, 0, 2), rot(2.0, Vector3d(2, 1, 1)), Vector3d(0, 0.3, 0),
        Vector3d(0.2, 3.0, -0.4));
    return st;
  }
};

/// The force on body a of a spring-damper between the body points pa (velocity va) and pb (vb):
/// T u with u = (pb - pa)/L, T = k (L - L0) + c u.(vb - va); body b gets the opposite force.
Vector3d coupling_force(const tumble::SpringDamperParameters& sd, const Vector3d& pa,
                        const Vector3d& va, const Vector3d& pb, const Vector3d& vb) {
  const Vector3d d = pb - pa;
  const double len = d.norm();
  const Vector3d u = d / len;
  return (sd.stiffness * (len - sd.rest_length) + sd.damping * u.dot(vb - va)) * u;
}

}  // namespace

TEST_CASE("the right-hand side is each body's accelerations under its loads", "[scene][scene]") {
  FullSetup s;
  const SceneState st = s.state();
  const VectorXd& y = st.y;
  const double t = 0.7;
  VectorXd ydot(s.scene.size());
  SceneWorkspace ws(s.scene);
  tumble::rhs(s.scene, ws, t, st, ydot);

  const int oa = s.scene.offset(s.a), ob = s.scene.offset(s.b), oc = s.scene.offset(s.c);
  const auto qa = q_of<EP>(y, oa);
  const auto qda = qdot_of<EP>(y, oa);
  const auto qb = q_of<ZYXOff>(y, ob);
  const auto qdb = qdot_of<ZYXOff>(y, ob);
  const auto qc = q_of<RV>(y, oc);
  const auto qdc = qdot_of<RV>(y, oc);

  // The coupling, computed here from the attachment points' positions and velocities (Eqs. 1.1,
  // 1.4) and applied to each body as a point force.
  const Matrix3d ra = EulerParameters::rotation(Vector4d(qa.tail<4>()));
  const Matrix3d rb = EulerZYX::rotation(Vector3d(qb.tail<3>()));
  const Vector3d wa = EulerParameters::G(Vector4d(qa.tail<4>())) * qda.tail<4>();
  const Vector3d wb = EulerZYX::G(Vector3d(qb.tail<3>())) * qdb.tail<3>();
  const Vector3d pa = qa.head<3>() + ra * s.point_a, pb = qb.head<3>() + rb * s.point_b;
  const Vector3d va = qda.head<3>() + ra * wa.cross(s.point_a);
  const Vector3d vb = qdb.head<3>() + rb * wb.cross(s.point_b);
  const Vector3d fa = coupling_force(s.coupling, pa, va, pb, vb);
  const tumble::PointForce on_a(s.point_a, fa), on_b(s.point_b, -fa);

  const EP& body_a = s.scene.body(s.a);
  const ZYXOff& body_b = s.scene.body(s.b);
  const RV& body_c = s.scene.body(s.c);
  const EP::Coords expected_a = tumble::accelerations(body_a, t, qa, qda, s.gravity, s.drag, on_a);
  const ZYXOff::Coords expected_b =
      tumble::accelerations(body_b, t, qb, qdb, s.gravity, s.spring, on_b);
  const RV::Coords expected_c = tumble::accelerations(body_c, t, qc, qdc, s.gravity, s.drag);

  // q' = qdot exactly; qdot' = qddot (on the quaternion constraint, where the Baumgarte terms
  // vanish).
  CHECK(ydot.segment<7>(oa) == qda);
  CHECK(ydot.segment<6>(ob) == qdb);
  CHECK(ydot.segment<6>(oc) == qdc);
  CHECK(max_abs(ydot.segment<7>(oa + 7) - expected_a) < 1e-13 * max_abs(expected_a));
  CHECK(max_abs(ydot.segment<6>(ob + 6) - expected_b) < 1e-13 * max_abs(expected_b));
  CHECK(max_abs(ydot.segment<6>(oc + 6) - expected_c) < 1e-13 * max_abs(expected_c));

  // The loads matter: without them the accelerations differ (the test is not vacuous).
  const EP::Coords free_a = body_a.accelerations(qa, qda, tumble::Wrench<double>{});
  CHECK(max_abs(expected_a - free_a) > 1.0);

  // Time enters through the user load: at another t the right-hand side changes accordingly.
  VectorXd ydot2(s.scene.size());
  tumble::rhs(s.scene, ws, t + 0.5, st, ydot2);
  const EP::Coords expected_a2 =
      tumble::accelerations(body_a, t + 0.5, qa, qda, s.gravity, s.drag, on_a);
  CHECK(max_abs(ydot2.segment<7>(oa + 7) - expected_a2) < 1e-13 * max_abs(expected_a2));
}

TEST_CASE("a re-centered chart gives the same physical accelerations", "[scene][scene]") {
  // Two copies of one body in the same physical state and under the same loads: one in Euler
  // parameters, one in ZYX angles started near gimbal lock (so on a chart with a base R0).
  // Both must have the same reference-point acceleration and angular acceleration
  // alpha = G thetaddot + Gdot thetadot (Eq. 1.10).
  using SceneT = Scene<Bodies<EPOff, ZYXOff>, Loads<tumble::UniformGravity, tumble::SpringDamper>>;
  SceneT scene;
  const Matrix3d r0 =
      rot(-0.2, Vector3d::UnitZ()) * rot(-1.45, Vector3d::UnitY()) * rot(0.9, Vector3d::UnitX());
  const InitialState s{Vector3d(0.3, 0.1, -0.2), r0, Vector3d(0.2, -0.1, 0.4),
                       Vector3d(1.5, -0.5, 2.5)};
  const auto e = scene.add(ep_off_body(), s);
  const auto z = scene.add(zyx_body(), s);
  const tumble::UniformGravity gravity(Vector3d(0, 0, -9.81));
  const tumble::SpringDamper spring(Vector3d(0.1, 0.2, -0.3), Vector3d(1, 1, 2),
                                    {.stiffness = 40.0, .damping = 1.5, .rest_length = 0.4});
  scene.add_load(e, gravity);
  scene.add_load(e, spring);
  scene.add_load(z, gravity);
  scene.add_load(z, spring);
  const SceneState& st = scene.initial_state();
  const VectorXd& y = st.y;
  REQUIRE(y.segment<3>(scene.offset(z) + 3).norm() == 0.0);      // the ZYX chart was re-centered
  REQUIRE(max_abs(st.base[z.id] - Matrix3d::Identity()) > 0.5);  // with a base

  VectorXd ydot(scene.size());
  SceneWorkspace ws(scene);
  tumble::rhs(scene, ws, 0.0, st, ydot);
  const int oe = scene.offset(e), oz = scene.offset(z);
  const Vector4d p = y.segment<4>(oe + 3);
  const Vector3d th = y.segment<3>(oz + 3), thd = y.segment<3>(oz + 9);
  const Vector3d alpha_e = EulerParameters::G(p) * ydot.segment<4>(oe + 10);
  const Vector3d alpha_z =
      EulerZYX::G(th) * ydot.segment<3>(oz + 9) + EulerZYX::Gdot_thetadot(th, thd);
  CHECK(max_abs(alpha_z - alpha_e) < 1e-12 * alpha_e.norm());
  CHECK(max_abs(ydot.segment<3>(oz + 6) - ydot.segment<3>(oe + 7)) <
        1e-12 * ydot.segment<3>(oe + 7).norm());
  CHECK(alpha_e.norm() > 1.0);
}

TEST_CASE("Euler parameters: the Baumgarte-stabilized constraint acceleration", "[scene][scene]") {
  // Off the constraint manifold (|p| = 1.01, p.pdot != 0) the scene imposes
  //   p.pddot = -|pdot|^2 - 2 g (p.pdot) - g^2 (|p|^2 - 1)/2,  g = |omega|,
  // and differs from the body's accelerations only along p. Without stabilization it uses the
  // body's accelerations unchanged.
  Scene<Bodies<EP>, Loads<tumble::BodyMoment>> scene;
  const auto a = scene.add(ep_body(), {.rotation = rot(1.1, Vector3d(1, -1, 2)),
                                       .velocity = Vector3d(1, 2, 3),
                                       .omega = Vector3d(0.9, -2.1, 1.3)});
  const tumble::BodyMoment moment(Vector3d(0.3, -0.2, 0.5));
  scene.add_load(a, moment);
  SceneState st = scene.initial_state();
  VectorXd& y = st.y;
  const Vector4d p = 1.01 * y.segment<4>(3);
  const Vector4d pd = y.segment<4>(10) + 0.05 * p;
  y.segment<4>(3) = p;
  y.segment<4>(10) = pd;

  const EP::Coords body_qdd =
      tumble::accelerations(scene.body(a), 0.0, q_of<EP>(y, 0), qdot_of<EP>(y, 0), moment);
  VectorXd ydot(scene.size());
  SceneWorkspace ws(scene);
  tumble::rhs(scene, ws, 0.0, st, ydot);
  const Vector4d pdd = ydot.segment<4>(10);
  const double g = (EulerParameters::G(p) * pd).norm();
  const double expected =
      -pd.squaredNorm() - 2.0 * g * p.dot(pd) - 0.5 * g * g * (p.squaredNorm() - 1.0);
  CHECK(std::abs(p.dot(pdd) - expected) < 1e-13 * pd.squaredNorm());
  const Vector4d diff = pdd - body_qdd.tail<4>();
  CHECK(max_abs(diff - diff.dot(p) / p.squaredNorm() * p) < 1e-14 * pdd.norm());
  CHECK(std::abs(diff.dot(p)) > 1e-3);  // the stabilization acts
  CHECK(ydot.segment<3>(7) == body_qdd.head<3>());

  ws.stabilize_constraints = false;
  tumble::rhs(scene, ws, 0.0, st, ydot);
  CHECK(max_abs(ydot.segment<7>(7) - body_qdd) < 1e-15 * max_abs(body_qdd));
}

// ---- physical quantities ---------------------------------------------------------------------

TEST_CASE("energy, momenta and centroids are the sums over the bodies", "[scene][scene]") {
  FullSetup s;
  const SceneState st = s.state();
  const VectorXd& y = st.y;
  double kinetic = 0.0, potential = 0.0;
  Vector3d momentum = Vector3d::Zero(), angular = Vector3d::Zero();
  const Vector3d g = s.gravity.g();

  // Each body from its own coordinates: R, omega = G thetadot, r_g = r_oc + R c,
  // v_g = rdot_oc + R (omega x c) (Eqs. 1.1, 1.4, 1.5).
  auto add_body = [&](auto h, const auto& body) {
    using Body = std::remove_cvref_t<decltype(body)>;
    using P = typename Body::Param;
    const int o = s.scene.offset(h);
    const typename Body::Theta th = y.segment<Body::n_theta>(o + 3);
    const typename Body::Theta thd = y.segment<Body::n_theta>(o + Body::nq + 3);
    const Matrix3d r = P::rotation(th);
    const Vector3d w = P::G(th) * thd;
    const auto& mp = body.mass_properties();
    const Vector3d rg = y.segment<3>(o) + r * mp.centroid();
    const Vector3d vg = y.segment<3>(o + Body::nq) + r * w.cross(mp.centroid());
    kinetic += 0.5 * mp.mass() * vg.squaredNorm() + 0.5 * w.dot(mp.inertia_centroid() * w);
    potential += -mp.mass() * g.dot(rg);
    momentum += mp.mass() * vg;
    angular += rg.cross(mp.mass() * vg) + r * (mp.inertia_centroid() * w);
    CHECK(max_abs(tumble::centroid_position(s.scene, h, st) - rg) < 1e-14);
  };
  add_body(s.a, s.scene.body(s.a));
  add_body(s.b, s.scene.body(s.b));
  add_body(s.c, s.scene.body(s.c));

  // Elastic energies 1/2 k (L - L0)^2 of the spring to the ground (on b) and of the coupling.
  const int ob = s.scene.offset(s.b), oa = s.scene.offset(s.a);
  const Matrix3d rb = EulerZYX::rotation(Vector3d(y.segment<3>(ob + 3)));
  const Matrix3d ra = EulerParameters::rotation(Vector4d(y.segment<4>(oa + 3)));
  const Vector3d spring_end = y.segment<3>(ob) + rb * Vector3d(0.1, 0.2, -0.3);
  const double stretch = (Vector3d(1, 1, 2) - spring_end).norm() - 0.4;
  potential += 0.5 * 40.0 * stretch * stretch;
  const Vector3d pa = y.segment<3>(oa) + ra * s.point_a, pb = y.segment<3>(ob) + rb * s.point_b;
  const double coupling_stretch = (pb - pa).norm() - s.coupling.rest_length;
  potential += 0.5 * s.coupling.stiffness * coupling_stretch * coupling_stretch;

  CHECK(std::abs(tumble::kinetic_energy(s.scene, st) - kinetic) < 1e-14 * kinetic);
  CHECK(std::abs(tumble::potential_energy(s.scene, st) - potential) < 1e-13 * std::abs(potential));
  CHECK(std::abs(tumble::energy(s.scene, st) - (kinetic + potential)) <
        1e-13 * std::abs(potential));
  CHECK(max_abs(tumble::linear_momentum(s.scene, st) - momentum) < 1e-14 * momentum.norm());
  CHECK(max_abs(tumble::angular_momentum(s.scene, st) - angular) < 1e-14 * angular.norm());
}

// ---- the quaternion constraint -----------------------------------------------------------------

TEST_CASE("project() takes Euler parameters onto their constraint manifold", "[scene][scene]") {
  Scene<Bodies<EP, RV>> scene;
  const auto a =
      scene.add(ep_body(), {.rotation = rot(0.5, Vector3d(1, 2, 0)), .omega = Vector3d(1, -2, 3)});
  const auto c =
      scene.add(rv_body(), {.rotation = rot(1.0, Vector3d(0, 0, 1)), .omega = Vector3d(0, 1, 0)});
  const auto d = scene.add(
      ep_body(), {.rotation = rot(2.5, Vector3d(-1, 0, 1)), .omega = Vector3d(3, 0, 0.5)});
  SceneState st = scene.initial_state();
  VectorXd& y = st.y;
  const int oa = scene.offset(a), od = scene.offset(d);
  y.segment<4>(oa + 3) *= 1.0 + 2e-6;
  y.segment<4>(oa + 10) += 3e-6 * y.segment<4>(oa + 3);
  y.segment<4>(od + 3) *= 1.0 - 4e-7;
  y.segment<4>(od + 10) -= 1e-6 * y.segment<4>(od + 3);

  // constraint_drift: the largest of | |p| - 1 | and |p.pdot| over the Euler-parameter bodies.
  const double expected_drift =
      std::max({std::abs(y.segment<4>(oa + 3).norm() - 1.0),
                std::abs(y.segment<4>(oa + 3).dot(y.segment<4>(oa + 10))),
                std::abs(y.segment<4>(od + 3).norm() - 1.0),
                std::abs(y.segment<4>(od + 3).dot(y.segment<4>(od + 10)))});
  CHECK(tumble::constraint_drift(scene, st) == expected_drift);
  CHECK(expected_drift > 2e-6);

  tumble::test::Random random(3);
  VectorXd corr = VectorXd::Constant(scene.size(), 99.0);
  VectorXd err(scene.size());
  for (int i = 0; i < err.size(); ++i) {
    err[i] = random.normal();
  }
  const VectorXd err0 = err;
  tumble::project(scene, y, corr, err);
  const SceneState sp{y + corr, st.base};
  const VectorXd& yp = sp.y;
  CHECK(tumble::constraint_drift(scene, sp) < 1e-15);
  for (int o : {oa, od}) {
    const Vector4d pn = yp.segment<4>(o + 3);
    // The orthogonal projection: p/|p|, and pdot minus its component along p.
    CHECK(max_abs(pn - y.segment<4>(o + 3).normalized()) < 1e-16);
    const Vector4d pd = y.segment<4>(o + 10);
    CHECK(max_abs(yp.segment<4>(o + 10) - (pd - pd.dot(pn) * pn)) < 1e-16);
    // The error estimate loses its components normal to the manifold, and only those.
    const Vector4d ep = err.segment<4>(o + 3), ev = err.segment<4>(o + 10);
    const Vector4d ep0 = err0.segment<4>(o + 3), ev0 = err0.segment<4>(o + 10);
    CHECK(std::abs(ep.dot(pn)) < 1e-15);
    CHECK(std::abs(ev.dot(pn)) < 1e-15);
    CHECK(max_abs(ep - (ep0 - ep0.dot(pn) * pn)) < 1e-15);
    CHECK(max_abs(ev - (ev0 - ev0.dot(pn) * pn)) < 1e-15);
    CHECK(err.segment<3>(o) == err0.segment<3>(o));
  }
  // The positions, velocities and the rotation vector are not touched.
  CHECK(corr.segment<3>(oa).norm() == 0.0);
  CHECK(corr.segment<3>(oa + 7).norm() == 0.0);
  CHECK(corr.segment<12>(scene.offset(c)).norm() == 0.0);
  CHECK(err.segment<12>(scene.offset(c)) == err0.segment<12>(scene.offset(c)));
  // The attitude is unchanged by the projection.
  CHECK(max_abs(tumble::rotation(scene, d, sp) - tumble::rotation(scene, d, st)) < 1e-5);
  CHECK(max_abs(tumble::rotation(scene, d, sp) - rot(2.5, Vector3d(-1, 0, 1))) < 1e-15);

  // Without an error estimate (size 0) only the correction is computed.
  VectorXd none(0);
  VectorXd corr2(scene.size());
  tumble::project(scene, y, corr2, none);
  CHECK(corr2 == corr);

  // In place (what the explicit integrator applies): the same map, p exactly p / |p| as Eigen
  // computes it, and nothing else touched.
  VectorXd yi = y;
  tumble::project_in_place(scene, yi);
  CHECK(tumble::constraint_drift(scene, SceneState{yi, st.base}) < 1e-15);
  for (int o : {oa, od}) {
    const Vector4d p = y.segment<4>(o + 3);
    CHECK(yi.segment<4>(o + 3) == Vector4d(p / p.norm()));
    CHECK(max_abs(yi.segment<4>(o + 10) - yp.segment<4>(o + 10)) < 1e-16);
  }
  CHECK(yi.segment<3>(oa) == y.segment<3>(oa));
  CHECK(yi.segment<3>(oa + 7) == y.segment<3>(oa + 7));
  CHECK(yi.segment<12>(scene.offset(c)) == y.segment<12>(scene.offset(c)));
  CHECK(max_abs(yi - yp) < 1e-16);
}

// ---- allocations -------------------------------------------------------------------------------

TEST_CASE("the right-hand side and the root functions allocate nothing", "[scene][scene]") {
  FullSetup s;
  s.scene.add_event({.function = [](double, const tumble::SceneStateView& v) { return v.y[2]; },
                     .direction = -1,
                     .action = {}});
  SceneState st = s.state();
  VectorXd& y = st.y;
  VectorXd ydot(s.scene.size()), g(s.scene.root_count());
  // As CVODE calls them: through maps of its own vectors.
  const Eigen::Map<const VectorXd> ym(y.data(), y.size());
  Eigen::Map<VectorXd> ydm(ydot.data(), ydot.size());
  Eigen::Map<VectorXd> gm(g.data(), g.size());
  SceneWorkspace ws(s.scene);
  const std::span<const Matrix3d> base(st.base);
  tumble::rhs(s.scene, ws, 0.0, ym, base, ydm);
  double sum = 0.0;
  tumble::test::AllocationCounter counter;
  for (int i = 0; i < 200; ++i) {
    tumble::rhs(s.scene, ws, 0.01 * i, ym, base, ydm);
    tumble::chart_roots(s.scene, ym, gm);
    const tumble::SceneStateView view(ym.data(), ym.size(), base);
    gm[2] = s.scene.events()[0].function(0.01 * i, view);
    sum += ydot[10] + g[0];
  }
  const long n = counter.stop();
  CHECK(n == 0);
  CHECK(std::isfinite(sum));
  CHECK(g.size() == 3);  // ZYX and rotation vector charts, and the event
  CHECK(g[2] == y[2]);
}

// A body held at a fixed point gets its position once, from the body: the initial state may leave
// it at zero or repeat it to 1e-12 relative; anything else is refused, naming both.
TEST_CASE("scene: a fixed point is given once, to the body", "[scene]") {
  using Held = RigidBody<EulerParameters, ReferencePoint::fixed_point>;
  const auto mp =
      MassProperties<>::about_centroid(1.0, Vector3d(1, 2, 3).asDiagonal(), Vector3d(0, 0, 0.2));
  const Vector3d pivot(3.0, -1.0, 2.0);
  tumble::Scene<Bodies<Held>> scene;
  const auto a = scene.add(Held(mp, pivot), {.omega = {0, 0, 1}});  // position left at zero
  CHECK(tumble::position(scene, a, scene.initial_state()) == pivot);
  // Repeated, with the rounding of a computed point (1e-15 relative): accepted.
  (void)scene.add(Held(mp, pivot), {.position = pivot * (1 + 1e-15)});
  // Off by 1e-9 m, or moving: refused with the point, the distance and the rule.
  const auto refused = [&](const InitialState& s) {
    try {
      (void)scene.add(Held(mp, pivot), s);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  const std::string off = refused({.position = pivot + Vector3d(0, 0, 1e-9)});
  CHECK(off.find("is held at its fixed point (3, -1, 2)") != std::string::npos);
  CHECK(off.find("leave InitialState::position at zero, or repeat that point") !=
        std::string::npos);
  CHECK(off.find("1.0000000") != std::string::npos);  // the distance, 1.0000000xxe-09 m
  CHECK(refused({.velocity = {0, 1e-6, 0}}).find("leave the velocity zero") != std::string::npos);
  CHECK(scene.body_count() == 2);
}

// The state's size from the types, for a fixed-size integrator: [r; p; v; omega] (13) and
// [r; theta; v; omega] (12) per free body, [p; omega] (7) for one held at a point; [q; qdot] in
// the chapter's form (14 for Euler parameters).
static_assert(tumble::state_size<tumble::Scene<Bodies<RigidBody<EulerParameters>>>,
                                 RigidBody<EulerParameters>> == 13);
static_assert(
    tumble::state_size<tumble::Scene<Bodies<RigidBody<EulerParameters>, RigidBody<EulerZYX>>>,
                       RigidBody<EulerParameters>, RigidBody<EulerZYX>, RigidBody<EulerZYX>> ==
    13 + 2 * 12);
static_assert(tumble::state_size<
                  tumble::Scene<Bodies<RigidBody<EulerParameters, ReferencePoint::fixed_point>>>,
                  RigidBody<EulerParameters, ReferencePoint::fixed_point>> == 7);
static_assert(tumble::state_size<tumble::Scene<Bodies<RigidBody<EulerParameters>>, tumble::Loads<>,
                                               tumble::StateForm::generalized>,
                                 RigidBody<EulerParameters>> == 14);
