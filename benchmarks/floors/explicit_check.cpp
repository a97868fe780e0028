// tumble_explicit_check: tumble's explicit path against its Fehlberg 7(8) floor measured a second
// way, outside the main job's harness, in one translation unit as a user's program with one scene
// type is compiled. The torque-free body I = diag(1, 2, 3) kg m^2 held at its centroid (Euler
// parameters, [q; v; omega]: 7 states), integrated over 200 output times by
//   tumble   OdeintIntegrator<SceneT, 7>, Fehlberg 7(8), rtol = atol = tol, reading the rotation
//            and omega of the body at each output (tumble::rotation, tumble::omega);
//   floor    Odeint's controlled runge_kutta_fehlberg78 on the hand-written [p; omega] right-hand
//            side of the main job's floors (floors/rhs.hpp) in a plain loop of try_step that
//            lands on each output time, normalizing p and forming R at each output.
// The floor starts with the first step tumble's integrator chose (so both take the same steps;
// it is spared the estimate, one evaluation). The two alternate, `rounds` times each, and the
// best time of each is kept (std::chrono::steady_clock); steps, right-hand sides and the final
// attitudes' difference are printed to show that both did the same work.
//
//   tumble_explicit_check [rounds=200]
//
// Two problems of the main job (work_precision/problems.cpp): the tumbling body (omega0 = (0.1, 2,
// 0.05) rad/s, 50 s) and the spinner (omega0 = (200, 0.5, 0.3) rad/s, 2 s), at tol 1e-6 and 1e-9.

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

// GCC 12 -O3 reports Odeint's copy of a freshly built stepper as -Wmaybe-uninitialized inside the
// Boost headers (floors/odeint.cpp says more): silenced for this file only.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <boost/numeric/odeint.hpp>

#include "floors/rhs.hpp"
#include "tumble/integrate/explicit_integrator.hpp"
#include "tumble/tumble.hpp"

namespace {

using namespace tumble;
namespace odeint = boost::numeric::odeint;
using Body = RigidBody<EulerParameters, ReferencePoint::fixed_point>;
using SceneT = Scene<Bodies<Body>, Loads<>, StateForm::quasi_velocities>;
using State = std::array<double, 7>;

struct Case {
  std::string name;
  Eigen::Vector3d omega0;
  double t_end = 0;
  double tol = 0;
};

/// What both record at an output.
struct Out {
  Eigen::Matrix3d rotation;
  Eigen::Vector3d omega;
};

struct Result {
  double best_s = 1e300;
  long steps = 0, rhs = 0;
  Eigen::Matrix3d last;
};

bench::Problem problem_of(const Case& c) {
  bench::Problem p;
  p.inertia = {1.0, 2.0, 3.0};
  p.omega0 = c.omega0;
  p.at_centroid = true;
  return p;
}

void run_tumble(const SceneT& scene, BodyId<Body> id, const OdeintOptions& o,
                const std::vector<double>& times, std::vector<Out>& out, Result& r) {
  const auto start = std::chrono::steady_clock::now();
  OdeintIntegrator<SceneT, 7> integrator(scene, 0.0, o);
  std::size_t k = 0;
  integrator.integrate(times, [&](double, const SceneState& y) {
    out[k].rotation = tumble::rotation(scene, id, y);
    out[k].omega = tumble::omega(scene, id, y);
    ++k;
  });
  const auto end = std::chrono::steady_clock::now();
  r.best_s = std::min(r.best_s, std::chrono::duration<double>(end - start).count());
  r.steps = integrator.statistics().steps;
  r.rhs = integrator.statistics().rhs_evals;
  r.last = out.back().rotation;
}

void run_floor(const bench::FloorRhs<7>& f, const State& x0, double h0, double tol,
               const std::vector<double>& times, std::vector<Out>& out, Result& r) {
  const auto start = std::chrono::steady_clock::now();
  f.evals = 0;
  const auto counted = [&f](const State& x, State& xd, double /*t*/) { f(x.data(), xd.data()); };
  auto stepper = odeint::make_controlled(tol, tol, odeint::runge_kutta_fehlberg78<State>());
  State x = x0, dxdt{}, trial{};
  counted(x, dxdt, 0.0);
  double t = 0, dt = h0;
  long steps = 0;
  for (std::size_t k = 0; k < times.size(); ++k) {
    const double t_out = times[k];
    while (t < t_out) {
      const bool last = dt >= t_out - t;  // the step ends on the output time
      double t_try = t, h = last ? t_out - t : dt;
      if (stepper.try_step(counted, x, dxdt, t_try, trial, h) == odeint::success) {
        ++steps;
        x = trial;
        t = last ? t_out : t_try;
        counted(x, dxdt, t);
        dt = std::max(dt, h);
      } else {
        dt = h;
      }
    }
    Eigen::Vector4d q(x[0], x[1], x[2], x[3]);
    q.normalize();
    out[k].rotation = Eigen::Quaterniond(q(0), q(1), q(2), q(3)).toRotationMatrix();
    out[k].omega = Eigen::Vector3d(x[4], x[5], x[6]);
  }
  const auto end = std::chrono::steady_clock::now();
  r.best_s = std::min(r.best_s, std::chrono::duration<double>(end - start).count());
  r.steps = steps;
  r.rhs = f.evals;
  r.last = out.back().rotation;
}

}  // namespace

int main(int argc, char** argv) {
  const int rounds = argc > 1 ? std::atoi(argv[1]) : 200;
  if (rounds < 1) {
    std::fprintf(stderr, "tumble_explicit_check: rounds must be at least 1\n");
    return 2;
  }
  const std::vector<Case> cases = {{"tumbling", {0.1, 2.0, 0.05}, 50.0, 1e-6},
                                   {"tumbling", {0.1, 2.0, 0.05}, 50.0, 1e-9},
                                   {"spinner", {200.0, 0.5, 0.3}, 2.0, 1e-6},
                                   {"spinner", {200.0, 0.5, 0.3}, 2.0, 1e-9}};
  std::printf("%-9s %6s %10s %10s %7s %7s %7s %9s\n", "problem", "tol", "tumble us", "floor us",
              "ratio", "steps", "rhs", "|dR|");
  for (const Case& c : cases) {
    std::vector<double> times;
    for (int i = 1; i <= 200; ++i) {
      times.push_back(c.t_end * i / 200.0);
    }
    SceneT scene;
    const BodyId<Body> id =
        scene.add(Body(MassProperties<>::about_centroid(1.0, Eigen::Vector3d(1, 2, 3).asDiagonal()),
                       Eigen::Vector3d::Zero()),
                  {.omega = c.omega0});
    OdeintOptions o;
    o.rtol = c.tol;
    o.atol = c.tol;
    const double h0 = OdeintIntegrator<SceneT, 7>(scene, 0.0, o).step_size();
    const bench::Problem p = problem_of(c);
    const bench::FloorRhs<7> f(p);
    const State x0 = f.initial(p);
    std::vector<Out> out_tumble(times.size()), out_floor(times.size());
    Result rt, rf;
    for (int r = 0; r < rounds; ++r) {
      run_tumble(scene, id, o, times, out_tumble, rt);
      run_floor(f, x0, h0, c.tol, times, out_floor, rf);
    }
    std::printf("%-9s %6.0e %10.1f %10.1f %7.3f %3ld/%-3ld %3ld/%-4ld %9.1e\n", c.name.c_str(),
                c.tol, rt.best_s * 1e6, rf.best_s * 1e6, rt.best_s / rf.best_s, rt.steps, rf.steps,
                rt.rhs, rf.rhs, (rt.last - rf.last).cwiseAbs().maxCoeff());
  }
  std::printf("(best of %d alternating runs each; steps and rhs: tumble/floor; |dR|: the largest "
              "difference of the final attitudes' entries)\n",
              rounds);
  return 0;
}
