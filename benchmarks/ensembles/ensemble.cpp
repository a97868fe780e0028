// tumble_bench: the ensemble study (d). Many runs of one scene, the tumbling body of
// ensembles/runs.hpp (50 s per run, MRP in the quasi-velocity form, OdeintIntegrator
// with Fehlberg 7(8)), at the loosest tolerance whose attitude error at 50 s is within the plan's
// target (1e-6 rad) on the nominal run and on a sample of dispersed runs, each against its exact
// torque-free solution (tests/support/torque_free.hpp). Measured, on the wall clock (a thread's
// CPU clock cannot time several threads), each the median of plan.reps repetitions:
//  - runs per second of Ensemble::integrate with 1 and 2 threads (EnsembleOptions::threads, the
//    default grain of 1 run per task), plan.calls calls in a row each, every call's time kept
//    (a slow call must show, not hide behind a median): on one Ensemble (its integrators kept
//    from call to call) and, on 2 threads, on a new Ensemble per call (new integrators each
//    call, the memory of the last call's freed by the calling thread);
//  - the per-run cost of the 1-thread ensemble against two serial loops of the same runs with the
//    same observer: one integrator made once and reset for each run (what the ensemble does in
//    each thread), and a new integrator per run;
//  - the same runs over 1 and 2 MPI processes: tumble_bench_mpi (ensembles/mpi.cpp)
//    under mpiexec (main/tools.cpp), one thread per rank, its output parsed, its results
//    compared bitwise (their sum in run order) with the threads';
//  - the large ensemble (10^5 runs) with Ensemble::fold on 2 threads, timed once, or, when the
//    2-thread rate says it would take longer than the plan's budget, extrapolated from that rate
//    and labelled so;
//  - memory: the bytes Ensemble::integrate keeps per run, and the growth of the peak resident
//    set (VmHWM, reset through /proc/self/clear_refs) during folds of N and 10 N runs;
//  - operator new calls per run for runs of 5 s and of 50 s (ten times the steps): equal counts
//    mean nothing is allocated per step.
// Beside each time, the process's CPU time (all its threads; MPI: all ranks) over the wall time,
// the cores the measurement had: on a busy machine a 2-thread run may get one core, and its
// speed-up then measures the machine (the report says so); and the CPU time per run, which
// waiting for a core does not inflate.

#include "tumble/ensemble/ensemble.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <time.h>

#include "common/format.hpp"
#include "ensembles/runs.hpp"
#include "main/driver.hpp"
#include "support/torque_free.hpp"

namespace tumble::bench {
namespace {

using ensemble::KeepAngle;
using ensemble::kEnd;
using ensemble::MakeIntegrator;
using ensemble::Tumbling;
using Integrator = OdeintIntegrator<ensemble::TumblingScene, ensemble::kStates>;

/// One run from body rates w to kEnd: its attitude error (rad) against the exact solution.
double run_error(const Tumbling& t, const OdeintOptions& o, const Eigen::Vector3d& w,
                 OdeintStatistics* stats = nullptr) {
  Integrator integrator(t.scene, 0.0, t.state_with(w), o);
  integrator.advance(kEnd);
  const Eigen::Matrix3d r = rotation(t.scene, t.body, integrator.state());
  if (stats != nullptr) {
    *stats = integrator.statistics();
  }
  const test::TorqueFreeBody exact(ensemble::kInertia, w);
  return geodesic_angle(exact.rotation(kEnd), r);
}

/// The loosest tolerance of 1e-3, 10^-3.5, ..., 1e-12 at which the nominal run and the sample of
/// dispersed runs all end within plan.target_error of their exact attitude.
void choose_tolerance(const Tumbling& t, const EnsemblePlan& plan, EnsembleResult& r) {
  for (int k = 0; k <= 18; ++k) {
    const double tol = 1e-3 * std::pow(10.0, -0.5 * k);
    try {
      const OdeintOptions o = ensemble::odeint_options(tol);
      OdeintStatistics st;
      const double nominal = run_error(t, o, ensemble::kOmega, &st);
      double sample = 0;
      for (int i = 0; i < plan.error_sample; ++i) {
        sample = std::max(sample, run_error(t, o, Tumbling::omega0(static_cast<std::size_t>(i))));
      }
      r.tol = tol;
      r.nominal_error = nominal;
      r.sample_error = sample;
      r.nominal_steps = st.steps;
      r.nominal_rhs = st.rhs_evals;
      if (std::max(nominal, sample) <= plan.target_error) {
        return;
      }
    } catch (const std::exception&) {
      // too loose to integrate at all: try the next
    }
  }
}

/// The sum of the runs' values in run order; throws naming the first failed run.
double checked_sum(const std::vector<RunOutcome<double>>& out) {
  const std::vector<RunError> failed = failures(out);
  if (!failed.empty()) {
    throw std::runtime_error(std::to_string(failed.size()) + " runs failed, run " +
                             std::to_string(failed.front().run) + ": " + failed.front().message);
  }
  return fold_runs(out, 0.0, [](double a, std::size_t, double v) { return a + v; });
}

/// The CPU time of this process, all its threads, s.
double process_cpu() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

/// The row's times from the wall times s of its repetitions (not empty) and their CPU time:
/// median, best, reps, cores (CPU over wall) and CPU per run.
void summarize_times(EnsembleRow& row, std::vector<double> s, double cpu) {
  double wall = 0;
  for (const double x : s) {
    wall += x;
  }
  row.cores = cpu / wall;
  row.cpu_per_run = cpu / static_cast<double>(s.size() * row.runs);
  std::sort(s.begin(), s.end());
  const std::size_t n = s.size();
  row.reps = static_cast<int>(n);
  row.seconds = n % 2 == 1 ? s[n / 2] : 0.5 * (s[n / 2 - 1] + s[n / 2]);
  row.best = s.front();
}

/// Times body() `reps` times on the wall clock into the row (median, best); a throw marks the
/// row failed.
template <class Body> void time_reps(EnsembleRow& row, int reps, Body&& body) {
  std::vector<double> s;
  double cpu = 0;
  try {
    for (int k = 0; k < reps; ++k) {
      const double cpu0 = process_cpu();
      const Stopwatch watch;
      body();
      s.push_back(watch.wall());
      cpu += process_cpu() - cpu0;
    }
  } catch (const std::exception& e) {
    row.ok = false;
    row.note = e.what();
  }
  row.reps = static_cast<int>(s.size());
  if (s.empty()) {
    row.ok = false;
    return;
  }
  row.calls = s;
  summarize_times(row, std::move(s), cpu);
}

/// A field of /proc/self/status in kB ("VmRSS", "VmHWM"); -1 where there is none.
long status_kb(const std::string& field) {
  std::ifstream f("/proc/self/status");
  for (std::string line; std::getline(f, line);) {
    if (line.rfind(field + ":", 0) == 0) {
      try {
        return std::stol(line.substr(field.size() + 1));
      } catch (const std::exception&) {
        return -1;
      }
    }
  }
  return -1;
}

/// Resets the peak resident set (VmHWM) to the current one (Linux: "5" into clear_refs).
bool reset_peak() {
  std::ofstream f("/proc/self/clear_refs");
  f << "5";
  f.flush();
  return f.good();
}

/// A row of the table, not yet timed.
EnsembleRow make_row(std::string what, std::string label, int threads, int ranks,
                     std::size_t runs) {
  EnsembleRow row;
  row.what = std::move(what);
  row.label = std::move(label);
  row.threads = threads;
  row.ranks = ranks;
  row.runs = runs;
  return row;
}

/// What the study shares between its measurements: the scene, the runs' inputs, the factory.
struct Study {
  const EnsemblePlan& plan;
  EnsembleResult& result;
  const std::function<void()>& step;
  Tumbling t;
  MakeIntegrator make;
  std::vector<double> times{kEnd};
  double reference_sum = 0;  ///< the 1-thread ensemble's sum of the values, in run order

  Study(const EnsemblePlan& p, EnsembleResult& r, const std::function<void()>& s)
      : plan(p), result(r), step(s) {
    choose_tolerance(t, plan, result);
    make.options = ensemble::odeint_options(result.tol);
    step();
  }

  [[nodiscard]] SceneState initial(std::size_t i) const { return t.initial(i); }
  [[nodiscard]] KeepAngle keep() const { return KeepAngle{&t}; }

  EnsembleRow& add(EnsembleRow row) {
    result.rows.push_back(std::move(row));
    step();
    return result.rows.back();
  }

  /// plan.calls calls in a row of Ensemble::integrate of plan.runs runs on `threads` threads:
  /// of one Ensemble, or (fresh) of a new Ensemble each call.
  void threads(int n, bool fresh) {
    EnsembleRow row =
        make_row(fresh ? "threads-new" : "threads",
                 "Ensemble::integrate, " + std::to_string(n) + (n == 1 ? " thread" : " threads") +
                     (fresh ? ", new ensembles" : ""),
                 n, 1, plan.runs);
    const Ensemble e(t.scene, make, {.threads = n});
    const auto start = [this](std::size_t i) { return initial(i); };
    double sum = 0;
    time_reps(row, plan.calls, [&] {
      if (fresh) {
        const Ensemble f(t.scene, make, {.threads = n});
        sum = checked_sum(f.integrate<double>(plan.runs, start, 0.0, times, keep()));
      } else {
        sum = checked_sum(e.integrate<double>(plan.runs, start, 0.0, times, keep()));
      }
    });
    if (n == 1) {
      reference_sum = sum;
    } else if (row.ok && sum != reference_sum) {
      row.note = "results differ from 1 thread's";
    }
    add(std::move(row));
  }

  /// The process's first parallel call, before any timed row: oneTBB starts its worker threads
  /// in it; timed apart, so that no row's first call carries it (docs/benchmarks/ensembles.md).
  void start_threads() {
    const Ensemble e(t.scene, make, {.threads = 2});
    const auto start = [this](std::size_t i) { return initial(i); };
    result.startup_runs = 64;
    for (double* s : {&result.startup_first, &result.startup_again}) {
      const Stopwatch watch;
      checked_sum(e.integrate<double>(result.startup_runs, start, 0.0, times, keep()));
      *s = watch.wall();
    }
  }

  /// A serial loop of the same runs: one integrator reset per run, or a new one per run.
  void serial(bool reuse) {
    EnsembleRow row = make_row(reuse ? "serial-reset" : "serial-new",
                               reuse ? "serial loop, one integrator reset per run"
                                     : "serial loop, a new integrator per run",
                               1, 1, plan.runs);
    const KeepAngle observe = keep();
    double sum = 0;
    time_reps(row, plan.reps, [&] {
      sum = 0;
      if (reuse) {
        Integrator integrator = make(t.scene, 0.0, initial(0));
        for (std::size_t i = 0; i < plan.runs; ++i) {
          double angle = 0;
          integrator.reset(0.0, initial(i));
          integrator.integrate(times,
                               [&](double tk, const SceneState& s) { observe(angle, i, tk, s); });
          sum += angle;
        }
      } else {
        for (std::size_t i = 0; i < plan.runs; ++i) {
          double angle = 0;
          Integrator integrator = make(t.scene, 0.0, initial(i));
          integrator.integrate(times,
                               [&](double tk, const SceneState& s) { observe(angle, i, tk, s); });
          sum += angle;
        }
      }
    });
    if (row.ok && sum != reference_sum) {
      row.note = "results differ from the ensemble's";
    }
    add(std::move(row));
  }

  /// plan.runs runs over `ranks` MPI processes (tumble_bench_mpi), one thread each.
  void mpi(int ranks, const std::filesystem::path& out) {
    EnsembleRow row = make_row(
        "mpi",
        "MpiEnsemble::integrate, " + std::to_string(ranks) + (ranks == 1 ? " rank" : " ranks"), 1,
        ranks, plan.runs);
    const std::filesystem::path log = out / ("ensemble_mpi_np" + std::to_string(ranks) + ".txt");
    const std::string args = "--runs " + std::to_string(plan.runs) + " --reps " +
                             std::to_string(plan.reps) + " --tol " + fmt("%.17g", result.tol);
    const std::string why = run_ensemble_mpi(ranks, args, log);
    std::vector<double> s;
    double sum = 0, cpu = 0;
    bool have_sum = false;
    std::ifstream f(log);
    for (std::string line; std::getline(f, line);) {
      if (line.rfind("seconds ", 0) == 0) {
        s.push_back(std::strtod(line.c_str() + 8, nullptr));
      } else if (line.rfind("cpu ", 0) == 0) {
        cpu += std::strtod(line.c_str() + 4, nullptr);
      } else if (line.rfind("sum ", 0) == 0) {
        sum = std::strtod(line.c_str() + 4, nullptr);  // a hexadecimal float, exact
        have_sum = true;
      }
    }
    std::erase_if(s, [](double x) { return !(x > 0); });
    if (!why.empty() || s.empty()) {
      row.ok = false;
      row.note = why.empty() ? "no times in " + log.string() : why;
      result.mpi_note = row.note;
    } else {
      summarize_times(row, std::move(s), cpu);
      result.mpi_same = (ranks == 1 || result.mpi_same) && have_sum && sum == reference_sum;
    }
    add(std::move(row));
  }

  /// Ensemble::fold of n runs on 2 threads, timed once, with the growth of the peak RSS.
  void fold(std::size_t n) {
    EnsembleRow row = make_row("fold", "Ensemble::fold, 2 threads", 2, 1, n);
    row.reps = 1;
    const Ensemble e(t.scene, make, {.threads = 2});
    const auto start = [this](std::size_t i) { return initial(i); };
    const bool reset = reset_peak();
    const long before = status_kb("VmRSS");
    try {
      const double cpu0 = process_cpu();
      const Stopwatch watch;
      const FoldedRuns<double> folded = e.fold<double>(
          n, start, 0.0, times, keep(), 0.0, [](double a, std::size_t, double v) { return a + v; });
      row.seconds = row.best = watch.wall();
      const double cpu = process_cpu() - cpu0;
      row.cores = cpu / row.seconds;
      row.cpu_per_run = cpu / static_cast<double>(n);
      if (!folded.errors.empty()) {
        row.ok = false;
        row.note = std::to_string(folded.errors.size()) + " runs failed";
      }
    } catch (const std::exception& x) {
      row.ok = false;
      row.note = x.what();
    }
    const long peak = status_kb("VmHWM");
    result.fold_peaks.push_back({n, reset && before >= 0 && peak >= 0 ? peak - before : -1});
    if (!reset) {
      result.memory_note = "the peak RSS could not be reset (/proc/self/clear_refs)";
    }
    add(std::move(row));
  }

  /// operator new calls of a 1-thread ensemble of n runs to `end`.
  long allocations(std::size_t n, double end) {
    const Ensemble e(t.scene, make, {.threads = 1});
    const std::vector<double> to{end};
    const auto start = [this](std::size_t i) { return initial(i); };
    reset_allocation_count();
    set_allocation_counting(true);
    const auto out = e.integrate<double>(n, start, 0.0, to, keep());
    set_allocation_counting(false);
    checked_sum(out);
    return allocation_count();
  }

  /// Allocations per run at kEnd / 10 and kEnd (the fixed part, the results' vector and the
  /// thread's first integrator, cancels in the difference of n and 2 n runs).
  void heap() {
    constexpr std::size_t n = 32;
    constexpr long runs = static_cast<long>(n);
    try {
      result.allocations_short = (allocations(2 * n, kEnd / 10) - allocations(n, kEnd / 10)) / runs;
      result.allocations_long = (allocations(2 * n, kEnd) - allocations(n, kEnd)) / runs;
      const SceneState s0 = initial(0);
      reset_allocation_count();
      set_allocation_counting(true);
      { const Integrator one = make(t.scene, 0.0, s0); }
      set_allocation_counting(false);
      result.allocations_new = allocation_count();
      for (const double end : {kEnd / 10, kEnd}) {
        Integrator integrator = make(t.scene, 0.0, s0);
        integrator.advance(end);
        (end < kEnd ? result.steps_short : result.steps_long) = integrator.statistics().steps;
      }
    } catch (const std::exception& x) {
      set_allocation_counting(false);
      result.memory_note += (result.memory_note.empty() ? "" : "; ") + std::string(x.what());
    }
    step();
  }
};

}  // namespace

int ensemble_measurements(const EnsemblePlan& plan) {
  return 9 + (plan.mpi && ensemble_mpi_built() ? 2 : 0);
}

EnsembleResult run_ensemble(const EnsemblePlan& plan, const std::filesystem::path& out,
                            const std::function<void()>& step) {
  EnsembleResult result;
  result.result_bytes = sizeof(RunOutcome<double>);
  Study study(plan, result, step);
  study.start_threads();
  study.threads(1, false);
  study.serial(true);
  study.serial(false);
  study.threads(2, false);
  study.threads(2, true);
  if (plan.mpi && ensemble_mpi_built()) {
    study.mpi(1, out);
    study.mpi(2, out);
  } else {
    result.mpi_note = plan.mpi ? "tumble_bench_mpi was not built (no tumble::mpi: MPI not found)"
                               : "not run (--no-mpi)";
  }
  // The large ensemble, timed if the 2-thread rate promises it within the budget; the memory
  // folds are N and 10 N runs, with 10 N the large ensemble when it is timed.
  const auto two = std::find_if(result.rows.begin(), result.rows.end(), [](const EnsembleRow& r) {
    return r.what == "threads" && r.threads == 2;
  });
  const double rate = two != result.rows.end() && two->ok ? two->rate() : 0.0;
  const bool timed = rate > 0 && static_cast<double>(plan.large) / rate <= plan.large_budget;
  const std::size_t small = timed ? plan.large / 10 : plan.runs;
  study.fold(small);
  study.fold(10 * small);
  if (!timed) {
    const EnsembleRow& last = result.rows.back();
    EnsembleRow row =
        make_row("fold", "Ensemble::fold, 2 threads (extrapolated)", 2, 1, plan.large);
    row.extrapolated = true;
    row.ok = last.ok;
    row.note = "from the rate of " + std::to_string(last.runs) + " runs";
    row.seconds = static_cast<double>(plan.large) / last.rate();
    result.rows.push_back(std::move(row));
  }
  study.heap();
  return result;
}

}  // namespace tumble::bench
