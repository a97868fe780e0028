// tumble_bench: the sweep. Which runs the work-precision study makes (every problem x method x
// setting), how one is made and measured, the stiff top's reference integration, and the sizes
// of the scaling, ensemble and mechanism studies.
//
// The methods are the entries of the list in work_precision/methods.cpp (tumble per
// parameterization, the hand-written floors, the peers, RK4). Adaptive methods sweep
// rtol = atol over kTolerances with each of their schemes; RK4 sweeps its step size.

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "common/format.hpp"
#include "main/driver.hpp"

namespace tumble::bench {

const std::vector<double> kTolerances = {1e-3, 1e-4,  1e-5,  1e-6,  1e-7, 1e-8,
                                         1e-9, 1e-10, 1e-11, 1e-12, 1e-13};

Timing sweep_timing(const Options& o) {
  return Timing{.reps = o.reps,
                .base = o.clock,
                .slow_run = 1.0,
                .min_total = 0.01,
                .max_reps = 200,
                .rounds = std::min(o.reps, 3)};
}

std::string Job::method() const {
  const std::string prefix = method_entry->family == "tumble" ? "tumble " : "";
  return prefix + method_entry->label + " " + scheme_name(scheme);
}

std::string Job::setting() const {
  if (fixed_step()) {
    const double dt = problem->times.front();
    return "h=" + sci(dt / substeps);
  }
  return "tol=" + sci(tol);
}

namespace {

/// The RK4 step counts per output interval for problem p: powers of two from 1 until the step
/// times the largest rate |omega0| is below 1e-3 rad (where RK4's error is near the round-off
/// floor on these problems).
std::vector<int> rk4_substeps(const Problem& p) {
  const double dt = p.times.front();
  const double rate = p.omega0.norm();
  std::vector<int> list;
  for (int s = 1; s <= (1 << 16); s *= 2) {
    list.push_back(s);
    if (dt / s * rate < 1e-3) {
      break;
    }
  }
  return list;
}

}  // namespace

std::vector<Method> methods(const Options& o) {
  std::vector<Method> list = all_methods();
  std::erase_if(list, [&](const Method& m) { return !o.full && !m.quick; });
  return list;
}

std::vector<Job> plan_jobs(const Options& o, const std::vector<Problem>& problems,
                           const std::vector<Method>& methods) {
  const std::vector<double>& tolerances = o.tolerances.empty() ? kTolerances : o.tolerances;
  std::vector<Job> jobs;
  for (const Problem& p : problems) {
    for (const Method& m : methods) {
      if (m.applies != nullptr && !m.applies(p)) {
        continue;
      }
      std::vector<double> ladder;
      const int stride = o.full || !o.tolerances.empty() ? 1 : p.quick_stride * m.quick_stride;
      for (std::size_t k = 0; k < tolerances.size(); k += static_cast<std::size_t>(stride)) {
        ladder.push_back(tolerances[k]);
      }
      for (Scheme s : m.schemes) {
        if (s == Scheme::rk4) {
          for (int sub : rk4_substeps(p)) {
            jobs.push_back({&p, &m, s, 0, sub});
          }
          continue;
        }
        for (double tol : ladder) {
          jobs.push_back({&p, &m, s, tol, 0});
        }
      }
    }
  }
  std::erase_if(jobs, [&](const Job& j) { return !method_chosen(o.methods, j.method()); });
  return jobs;
}

namespace {

/// What the method of job j is asked for, with the options that apply to every method.
MethodSetting setting_of(const Job& j, const Options& o) {
  return MethodSetting{.scheme = j.scheme,
                       .tol = j.tol,
                       .substeps = j.substeps,
                       .exact_jacobian = o.exact_jacobian,
                       .fused = o.fused_ops};
}

}  // namespace

Row run_job(const Job& j, const Options& o, const Timing& timing) {
  const Problem& p = *j.problem;
  Row r{j, {}, {}};
  r.run = j.method_entry->run(p, setting_of(j, o), timing);
  r.errors = evaluate(p, r.run);
  r.run.samples.clear();
  r.run.samples.shrink_to_fit();
  return r;
}

void retime_job(Row& r, const Options& o, const Timing& timing) {
  if (!r.run.ok || r.run.seconds > timing.slow_run) {
    return;  // a failed run is not timed; a slow one is far above the noise a round averages out
  }
  const Run again = r.job.method_entry->run(*r.job.problem, setting_of(r.job, o), timing.round());
  if (again.ok) {  // the same deterministic run: its counters and samples are those of round 1
    merge_timing(r.run, again);
  }
}

/// The stiff top has no closed form. Its reference integrates tumble's equations of the same
/// body and loads in long double with fixed-step RK4 (h = 5 us, 200,000 steps over 1 s: far
/// below both the spring's period, 6.3 ms, and the spin's, 42 ms), independent of CVODE and of
/// double rounding; its own error is estimated by Richardson's rule against h = 10 us.
/// (A CVODE run at rtol 1e-14 is no reference here: BDF and Adams at 1e-14 differ by 1e-9 rad.)
void make_stiff_reference(Problem& p) {
  constexpr double step = 5e-6;
  const int substeps = std::max(1, static_cast<int>(std::lround(p.times.front() / step)));
  p.reference = stiff_top_reference(p, substeps, p.reference_uncertainty);
  p.reference_note = "long-double RK4 (tumble's equations, h = " + sci(p.times.front() / substeps) +
                     " s), error estimate " + sci(p.reference_uncertainty) + " rad";
}

MechanismPlan mechanism_plan(const Options& o) {
  MechanismPlan plan;
  plan.tolerances = o.tolerances.empty() ? mechanism_tolerances(o.full) : o.tolerances;
  plan.filter = o.methods;
  for (const MechanismMethod m :
       {MechanismMethod::front_door, MechanismMethod::odeint_f78, MechanismMethod::cvode_bdf}) {
    if (method_chosen(o.methods, mechanism_method_label(m))) {
      plan.methods.push_back(m);
    }
  }
  // Best of --reps, but a single run once one takes 0.1 s (far above the clock's resolution):
  // the tight tolerances of BDF are long, and the study should add seconds, not minutes.
  plan.timing = Timing{.reps = o.reps, .base = o.clock, .slow_run = 0.1};
  return plan;
}

ScalingPlan scaling_plan(const Options& o) {
  ScalingPlan plan;
  if (o.full) {
    plan.rhs_sizes = {1, 3, 10, 30, 100, 300, 1000, 3000, 10000};
    plan.bdf_sizes = {1, 3, 10, 30, 100, 300, 1000, 3000, 10000};
    plan.dense_limit = 200;
    plan.bdf_sizes.insert(std::lower_bound(plan.bdf_sizes.begin(), plan.bdf_sizes.end(), 200), 200);
  } else {
    plan.rhs_sizes = {1, 3, 10, 30, 100, 300, 1000};
    plan.bdf_sizes = {1, 3, 10, 30, 100, 300, 1000};
    plan.dense_limit = 100;
  }
  plan.reps = o.reps;
  plan.base = o.clock;
  return plan;
}

EnsemblePlan ensemble_plan(const Options& o) {
  EnsemblePlan plan;
  // Quick: 2,000 runs per timed ensemble (about 0.3 s per repetition on one thread) and the
  // 10^5-run ensemble timed if it fits in 30 s; --full: 10,000 runs, and up to 120 s for it.
  plan.runs = o.full ? 10000 : 2000;
  plan.large_budget = o.full ? 120.0 : 30.0;
  plan.reps = o.reps;
  plan.mpi = o.mpi;
  return plan;
}

}  // namespace tumble::bench
