// tumble_bench: the list of methods the work-precision sweep runs, in the order of the report.
// One entry per method (common/bench.hpp, Method): a row label, a family (the CSV's and the
// plot's grouping), the schemes it is run with (one curve each), whether the quick run has it,
// the problems it applies to, and the function that runs it. To add a configuration of tumble (a
// state form of the scene, another integrator on a tumble scene), add one entry here (or in
// add_tumble_methods_a/b/c/d: tumble's parameterizations, state forms and integrators); the
// sweep, the report, the CSV and the plots take it from this list.

#include <vector>

#include "common/bench.hpp"

namespace tumble::bench {

std::vector<Method> all_methods() {
  std::vector<Method> list;
  // tumble on [q; qdot], CVODE Adams and BDF, one entry per parameterization
  add_tumble_methods_a(list);
  add_tumble_methods_b(list);
  // tumble on [q; v; omega] (the quasi-velocity state form), CVODE Adams and BDF
  add_tumble_methods_c(list);
#ifdef TUMBLE_BENCH_HAVE_TUMBLE_ODEINT
  // tumble's scenes under OdeintIntegrator: Fehlberg 7(8), Dormand-Prince 5(4), both state forms
  add_tumble_methods_d(list);
#endif

  // The floors: the same problems written by hand. The first one integrates tumble's own state
  // form (the cost of tumble's scene above CVODE); the others the first-order [p; omega] form.
  list.push_back({.label = "floor CVODE [q; qd] EP",
                  .family = "floor",
                  .schemes = {Scheme::adams, Scheme::bdf},
                  .applies = &closed_form_problem,
                  .run = &run_handwritten});
  list.push_back({.label = "floor CVODE [p; w]",
                  .family = "floor",
                  .schemes = {Scheme::adams, Scheme::bdf},
                  .run = &run_floor_cvode});
  list.push_back({.label = "floor ARKODE F78 [p; w]",
                  .family = "floor",
                  .schemes = {Scheme::erk78},
                  .run = &run_floor_arkode_f78});
  list.push_back({.label = "floor Odeint RKF78 [p; w]",
                  .family = "floor",
                  .schemes = {Scheme::rkf78},
                  .run = &run_floor_odeint_rkf78});
  list.push_back({.label = "floor Odeint RKF78 loop",
                  .family = "floor",
                  .schemes = {Scheme::rkf78},
                  .run = &run_floor_odeint_rkf78_loop});
  list.push_back({.label = "floor Odeint DP5 [p; w]",
                  .family = "floor",
                  .schemes = {Scheme::dopri5},
                  .run = &run_floor_odeint_dopri5});

  // Peers and fixed-step references
  if (pinocchio_available()) {
    list.push_back({.label = "Pinocchio aba",
                    .family = "peer",
                    .schemes = {Scheme::adams, Scheme::bdf},
                    .applies = &closed_form_problem,
                    .run = &run_pinocchio});
  }
  if (mujoco_available()) {
    list.push_back({.label = "MuJoCo RK4",
                    .family = "peer",
                    .schemes = {Scheme::rk4},
                    .applies = &closed_form_problem,
                    .run = &run_mujoco});
  }
  list.push_back({.label = "RK4 fixed step (EP)",
                  .family = "rk4",
                  .schemes = {Scheme::rk4},
                  .applies = &closed_form_problem,
                  .run = &run_rk4});
  return list;
}

}  // namespace tumble::bench
