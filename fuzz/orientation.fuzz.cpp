// libFuzzer target: the orientation parameterizations' conversions from arbitrary bytes.
// Input: one byte picks the source and target sets (16 each), then the source coordinates and an
// angular velocity. Property: on finite coordinates every step either works with
// finite results or throws std::invalid_argument / std::domain_error (NonFiniteError), and a
// result that works is correct: R orthonormal, the converted coordinates give the same R, and
// G(theta) thetadot(theta, omega) = omega away from the singular attitudes. Non-finite
// coordinates are outside the domain of these unchecked hot-path functions (the scene and the
// integrator reject non-finite states before they reach them) and are skipped, as are
// coordinates above 1e6 (see check()).

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <tuple>

#include "fuzz_input.hpp"
#include "tumble/tumble.hpp"

namespace {

using All = std::tuple<tumble::EulerParameters, tumble::EulerXYZ, tumble::EulerXZY,
                       tumble::EulerYXZ, tumble::EulerYZX, tumble::EulerZXY, tumble::EulerZYX,
                       tumble::EulerXYX, tumble::EulerXZX, tumble::EulerYXY, tumble::EulerYZY,
                       tumble::EulerZXZ, tumble::EulerZYZ, tumble::RodriguesParameters,
                       tumble::ModifiedRodriguesParameters, tumble::RotationVector>;

[[noreturn]] void finding(const char* what, std::string_view from, std::string_view to) {
  std::fprintf(stderr, "FINDING: %s (from %.*s to %.*s)\n", what, static_cast<int>(from.size()),
               from.data(), static_cast<int>(to.size()), to.data());
  std::abort();
}

template <class F> void with_type(int index, F&& f) {
  int i = 0;
  std::apply([&](auto... p) { ((i++ == index ? f(p) : void()), ...); }, All{});
}

template <class From, class To> void check(const Eigen::Vector4d& raw, const Eigen::Vector3d& w) {
  using CF = typename From::template Coords<double>;
  CF c = raw.head<From::size>();
  // Domain: finite coordinates up to 1e6 (a million rad, far beyond any simulated attitude).
  // Beyond that, sin/cos of the angle and of its half stop agreeing to 1e-8 after rounding (the
  // first finding of this target: EulerZXZ with theta3 = 5.7e67 converted to EulerZXY).
  if (!c.allFinite() || !w.allFinite() || c.cwiseAbs().maxCoeff() > 1e6) return;
  try {
    c = From::canonical(c);
    if (!c.allFinite()) finding("canonical() returned a non-finite value", From::name, To::name);
    const Eigen::Matrix3d r = From::rotation(c);
    if (!r.allFinite()) finding("rotation() returned a non-finite matrix", From::name, To::name);
    if ((r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-9 ||
        r.determinant() < 0)
      finding("rotation() is not a rotation", From::name, To::name);
    const auto t = tumble::convert<To, From>(c);
    if (!t.allFinite()) finding("convert() returned a non-finite value", From::name, To::name);
    const Eigen::Matrix3d rt = To::rotation(t);
    if ((rt - r).cwiseAbs().maxCoeff() > 1e-8)
      finding("convert() changed the attitude", From::name, To::name);
    const auto back = To::from_rotation(r);
    if (!back.allFinite())
      finding("from_rotation() returned a non-finite value", From::name, To::name);
    if ((To::rotation(back) - r).cwiseAbs().maxCoeff() > 1e-8)
      finding("from_rotation() changed the attitude", From::name, To::name);
    // The rate map, away from the singular attitudes (where G is ill-conditioned by design).
    if (From::singularity_distance(c) > 1e-2 && w.norm() < 1e6) {
      const CF td = From::thetadot(c, w);
      if (!td.allFinite()) finding("thetadot() returned a non-finite value", From::name, To::name);
      const Eigen::Vector3d w2 = From::G(c) * td;
      if ((w2 - w).norm() > 1e-6 * (1.0 + w.norm()))
        finding("G(theta) thetadot(theta, omega) != omega", From::name, To::name);
    }
  } catch (const std::invalid_argument&) {
  } catch (const std::domain_error&) {  // tumble::NonFiniteError, canonical() of zero
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  tumble_fuzz::Input in(data, size);
  const std::uint8_t pick = in.byte();
  Eigen::Vector4d raw;
  for (int i = 0; i < 4; ++i) raw(i) = in.real();
  Eigen::Vector3d w;
  for (int i = 0; i < 3; ++i) w(i) = in.real();
  with_type(pick % 16, [&](auto from) {
    with_type((pick / 16) % 16, [&](auto to) { check<decltype(from), decltype(to)>(raw, w); });
  });
  return 0;
}
