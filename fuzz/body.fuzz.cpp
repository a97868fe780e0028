// libFuzzer target: mass properties and rigid bodies from arbitrary bytes.
// Input: a mode byte (about the centroid or the reference point), the mass, 9 inertia entries,
// the centroid, then a state (position, quaternion, velocity, omega) and a wrench. Property:
// construction either works, with finite mass properties (inverse included), or
// throws std::invalid_argument; the accelerations of a constructed body at a finite state are
// finite or throw tumble::NonFiniteError. Never a crash, a hang or a silent NaN.

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <stdexcept>

#include "fuzz_input.hpp"
#include "tumble/tumble.hpp"

namespace {

[[noreturn]] void finding(const char* what) {
  std::fprintf(stderr, "FINDING: %s\n", what);
  std::abort();
}

template <class Body> void accelerations(const Body& body, tumble_fuzz::Input& in) {
  typename Body::Coords q, qd;
  for (int i = 0; i < 3; ++i) q(i) = in.real();
  Eigen::Vector4d p;
  for (int i = 0; i < 4; ++i) p(i) = in.real();
  Eigen::Vector3d v, w;
  for (int i = 0; i < 3; ++i) v(i) = in.real();
  for (int i = 0; i < 3; ++i) w(i) = in.real();
  tumble::Wrench<double> wr;
  for (int i = 0; i < 3; ++i) wr.force(i) = in.real();
  for (int i = 0; i < 3; ++i) wr.moment(i) = in.real();
  try {
    q.template tail<4>() = tumble::EulerParameters::canonical<double>(p);
    qd = Body::qdot_from(q, v, w);
    const typename Body::Coords qdd = body.accelerations(q, qd, wr);
    if (!qdd.allFinite()) finding("accelerations() returned a non-finite value without throwing");
  } catch (const tumble::NonFiniteError&) {
  } catch (const std::domain_error&) {  // canonical() of a zero or non-finite quaternion
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  tumble_fuzz::Input in(data, size);
  const std::uint8_t mode = in.byte();
  const double mass = in.real();
  Eigen::Matrix3d inertia;
  for (int i = 0; i < 9; ++i) inertia(i / 3, i % 3) = in.real();
  Eigen::Vector3d centroid;
  for (int i = 0; i < 3; ++i) centroid(i) = in.real();
  std::optional<tumble::MassProperties<>> mp;
  try {
    mp = (mode & 1u) ? tumble::MassProperties<>::about_reference(mass, inertia, centroid)
                     : tumble::MassProperties<>::about_centroid(mass, inertia, centroid);
  } catch (const std::invalid_argument&) {
    return 0;
  }
  if (!(std::isfinite(mp->mass()) && mp->mass() > 0)) finding("accepted a bad mass");
  if (!mp->inertia_centroid().allFinite() || !mp->inertia_reference().allFinite() ||
      !mp->inertia_centroid_inverse().allFinite() || !mp->first_moment().allFinite())
    finding("accepted mass properties with a non-finite derived quantity");
  if (!mp->principal_moments().allFinite() || !(mp->principal_moments()(0) > 0))
    finding("accepted an inertia that is not positive definite");
  const tumble::RigidBody<tumble::EulerParameters, tumble::ReferencePoint::offset> body(*mp);
  accelerations(body, in);
  if (mp->centroid().isZero(0.0)) {
    const tumble::RigidBody<tumble::EulerParameters> centroidal(*mp);
    accelerations(centroidal, in);
  }
  return 0;
}
