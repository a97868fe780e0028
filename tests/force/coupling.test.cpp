// Tests of the loads between two bodies (include/tumble/force/coupling.hpp): UserCoupling adds
// the callable's loads to both bodies and throws NonFiniteError, as UserForce does, when they are
// not finite (leaving the wrenches untouched); SpringDamperBetween's elastic energy is
// 1/2 k (L - L0)^2 and the same as SpringDamper's for the same ends.

#include "tumble/force/coupling.hpp"

#include <cmath>
#include <limits>

#include "support/body_fixtures.hpp"
#include "support/catch.hpp"
#include "tumble/force/spring_damper.hpp"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using tumble::KinematicsView;
using tumble::Wrench;

constexpr double kTol = 256 * std::numeric_limits<double>::epsilon();

/// Equal and opposite forces f at the reference points, and a moment m on body a only.
struct Push {
  Vector3d f;
  Vector3d m = Vector3d::Zero();
  template <class S>
  void operator()(const S& /*t*/, const KinematicsView<S>& /*a*/, const KinematicsView<S>& /*b*/,
                  Wrench<S>& wa, Wrench<S>& wb) const {
    wa.force += f.cast<S>();
    wa.moment += m.cast<S>();
    wb.force -= f.cast<S>();
  }
};

/// Adds `bad` to one of the 12 entries of (wa.force, wa.moment, wb.force, wb.moment).
struct Broken {
  int entry;
  double bad;
  template <class S>
  void operator()(const S& /*t*/, const KinematicsView<S>& /*a*/, const KinematicsView<S>& /*b*/,
                  Wrench<S>& wa, Wrench<S>& wb) const {
    Wrench<S>& w = entry < 6 ? wa : wb;
    const int i = entry % 6;
    (i < 3 ? w.force(i) : w.moment(i - 3)) += S(bad);
  }
};

static_assert(tumble::CouplingElement<tumble::UserCoupling<Push>>);
static_assert(tumble::CouplingElement<tumble::UserCoupling<Broken>>);

/// A body at `position`, rotated by `rotation`, at rest.
KinematicsView<double> at(const Vector3d& position, const Matrix3d& rotation) {
  KinematicsView<double> k;
  k.position = position;
  k.rotation = rotation;
  return k;
}

}  // namespace

TEST_CASE("UserCoupling adds the callable's loads to both bodies", "[force][coupling]") {
  const tumble::UserCoupling<Push> push(Push{Vector3d(1, 2, 3), Vector3d(0, 0, 4)});
  const auto a = at(Vector3d::Zero(), Matrix3d::Identity());
  const auto b = at(Vector3d(1, 0, 0), Matrix3d::Identity());
  Wrench<double> wa, wb;
  wa.force = Vector3d(10, 0, 0);  // a load applied before: kept
  push.apply(0.0, a, b, wa, wb);
  CHECK(wa.force == Vector3d(11, 2, 3));
  CHECK(wa.moment == Vector3d(0, 0, 4));
  CHECK(wb.force == Vector3d(-1, -2, -3));
  CHECK(wb.moment == Vector3d::Zero());
}

TEST_CASE("UserCoupling throws NonFiniteError for a non-finite load", "[force][coupling]") {
  const auto a = at(Vector3d::Zero(), Matrix3d::Identity());
  const auto b = at(Vector3d(1, 0, 0), Matrix3d::Identity());
  for (const double bad :
       {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
        -std::numeric_limits<double>::infinity()}) {
    for (int entry = 0; entry < 12; ++entry) {
      INFO("entry " << entry << " = " << bad);
      const tumble::UserCoupling<Broken> broken(Broken{entry, bad});
      Wrench<double> wa, wb;
      wa.force = Vector3d(1, 2, 3);
      REQUIRE_THROWS_AS(broken.apply(0.0, a, b, wa, wb), tumble::NonFiniteError);
      REQUIRE_THROWS_WITH(broken.apply(0.0, a, b, wa, wb),
                          TUMBLE_CONTAINS("tumble::UserCoupling: the user coupling added a "
                                          "non-finite load"));
      // Nothing was added to either body.
      CHECK(wa.force == Vector3d(1, 2, 3));
      CHECK(wa.moment == Vector3d::Zero());
      CHECK(wb.force == Vector3d::Zero());
      CHECK(wb.moment == Vector3d::Zero());
    }
  }
}

TEST_CASE("spring energy: 1/2 k (L - L0)^2, the same between bodies and to the ground",
          "[force][coupling]") {
  const tumble::SpringDamperParameters sd{8.0, 0.5, 1.5};
  // Body a at (1, 0, 0) turned 90 degrees about z: its point (0, 1, 0) sits at (0, 0, 0).
  Matrix3d rz;
  rz << 0, -1, 0,  //
      1, 0, 0,     //
      0, 0, 1;
  const auto a = at(Vector3d(1, 0, 0), rz);
  const Vector3d point_a(0, 1, 0);
  // Body b at (0, 0, 4), not rotated: its point (0, 0, -1) sits at (0, 0, 3). L = 3.
  const auto b = at(Vector3d(0, 0, 4), Matrix3d::Identity());
  const Vector3d point_b(0, 0, -1);
  const double expected = 0.5 * 8.0 * (3.0 - 1.5) * (3.0 - 1.5);  // 9

  const tumble::SpringDamperBetween between(point_a, point_b, sd);
  CHECK(std::abs(between.potential_energy(a, b) - expected) < kTol * expected);

  // The same spring from body a to the fixed point (0, 0, 3).
  const tumble::SpringDamper ground(point_a, Vector3d(0, 0, 3), sd);
  tumble::BodyKinematics<double> ka;
  static_cast<KinematicsView<double>&>(ka) = a;
  CHECK(ground.potential_energy(ka) == between.potential_energy(a, b));
}
