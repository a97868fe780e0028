// tumble_bench: the README's main job. What tumble's rigid-body dynamics cost and the accuracy
// they buy, in four parts, each a phase of this file:
//   (a) the per-call cost of the core assembly (tumble_micro's short list, Google Benchmark);
//   (b) work precision: for each problem with a known answer (work_precision/problems.cpp),
//       tumble with every parameterization of the run and CVODE's Adams and BDF, swept over the
//       tolerance, beside the hand-written CVODE floor, fixed-step RK4 and (when installed)
//       Pinocchio's aba in CVODE (work_precision/sweep.cpp);
//   (c) the scaling study, a chain of N bodies (scaling/scaling.cpp);
//   (d) the ensemble study, many runs of the tumbling body across threads and MPI processes
//       (ensembles/ensemble.cpp; built when tumble::ensemble exists,
//       TUMBLE_BENCH_HAVE_ENSEMBLE);
//   (e) mechanisms: work precision of tumble's integrators on the IFToMM problems A01-A05 and an
//       open spatial chain against independent references, beside the peers that are installed
//       (mechanisms/mechanisms.hpp; --no-mechanisms skips it).
// It prints a header, one progress line per phase (stderr), then the tables
// (main/report.cpp) and where the files are: CSVs (main/csv.cpp), PNG
// diagrams and the raw micro-benchmark output (main/tools.cpp). `--help` for options.

#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "common/format.hpp"
#include "main/driver.hpp"

namespace tumble::bench {
namespace {

/// One line per phase on stderr, "[k/n] what: i/N done", rewritten in place on a terminal and
/// written once (with its duration) otherwise.
class Progress {
 public:
  explicit Progress(int phases) : phases_(phases), tty_(isatty(fileno(stderr)) != 0) {}

  void begin(const std::string& what, int steps) {
    ++phase_;
    what_ = what;
    steps_ = steps;
    done_ = 0;
    start_ = Clock::now();
    if (tty_) {
      show();
    } else {
      std::fprintf(stderr, "[%d/%d] %s ...", phase_, phases_, what_.c_str());
      std::fflush(stderr);
    }
  }
  void step() {
    ++done_;
    if (tty_) {
      show();
    }
  }
  void end(const std::string& note = "") {
    const std::string took = fmt("%.0f s", seconds_since(start_));
    if (tty_) {
      std::fprintf(stderr, "\r\033[K[%d/%d] %s: %s%s\n", phase_, phases_, what_.c_str(),
                   took.c_str(), note.c_str());
    } else {
      std::fprintf(stderr, " %s%s\n", took.c_str(), note.c_str());
    }
    std::fflush(stderr);
  }

 private:
  void show() const {
    std::fprintf(stderr, "\r\033[K[%d/%d] %s", phase_, phases_, what_.c_str());
    if (steps_ > 0) {
      std::fprintf(stderr, ": %d/%d", done_, steps_);
    }
    std::fflush(stderr);
  }

  int phases_;
  bool tty_;
  int phase_ = 0;
  std::string what_;
  int steps_ = 0;
  int done_ = 0;
  Clock::time_point start_;
};

std::string failures(int failed) {
  return failed == 0 ? std::string() : " (" + std::to_string(failed) + " failed: see its CSV)";
}

int run(const Options& o) {
  const auto start = Clock::now();
  namespace fs = std::filesystem;
  const fs::path out = fs::absolute(o.out);
  fs::create_directories(out);

  const std::vector<Method> list = methods(o);
  std::vector<Problem> problems = make_problems(o.outputs, o.full);
  std::erase_if(problems, [&](const Problem& p) {
    return !o.work_precision || (!o.problems.empty() && !o.problems.contains(p.id));
  });
  const std::vector<Job> jobs = plan_jobs(o, problems, list);
  const ScalingPlan plan = scaling_plan(o);
  [[maybe_unused]] const EnsemblePlan ensembles = ensemble_plan(o);
#if TUMBLE_BENCH_HAVE_ENSEMBLE
  const bool run_ensemble_study = o.ensemble;
#else
  const bool run_ensemble_study = false;
#endif

  std::vector<MechanismProblem> mechanisms = mechanism_problems();
  std::erase_if(mechanisms, [&](const MechanismProblem& m) {
    return !o.mechanisms || (!o.problems.empty() && !o.problems.contains(m.id));
  });
  const MechanismPlan mechanism_runs = mechanism_plan(o);

  const std::string header = header_text(o, out, static_cast<int>(jobs.size()));
  std::printf("%s\n", header.c_str());
  std::fflush(stdout);
  Progress progress((o.micro ? 1 : 0) + static_cast<int>(problems.size()) + (o.scaling ? 1 : 0) +
                    (run_ensemble_study ? 1 : 0) + static_cast<int>(mechanisms.size()) +
                    (o.plots ? 1 : 0));

  // (a) per-call costs
  std::string tables;
  if (o.micro) {
    progress.begin("per-call micro-benchmarks (tumble_micro)", 0);
    std::string note;
    const auto ns = run_micro(o, out, note);
    progress.end(ns ? "" : ", " + note);
    tables += ns ? micro_table(*ns) : "(a) per-call micro-benchmarks: " + note + "\n";
  }

  // (b) work precision, problem by problem
  const Timing timing = sweep_timing(o);
  std::string work_precision;
  for (Problem& p : problems) {
    std::vector<const Job*> mine;
    for (const Job& j : jobs) {
      if (j.problem == &p) {
        mine.push_back(&j);
      }
    }
    progress.begin("work precision, " + p.id, static_cast<int>(mine.size()) * timing.rounds);
    if (!p.exact) {
      make_stiff_reference(p);
    }
    std::vector<Row> rows;
    int failed = 0;
    for (const Job* j : mine) {
      rows.push_back(run_job(*j, o, timing.round()));
      failed += rows.back().run.ok ? 0 : 1;
      progress.step();
    }
    for (int round = 1; round < timing.rounds; ++round) {
      for (Row& r : rows) {
        retime_job(r, o, timing);
        progress.step();
      }
    }
    progress.end(failures(failed));
    write_runs_csv(out / ("work_precision_" + p.id + ".csv"), rows);
    work_precision += problem_table(p, rows);
  }
  write_problems_csv(out / "problems.csv", problems);
  if (!problems.empty()) {
    tables += "\n";
    tables += problem_table_header();
    tables += work_precision;
    tables += problem_table_footer(o.clock);
  }

  // (c) scaling
  if (o.scaling) {
    progress.begin("scaling, chain of N bodies", scaling_measurements(plan));
    int failed = 0;
    const ScalingProgress callbacks{.start = [&](const std::string&) {},
                                    .done =
                                        [&](const ScalingRow& r) {
                                          failed += r.ok ? 0 : 1;
                                          progress.step();
                                        }};
    const std::vector<ScalingRow> rows = run_scaling(plan, callbacks);
    progress.end(failures(failed));
    write_scaling_csv(out / "scaling.csv", rows);
    tables += "\n";
    tables += scaling_table(rows);
  }

  // (d) ensembles
#if TUMBLE_BENCH_HAVE_ENSEMBLE
  if (run_ensemble_study) {
    progress.begin("ensembles, threads and MPI ranks", ensemble_measurements(ensembles));
    const EnsembleResult result = run_ensemble(ensembles, out, [&] { progress.step(); });
    progress.end();
    write_ensemble_csv(out / "ensemble.csv", result);
    tables += "\n";
    tables += ensemble_table(result, ensembles);
  }
#else
  if (o.ensemble) {
    tables += "\n(d) ensembles: not built (tumble::ensemble needs oneTBB and tumble::odeint)\n";
  }
#endif

  // (e) mechanisms
  std::string mechanism_tables;
  std::vector<MechanismResult> mechanism_results;
  for (const MechanismProblem& m : mechanisms) {
    const int runs =
        static_cast<int>(mechanism_runs.methods.size() * mechanism_runs.tolerances.size());
    progress.begin("mechanisms, " + m.id, runs);
    MechanismResult result = m.run(mechanism_runs, [&] { progress.step(); });
    keep_wanted(mechanism_runs, result.rows);  // the peers' rows, by their labels
    int failed = 0;
    for (const MechanismRow& r : result.rows) {
      failed += r.run.ok ? 0 : 1;
    }
    progress.end(failures(failed));
    write_mechanism_csv(out / ("mechanism_" + m.id + ".csv"), result);
    mechanism_tables += mechanism_table(result);
    mechanism_results.push_back(result);
  }
  if (!mechanisms.empty()) {
    write_mechanisms_csv(out / "mechanisms.csv", mechanism_results);
    tables += "\n" + mechanism_table_header() + mechanism_tables + mechanism_table_footer(o.clock);
  }

  std::string plots = "not drawn (--no-plots)";
  if (o.plots) {
    progress.begin("plots (matplotlib)", 0);
    const std::string note = draw_plots(o, out);
    progress.end(note.empty() ? "" : ", " + note);
    plots = note;
    if (note.empty()) {
      int n = 0;  // main/plot.py prints "plot: FILE" per diagram
      std::ifstream log(out / "plots.log");
      for (std::string line; std::getline(log, line);) {
        n += line.rfind("plot: ", 0) == 0 ? 1 : 0;
      }
      plots = std::to_string(n) +
              " diagrams: work_precision_<problem>.png, scaling.png, mechanisms.png";
    }
  }

  std::string text = tables.starts_with('\n') ? tables.substr(1) : tables;
  text += "\nfinished in " + fmt("%.0f s", seconds_since(start)) + "; files in " + out.string();
  text += "/\n  summary.txt            this report\n"
          "  *.csv                  every run and counter: work_precision_<problem>.csv, "
          "scaling.csv,\n"
          "                         ensemble.csv (ensemble_mpi_np*.txt: the MPI runs' output),\n"
          "                         mechanism_<problem>.csv, mechanisms.csv\n"
          "  *.png                  " +
          plots + "\n";
  if (o.micro) {
    text += "  micro.txt, micro.json  Google Benchmark's raw output; micro_summary.txt: ratios\n";
  }
  std::printf("\n%s", text.c_str());
  std::ofstream(out / "summary.txt") << header << "\n" << text;
  return 0;
}

}  // namespace
}  // namespace tumble::bench

int main(int argc, char** argv) {
  try {
    const auto options = tumble::bench::parse_options(argc, argv);
    if (!options) {
      return 0;
    }
    return tumble::bench::run(*options);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tumble_bench: %s\n", e.what());
    return 1;
  }
}
