#pragma once
// The mixed scenes of the Jacobian tests (tests/scene/jacobian*.test.cpp): five bodies of three
// types (P framed off its centroid, P at its centroid, and a third parameterization), every load
// type tumble has, and a user force and a user coupling written for any scalar, so that the
// scene is differentiable. Random mass properties and states from a seeded generator, and the
// reference the tests hold the Jacobian to: a column of df/dy by extrapolated central differences
// of tumble::rhs.

#include <cmath>
#include <limits>
#include <span>
#include <type_traits>
#include <utility>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "support/finite_difference.hpp"
#include "support/random.hpp"
#include "tumble/body/rigid_body.hpp"
#include "tumble/force/coupling.hpp"
#include "tumble/force/gravity.hpp"
#include "tumble/force/point_force.hpp"
#include "tumble/force/spring_damper.hpp"
#include "tumble/force/user_force.hpp"
#include "tumble/orientation/euler_parameters.hpp"
#include "tumble/orientation/rotation_vector.hpp"
#include "tumble/scene/rhs.hpp"
#include "tumble/scene/scene.hpp"
#include "tumble/scene/state.hpp"
#include "tumble/scene/workspace.hpp"

namespace tumble::test::mixed {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using Eigen::VectorXd;
using tumble::Bodies;
using tumble::InitialState;
using tumble::Loads;
using tumble::MassProperties;
using tumble::ReferencePoint;
using tumble::RigidBody;
using tumble::Scene;

/// A user force for any scalar: a smooth nonlinear drag -c sqrt(1 + |v|^2) v, a time-dependent
/// push sin(t) e_x, and a body-fixed force a x omega at the body point r (so it reads R).
struct Swirl {
  template <class S, ReferencePoint Ref>
  tumble::Wrench<S> operator()(const S& t, const tumble::BodyKinematics<S, Ref>& k) const {
    using std::sin;
    using std::sqrt;
    tumble::Wrench<S> w;
    w.force = -S(0.4) * sqrt(S(1) + k.velocity.squaredNorm()) * k.velocity +
              tumble::Vector3<S>(sin(t), S(0), S(0));
    const tumble::Vector3<S> a(S(0.3), S(-0.2), S(0.5));
    w.add_body_force(k.rotation, tumble::Vector3<S>(S(0.1), S(0.2), S(-0.1)), a.cross(k.omega));
    return w;
  }
};

/// A user coupling for any scalar: a torsional damper, moment c (omega_b - omega_a) in a's axes
/// on a, and the opposite on b.
struct Torsion {
  template <class S>
  void operator()(const S& /*t*/, const tumble::KinematicsView<S>& a,
                  const tumble::KinematicsView<S>& b, tumble::Wrench<S>& wa,
                  tumble::Wrench<S>& wb) const {
    const tumble::Matrix3<S> rab = a.rotation.transpose() * b.rotation;
    const tumble::Vector3<S> m = S(0.7) * (rab * b.omega - a.omega);
    wa.add_moment(m);
    wb.add_moment(tumble::Vector3<S>(-(rab.transpose() * m)));
  }
};

using AllLoads =
    Loads<tumble::UniformGravity, tumble::PointForce, tumble::BodyMoment, tumble::SpringDamper,
          tumble::UserForce<Swirl>, tumble::SpringDamperBetween, tumble::UserCoupling<Torsion>>;

/// A third body type distinct from RigidBody<P, centroid>.
template <class P>
using Other = RigidBody<std::conditional_t<std::is_same_v<P, tumble::RotationVector>,
                                           tumble::EulerParameters, tumble::RotationVector>>;

template <class P>
using MixedScene =
    Scene<Bodies<RigidBody<P, ReferencePoint::offset>, RigidBody<P>, Other<P>>, AllLoads>;

inline MassProperties<double> random_mass(Random& rng, bool offset) {
  const Vector3d moments(rng.uniform(1, 2), rng.uniform(1, 2), rng.uniform(1, 2));  // I1 + I2 >= I3
  const Matrix3d r = Eigen::Matrix3d(rng.quaternion());
  return MassProperties<double>::about_centroid(rng.uniform(0.5, 3),
                                                r * moments.asDiagonal() * r.transpose(),
                                                offset ? rng.vector(0.3) : Vector3d::Zero());
}

inline InitialState random_state(Random& rng) {
  InitialState s;
  s.position = rng.vector(1.0);
  s.rotation = Matrix3d(rng.quaternion());
  s.velocity = rng.vector(1.0);
  s.omega = rng.vector(1.5);
  return s;
}

/// Five bodies of three types, every load type, two bodies of one type, one body without loads.
template <class P> void build(MixedScene<P>& scene, Random& rng) {
  using Off = RigidBody<P, ReferencePoint::offset>;
  using Cen = RigidBody<P>;
  const auto a = scene.add(Off(random_mass(rng, true)), random_state(rng));
  const auto b = scene.add(Cen(random_mass(rng, false)), random_state(rng));
  const auto c = scene.add(Other<P>(random_mass(rng, false)), random_state(rng));
  const auto d = scene.add(Off(random_mass(rng, true)), random_state(rng));
  scene.add(Cen(random_mass(rng, false)), random_state(rng));  // no loads at all
  const tumble::UniformGravity gravity(Vector3d(0, 0, -9.81));
  scene.add_load(a, gravity);
  scene.add_load(b, gravity);
  scene.add_load(a, tumble::PointForce(rng.vector(0.3), rng.vector(2.0), tumble::Components::body));
  scene.add_load(b, tumble::PointForce(Vector3d::Zero(), rng.vector(2.0)));
  scene.add_load(c, tumble::BodyMoment(rng.vector(1.0)));
  scene.add_load(a, tumble::SpringDamper(rng.vector(0.3), rng.vector(3.0),
                                         {.stiffness = 40, .damping = 1.5, .rest_length = 0.4}));
  scene.add_load(d, tumble::make_user_force(Swirl{}));
  scene.add_load(c, tumble::make_user_force(Swirl{}));
  scene.add_load(
      a, b,
      tumble::SpringDamperBetween(rng.vector(0.3), rng.vector(0.3),
                                  {.stiffness = 25, .damping = 0.8, .rest_length = 0.5}));
  scene.add_load(b, c,
                 tumble::SpringDamperBetween(rng.vector(0.3), Vector3d::Zero(),
                                             {.stiffness = 10, .damping = 0.3}));
  scene.add_load(a, d, tumble::UserCoupling<Torsion>(Torsion{}));
}

/// Column j of df/dy at y by Richardson-extrapolated central differences of tumble::rhs, with a
/// bound on its error: the extrapolation's own estimate (tests/support/finite_difference.hpp,
/// which assumes f in long double) plus the rounding of f in double, 3 eps |f| / h_min (the
/// weights of the extrapolation sum to less than 3).
template <class SceneT>
std::pair<VectorXd, double> fd_column(const SceneT& scene, tumble::SceneWorkspace<SceneT>& ws,
                                      double t, const tumble::SceneState& st, int j) {
  double f_scale = 0;
  const auto f = [&](long double h) {
    VectorXd yh = st.y;
    yh(j) += static_cast<double>(h);
    VectorXd out(yh.size());
    tumble::rhs(scene, ws, t, yh, std::span<const Matrix3d>(st.base), out);
    f_scale = std::max(f_scale, out.cwiseAbs().maxCoeff());
    return Eigen::Matrix<long double, Eigen::Dynamic, 1>(out.cast<long double>());
  };
  // Every coordinate and rate varies on a scale of order 1 here (rad, m, rad/s, m/s): h0 = 1/32,
  // five levels, h_min = 1/512.
  const auto fd = richardson_derivative(f, 1.0L / 32, 5);
  const double rounding = 3 * std::numeric_limits<double>::epsilon() * f_scale * 512;
  return {fd.value.template cast<double>(), static_cast<double>(fd.error) + rounding};
}

}  // namespace tumble::test::mixed
