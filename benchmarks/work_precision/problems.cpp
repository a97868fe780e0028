// tumble_bench: the problems (bodies, initial states, loads, output times), their references
// (exact, or a long-double integration for the stiff top), the error measures, and the timing
// bookkeeping every method shares. The methods themselves: work_precision/tumble.hpp (tumble),
// floors/cvode_rk4.cpp (hand-written CVODE floor, RK4), peers/pinocchio_work_precision.cpp.
//
// Sources of the exact solutions: tests/support/torque_free.hpp (Jacobi elliptic functions for
// omega, the angular-momentum angles for R; long double) and, under uniform gravity, the
// parabola of the centroid r_g(t) = r_g(0) + v_g(0) t + g t^2 / 2 (gravity exerts no moment about
// the centroid, so the attitude is that of the torque-free body).

#include <algorithm>
#include <cmath>
#include <exception>
#include <numeric>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "common/bench.hpp"
#include "support/torque_free.hpp"
#include "tumble/cvode.hpp"

namespace tumble::bench {

// ---- errors ------------------------------------------------------------------------------------

double geodesic_angle(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  const Eigen::Matrix3d e = a.transpose() * b;
  const Eigen::Vector3d axial(e(2, 1) - e(1, 2), e(0, 2) - e(2, 0), e(1, 0) - e(0, 1));
  return std::atan2(0.5 * axial.norm(), 0.5 * (e.trace() - 1.0));
}

namespace {
Eigen::Vector3d centroid_of(const Problem& p, const Sample& s) {
  return s.position + s.rotation * p.centroid;
}
Eigen::Vector3d centroid_velocity_of(const Problem& p, const Sample& s) {
  return s.velocity + s.rotation * s.omega.cross(p.centroid);
}
}  // namespace

double energy(const Problem& p, const Sample& s) {
  const Eigen::Vector3d vg = centroid_velocity_of(p, s);
  const double kinetic =
      0.5 * p.mass * vg.squaredNorm() + 0.5 * s.omega.dot(p.inertia.cwiseProduct(s.omega));
  double potential = -p.mass * p.gravity.dot(centroid_of(p, s));
  if (p.stiffness > 0) {
    potential += 0.5 * p.stiffness * s.position.squaredNorm();  // spring to the origin, L0 = 0
  }
  return kinetic + potential;
}

Eigen::Vector3d centroid_momentum(const Problem& p, const Sample& s) {
  return s.rotation * p.inertia.cwiseProduct(s.omega);
}

Errors evaluate(const Problem& p, const Run& r) {
  Errors e;
  if (!r.ok || r.samples.size() != p.reference.size() || r.samples.empty()) {
    return e;
  }
  const double e_scale = std::max(std::abs(energy(p, p.reference.front())), 1e-300);
  const double h_scale = std::max(centroid_momentum(p, p.reference.front()).norm(), 1e-300);
  e.max_attitude = e.max_centroid = e.max_omega = e.energy_drift = e.momentum_drift = 0;
  for (std::size_t k = 0; k < r.samples.size(); ++k) {
    const Sample& s = r.samples[k];
    const Sample& x = p.reference[k];
    const double angle = geodesic_angle(x.rotation, s.rotation);
    if (!std::isfinite(angle)) {
      e.max_attitude = std::numeric_limits<double>::infinity();
      break;
    }
    e.max_attitude = std::max(e.max_attitude, angle);
    e.max_centroid = std::max(e.max_centroid, (centroid_of(p, s) - centroid_of(p, x)).norm());
    e.max_omega = std::max(e.max_omega, (s.omega - x.omega).norm());
    e.energy_drift = std::max(e.energy_drift, std::abs(energy(p, s) - energy(p, x)) / e_scale);
    e.momentum_drift = std::max(
        e.momentum_drift, (centroid_momentum(p, s) - centroid_momentum(p, x)).norm() / h_scale);
  }
  e.final_attitude = geodesic_angle(p.reference.back().rotation, r.samples.back().rotation);
  return e;
}

// ---- timing
// --------------------------------------------------------------------------------------

void record_time(Run& run, std::vector<double>& times, const Stopwatch& watch,
                 const Timing& timing) {
  const double wall = watch.wall();
  const double cpu = watch.cpu();
  const double seconds = timing.base == TimeBase::cpu ? cpu : wall;
  times.push_back(seconds);
  run.seconds = std::min(run.seconds, seconds);
  run.wall_seconds = std::min(run.wall_seconds, wall);
  run.cpu_seconds = std::min(run.cpu_seconds, cpu);
}

bool another_rep(const Timing& timing, const std::vector<double>& times) {
  const auto n = static_cast<int>(times.size());
  if (n == 1 && times.front() > timing.slow_run) {
    return false;
  }
  if (n < timing.reps) {
    return true;
  }
  return n < timing.max_reps && std::accumulate(times.begin(), times.end(), 0.0) < timing.min_total;
}

void finish_timing(Run& run, std::vector<double>& times) {
  run.reps = static_cast<int>(times.size());
  if (times.empty()) {
    return;
  }
  std::sort(times.begin(), times.end());
  const std::size_t n = times.size();
  run.seconds_median = n % 2 == 1 ? times[n / 2] : 0.5 * (times[n / 2 - 1] + times[n / 2]);
  run.rep_seconds = times;
}

void merge_timing(Run& run, const Run& again) {
  run.seconds = std::min(run.seconds, again.seconds);
  run.wall_seconds = std::min(run.wall_seconds, again.wall_seconds);
  run.cpu_seconds = std::min(run.cpu_seconds, again.cpu_seconds);
  std::vector<double> times = run.rep_seconds;
  times.insert(times.end(), again.rep_seconds.begin(), again.rep_seconds.end());
  finish_timing(run, times);
}

// ---- the problems
// --------------------------------------------------------------------------------

std::vector<Sample> exact_samples(const Problem& p) {
  using test::TorqueFreeBody;
  using Vec3L = TorqueFreeBody::Vec3L;
  using Mat3L = TorqueFreeBody::Mat3L;
  const Vec3L inertia = p.inertia.cast<long double>();
  const Vec3L omega0 = p.omega0.cast<long double>();
  const Mat3L r0 = p.r0.cast<long double>();
  const TorqueFreeBody body(inertia, omega0, r0);
  // The centroid's parabola, in long double.
  const Vec3L c = p.centroid.cast<long double>();
  const Vec3L rg0 = p.position0.cast<long double>() + p.r0.cast<long double>() * c;
  const Vec3L vg0 = p.velocity0.cast<long double>() +
                    p.r0.cast<long double>() * p.omega0.cast<long double>().cross(c);
  const Vec3L g = p.gravity.cast<long double>();
  std::vector<Sample> out(p.times.size());
  for (std::size_t k = 0; k < p.times.size(); ++k) {
    const long double t = p.times[k];
    const TorqueFreeBody::Mat3L r = body.rotation_ld(t);
    const Vec3L w = body.omega_ld(t);
    const Vec3L rg = rg0 + vg0 * t + 0.5L * g * t * t;
    const Vec3L vg = vg0 + g * t;
    out[k].rotation = r.cast<double>();
    out[k].omega = w.cast<double>();
    out[k].position = (rg - r * c).cast<double>();
    out[k].velocity = (vg - r * w.cross(c)).cast<double>();
  }
  return out;
}

namespace {

/// One long double RK4 integration of the stiff top (see stiff_top_reference).
std::vector<Sample> stiff_top_rk4(const Problem& p, int substeps) {
  using L = long double;
  using P = EulerParameters;
  using Body = RigidBody<P, ReferencePoint::offset, L>;
  using Coords = Body::Coords;
  const Body body(MassProperties<L>::about_centroid(
      L(p.mass), Matrix3<L>(p.inertia.cast<L>().asDiagonal()), p.centroid.cast<L>()));
  const UniformGravity gravity(p.gravity);
  const SpringDamper spring(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                            {.stiffness = p.stiffness, .damping = p.damping, .rest_length = 0.0});
  const Vector4<L> p0 = P::from_rotation(Matrix3<L>(p.r0.cast<L>()));
  Coords q, qd;
  q << p.position0.cast<L>(), p0;
  qd << p.velocity0.cast<L>(), P::thetadot(p0, Vector3<L>(p.omega0.cast<L>()));
  auto f = [&](const L& t, const Coords& x, const Coords& xd) {
    return accelerations(body, t, x, xd, gravity, spring);
  };
  std::vector<Sample> out(p.times.size());
  L t = 0;
  for (std::size_t k = 0; k < p.times.size(); ++k) {
    const L h = (L(p.times[k]) - t) / L(substeps);
    for (int i = 0; i < substeps; ++i) {
      const Coords a1 = f(t, q, qd);
      const Coords v1 = qd;
      const Coords a2 = f(t + h / 2, q + h / 2 * v1, qd + h / 2 * a1);
      const Coords v2 = qd + h / 2 * a1;
      const Coords a3 = f(t + h / 2, q + h / 2 * v2, qd + h / 2 * a2);
      const Coords v3 = qd + h / 2 * a2;
      const Coords a4 = f(t + h, q + h * v3, qd + h * a3);
      const Coords v4 = qd + h * a3;
      q += h / 6 * (v1 + L(2) * v2 + L(2) * v3 + v4);
      qd += h / 6 * (a1 + L(2) * a2 + L(2) * a3 + a4);
      t += h;
      // Projection onto |p| = 1, p.pdot = 0 (as CVODE's projection in the scene).
      const Vector4<L> pn = q.template tail<4>().normalized();
      q.template tail<4>() = pn;
      qd.template tail<4>() -= pn.dot(qd.template tail<4>()) * pn;
    }
    t = L(p.times[k]);
    const Vector4<L> pk = q.template tail<4>();
    const Matrix3<L> r = P::rotation(pk);
    const Vector3<L> w = P::G(pk) * qd.template tail<4>();
    out[k].rotation = r.cast<double>();
    out[k].omega = w.cast<double>();
    out[k].position = q.template head<3>().cast<double>();
    out[k].velocity = qd.template head<3>().cast<double>();
  }
  return out;
}

}  // namespace

std::vector<Sample> stiff_top_reference(const Problem& p, int substeps, double& uncertainty) {
  std::vector<Sample> fine = stiff_top_rk4(p, substeps);
  const std::vector<Sample> coarse = stiff_top_rk4(p, std::max(1, substeps / 2));
  uncertainty = 0;
  for (std::size_t k = 0; k < fine.size(); ++k) {
    uncertainty = std::max(uncertainty, geodesic_angle(fine[k].rotation, coarse[k].rotation));
  }
  uncertainty /= 15.0;  // err(h) = (x_2h - x_h) / (2^4 - 1)
  return fine;
}

std::vector<Problem> make_problems(int output_count, bool full) {
  auto times = [output_count](double t_end) {
    std::vector<double> t(static_cast<std::size_t>(output_count));
    for (int k = 0; k < output_count; ++k) {
      t[static_cast<std::size_t>(k)] = t_end * (k + 1) / output_count;
    }
    t.back() = t_end;
    return t;
  };
  std::vector<Problem> list;

  Problem tumbling;
  tumbling.kind = ProblemKind::tumbling;
  tumbling.id = "tumbling";
  tumbling.title =
      "torque-free asymmetric body, I = diag(1, 2, 3), omega0 = (0.1, 2, 0.05) rad/s, T = 50 s";
  tumbling.t_end = 50.0;
  tumbling.inertia = {1.0, 2.0, 3.0};
  tumbling.omega0 = {0.1, 2.0, 0.05};
  list.push_back(tumbling);

  // Stable spins about the two stable principal axes, with a small wobble.
  Problem minor = tumbling;
  minor.kind = ProblemKind::minor_axis;
  minor.id = "minor_axis";
  minor.title =
      "spin near the minor axis, I = diag(1, 2, 3), omega0 = (2, 0.1, 0.05) rad/s, T = 50 s";
  minor.omega0 = {2.0, 0.1, 0.05};
  list.push_back(minor);

  Problem major = tumbling;
  major.kind = ProblemKind::major_axis;
  major.id = "major_axis";
  major.title =
      "spin near the major axis, I = diag(1, 2, 3), omega0 = (0.05, 0.1, 2) rad/s, T = 50 s";
  major.omega0 = {0.05, 0.1, 2.0};
  list.push_back(major);

  // 200 rad/s for 50 s is 1600 turns: tumble's runs at tight tolerances take seconds each
  // (3.4e6 BDF steps for ZXZ at tol 1e-13), so the quick run integrates 2 s (64 turns, the
  // spinner's length before 2026-11-25) with every other tolerance; --full integrates the 50 s
  // with all of them.
  Problem spinner = tumbling;
  spinner.kind = ProblemKind::spinner;
  spinner.id = "spinner";
  spinner.t_end = full ? 50.0 : 2.0;
  spinner.title = "fast spin about the minor axis, I = diag(1, 2, 3), omega0 = (200, 0.5, 0.3) "
                  "rad/s, T = " +
                  std::string(full ? "50" : "2") + " s";
  spinner.omega0 = {200.0, 0.5, 0.3};
  spinner.quick_stride = 2;
  list.push_back(spinner);

  Problem thrown;
  thrown.kind = ProblemKind::gravity_offset;
  thrown.id = "gravity_offset";
  thrown.title = "body framed 0.62 m off its centroid, thrown under gravity, T = 5 s";
  thrown.t_end = 5.0;
  thrown.mass = 2.0;
  thrown.inertia = {1.0, 2.0, 3.0};
  thrown.centroid = {0.3, -0.2, 0.5};
  thrown.at_centroid = false;
  thrown.r0 = Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  thrown.omega0 = {0.5, 2.0, -1.0};
  thrown.position0 = {0.0, 0.0, 10.0};
  thrown.velocity0 = {3.0, 1.0, 15.0};
  thrown.gravity = {0.0, 0.0, -9.81};
  list.push_back(thrown);

  // The heavy top of examples/heavy_top.cpp with k/m = 1e6 s^-2 and a damping ratio of 0.05.
  Problem top;
  top.kind = ProblemKind::stiff_top;
  top.id = "stiff_top";
  top.title =
      "spinning top (150 rad/s) on a stiff spring-damper at its tip, k/m = 1e6 s^-2, T = 1 s";
  top.t_end = 1.0;
  top.mass = 0.5;
  top.inertia = {1.5e-3, 1.5e-3, 1.0e-3};
  top.centroid = {0.0, 0.0, 0.05};
  top.at_centroid = false;
  top.r0 = Eigen::AngleAxisd(0.35, Eigen::Vector3d::UnitX()).toRotationMatrix();
  top.omega0 = {0.0, 0.0, 150.0};
  top.gravity = {0.0, 0.0, -9.81};
  top.stiffness = 5.0e5;
  top.damping = 50.0;  // c / (2 sqrt(k m)) = 0.05
  top.exact = false;
  list.push_back(top);

  // The same top on an overdamped spring-damper (damping ratio 20): the tip's fast mode decays
  // at c/m = 4e4 s^-1 and bounds an explicit method's step (about 2.8 / 4e4 = 70 us for RK
  // methods of order 4-8) while the solution stays smooth, which BDF is for. The stiff_top
  // above (damping ratio 0.05) oscillates at 1000 rad/s: accuracy, not stability, sets the
  // step there.
  Problem damped = top;
  damped.id = "stiff_top_damped";
  // Adams and the explicit methods take about 1e5 stability-bound steps per second of it: the
  // quick run integrates 0.1 s (15 rad of spin), --full the whole second.
  damped.t_end = full ? 1.0 : 0.1;
  damped.title = "the same top on an overdamped spring-damper at its tip, k/m = 1e6 s^-2, "
                 "c/m = 4e4 s^-1, T = " +
                 std::string(full ? "1" : "0.1") + " s";
  damped.damping = 2.0e4;  // c / (2 sqrt(k m)) = 20
  damped.quick_stride = 2;
  list.push_back(damped);

  for (Problem& p : list) {
    p.times = times(p.t_end);
    if (p.exact) {
      try {
        p.reference = exact_samples(p);
        p.reference_note = p.kind == ProblemKind::gravity_offset
                               ? "exact: TorqueFreeBody (elliptic functions, long double) for "
                                 "the attitude, the parabola for the centroid"
                               : "exact: TorqueFreeBody (elliptic functions, long double)";
      } catch (const std::exception& e) {
        // E.g. under valgrind, whose long double is a double: the runs are still timed (for
        // profiles), their errors are not measured.
        p.reference.clear();
        p.reference_note = std::string("UNAVAILABLE (") + e.what() + "): errors not measured";
      }
    }
  }
  return list;
}

}  // namespace tumble::bench
