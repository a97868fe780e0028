// tumble_explicit_check: tumble's explicit path against its Fehlberg 7(8) floor measured a second
// way, outside the main job's harness (its sweep, rounds and timing), in one translation unit as
// a user's program with one scene type is compiled. The main job's tumbling body and spinner
// (work_precision/problems.cpp, the quick run: 200 outputs), at tol 1e-6 and 1e-9, by
//   tumble   OdeintIntegrator<SceneT, 7>, Fehlberg 7(8), rtol = atol = tol, on the main job's
//            scene (the body held at its centroid, work_precision/tumble_scene.hpp), recording
//            scene_sample at each output;
//   floor    the main job's loop floor (floors/fehlberg_loop.hpp) on the hand-written [p; omega]
//            right-hand side (floors/rhs.hpp), recording FloorRhs::sample at each output.
// The floor starts with the first step tumble's integrator chose (so both take the same steps;
// it is spared the estimate, one evaluation). The two alternate, `rounds` times each, and the
// best time of each is kept (std::chrono::steady_clock); steps, right-hand sides and the final
// attitudes' difference are printed to show that both did the same work.
//
//   tumble_explicit_check [rounds=200]

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

// GCC 12 -O3 reports Odeint's copy of a freshly built stepper as -Wmaybe-uninitialized or
// -Wuninitialized inside the Boost headers (floors/odeint.cpp says more): silenced for this file
// only.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"
#endif
#include <boost/numeric/odeint.hpp>

#include "floors/fehlberg_loop.hpp"
#include "floors/rhs.hpp"
#include "tumble/integrate/explicit_integrator.hpp"
#include "work_precision/tumble_scene.hpp"

namespace {

using namespace tumble;
using namespace tumble::bench;
using Body = RigidBody<EulerParameters, ReferencePoint::fixed_point>;
using SceneT = Scene<Bodies<Body>, Loads<>, StateForm::quasi_velocities>;
using State = std::array<double, 7>;

struct Result {
  double best_s = 1e300;
  long steps = 0, rhs = 0;
};

void keep_best(Result& r, std::chrono::steady_clock::time_point start) {
  const auto end = std::chrono::steady_clock::now();
  r.best_s = std::min(r.best_s, std::chrono::duration<double>(end - start).count());
}

void run_tumble(const Problem& p, const SceneT& scene, BodyId<Body> id, const OdeintOptions& o,
                std::vector<Sample>& out, Result& r) {
  const auto start = std::chrono::steady_clock::now();
  OdeintIntegrator<SceneT, 7> integrator(scene, 0.0, o);
  std::size_t k = 0;
  integrator.integrate(p.times,
                       [&](double, const SceneState& y) { out[k++] = scene_sample(scene, id, y); });
  keep_best(r, start);
  r.steps = integrator.statistics().steps;
  r.rhs = integrator.statistics().rhs_evals;
}

void run_floor(const Problem& p, const FloorRhs<7>& f, double h0, double tol,
               std::vector<Sample>& out, Result& r) {
  const auto start = std::chrono::steady_clock::now();
  f.evals = 0;
  const auto counted = [&f](const State& x, State& xd, double /*t*/) { f(x.data(), xd.data()); };
  State x = f.initial(p), dxdt{};
  counted(x, dxdt, 0.0);
  std::size_t k = 0;
  const std::size_t steps =
      fehlberg78_loop(tol, counted, x, dxdt, h0, p.times,
                      [&](const State& y, double) { out[k++] = f.sample(p, y.data()); });
  keep_best(r, start);
  r.steps = static_cast<long>(steps);
  r.rhs = f.evals;
}

}  // namespace

int main(int argc, char** argv) {
  const int rounds = argc > 1 ? std::atoi(argv[1]) : 200;
  if (rounds < 1) {
    std::fprintf(stderr, "tumble_explicit_check: rounds must be at least 1\n");
    return 2;
  }
  std::printf("%-9s %6s %10s %10s %7s %7s %9s %9s\n", "problem", "tol", "tumble us", "floor us",
              "ratio", "steps", "rhs", "|dR|");
  for (const Problem& p : make_problems(200, false)) {
    if (p.kind != ProblemKind::tumbling && p.kind != ProblemKind::spinner) {
      continue;
    }
    SceneT scene;
    const BodyId<Body> id =
        scene.add(Body(mass_properties(p), p.position0), initial_state(p));  // as the main job
    const FloorRhs<7> f(p);
    for (const double tol : {1e-6, 1e-9}) {
      OdeintOptions o;
      o.rtol = tol;
      o.atol = tol;
      const double h0 = OdeintIntegrator<SceneT, 7>(scene, 0.0, o).step_size();
      std::vector<Sample> out_tumble(p.times.size()), out_floor(p.times.size());
      Result rt, rf;
      for (int r = 0; r < rounds; ++r) {
        run_tumble(p, scene, id, o, out_tumble, rt);
        run_floor(p, f, h0, tol, out_floor, rf);
      }
      const double dr =
          (out_tumble.back().rotation - out_floor.back().rotation).cwiseAbs().maxCoeff();
      std::printf("%-9s %6.0e %10.1f %10.1f %7.3f %3ld/%-3ld %4ld/%-4ld %9.1e\n", p.id.c_str(), tol,
                  rt.best_s * 1e6, rf.best_s * 1e6, rt.best_s / rf.best_s, rt.steps, rf.steps,
                  rt.rhs, rf.rhs, dr);
    }
  }
  std::printf("(best of %d alternating runs each; steps and rhs: tumble/floor; |dR|: the largest "
              "difference of the final attitudes' entries)\n",
              rounds);
  return 0;
}
