#pragma once
// tumble_bench, the driver: what its own files offer each other. The shared data types
// (problems, runs, errors, methods, the scaling study) are in common/bench.hpp; this header adds
//   options    the command line                        (main/options.cpp)
//   sweep      which runs to make, and making them     (work_precision/sweep.cpp)
//   report     the terminal tables                     (main/report.cpp)
//   csv        the CSV files                           (main/csv.cpp)
//   tools      tumble_micro, the plot script, tumble_bench_mpi (main/tools.cpp)
// and study (e), mechanisms, declares its own (mechanisms/mechanisms.hpp);
// and main/main.cpp runs the phases in order.

#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "common/bench.hpp"
#include "mechanisms/mechanisms.hpp"

#ifndef TUMBLE_BENCH_DEFAULT_OUT
#define TUMBLE_BENCH_DEFAULT_OUT "benchmark-results"
#endif
#ifndef TUMBLE_BENCH_PLOT_PYTHON
#define TUMBLE_BENCH_PLOT_PYTHON "python3"
#endif

namespace tumble::bench {

// ---- options ---------------------------------------------------------------------------------

struct Options {
  bool full = false;
  std::string out = TUMBLE_BENCH_DEFAULT_OUT;
  int reps = 3;
  int outputs = 200;
  std::set<std::string> problems;    // empty: all
  std::vector<std::string> methods;  // empty: all; else method labels containing one of these
  std::vector<double> tolerances;    // empty: the default sweep
  bool work_precision = true;        // the work-precision sweep (b)
  bool scaling = true;
  bool ensemble = true;    // the ensemble study (d), when tumble::ensemble was found
  bool mechanisms = true;  // the mechanisms' work precision (e)
  bool mpi = true;         // its runs over MPI ranks, when tumble_bench_mpi was built
  bool plots = true;
  bool micro = true;
  bool exact_jacobian = true;  // tumble with BDF: the scene's Jacobian, or difference quotients
  bool fused_ops = true;       // CVODE methods: SUNDIALS' fused vector operations
  TimeBase clock = TimeBase::wall;
  std::string python = TUMBLE_BENCH_PLOT_PYTHON;
};

/// The options, or nullopt after --help (printed). Throws std::invalid_argument on a bad one.
std::optional<Options> parse_options(int argc, char** argv);

// ---- sweep -----------------------------------------------------------------------------------

/// The tolerances rtol = atol of the CVODE methods, unless --tolerances says otherwise.
extern const std::vector<double> kTolerances;

/// How the sweep times a setting: the best of --reps runs, and of more when they are fast, until
/// the runs add up to min_total (a setting of 50 us is timed 200 times, one of 2 ms 5 times); a
/// single run once one takes longer than slow_run. The repetitions are made in up to 3 rounds
/// over each problem's settings (Timing::rounds).
Timing sweep_timing(const Options& o);

/// One measurement to make: a method on a problem at one setting.
struct Job {
  const Problem* problem = nullptr;
  const Method* method_entry = nullptr;
  Scheme scheme = Scheme::adams;
  double tol = 0;    // adaptive methods
  int substeps = 0;  // RK4: steps per output interval
  [[nodiscard]] bool fixed_step() const { return scheme == Scheme::rk4; }
  [[nodiscard]] std::string method() const;   ///< "tumble EulerParameters adams", ...
  [[nodiscard]] std::string setting() const;  ///< "tol=1.0e-06" or "h=2.5e-01"
};

/// A finished measurement.
struct Row {
  Job job;
  Run run;
  Errors errors;
};

/// The methods of the run (the quick ones, or all with --full).
std::vector<Method> methods(const Options& o);
/// Every run of the work-precision sweep, problem by problem, filtered by --methods.
std::vector<Job> plan_jobs(const Options& o, const std::vector<Problem>& problems,
                           const std::vector<Method>& methods);
/// Makes one run and measures its errors (the samples are then dropped); `timing` is one
/// round's (Timing::round()).
Row run_job(const Job& j, const Options& o, const Timing& timing);
/// A later round of r's run: its repetitions added to r's timing record (Timing::rounds), unless
/// it failed or took longer than timing.slow_run.
void retime_job(Row& r, const Options& o, const Timing& timing);
/// The stiff top's reference integration (it has no closed form), into p.reference.
void make_stiff_reference(Problem& p);
/// The bodies counts and repetitions of the scaling study.
ScalingPlan scaling_plan(const Options& o);
/// The run counts and repetitions of the ensemble study.
EnsemblePlan ensemble_plan(const Options& o);

// ---- report ----------------------------------------------------------------------------------

/// CPU ns per call of each micro-benchmark (Google Benchmark name -> median).
using MicroTimes = std::map<std::string, double>;

/// The header: what is measured, on what, how it is timed, how long it takes, where it goes.
std::string header_text(const Options& o, const std::filesystem::path& out, int runs);
/// (a) ns per call of the core assembly per parameterization, with the baselines and peers.
std::string micro_table(const MicroTimes& ns);
/// A run's error (any measure) and time, one point of a work-precision sweep.
struct Point {
  double error;
  double time;
};
/// The time a method needs to reach an error, read off its sweep (time_at).
struct TimeAt {
  double time = std::numeric_limits<double>::quiet_NaN();
  bool bound = false;  ///< the cheapest run is already more accurate: its time, an upper bound
};
/// The time to reach error `target` read off a sweep's points: on the Pareto front (each kept
/// run is faster than every more accurate one), log(time) interpolated linearly in log(error)
/// between the two runs that bracket the target; nullopt when no run reaches it.
std::optional<TimeAt> time_at(std::vector<Point> points, double target);

/// (b) time to reach max attitude error 1e-3 / 1e-6 / 1e-9 / 1e-11 and the best error, per
/// method.
std::string problem_table(const Problem& p, const std::vector<Row>& rows);
/// The column headings of the work-precision tables (one for all problems).
std::string problem_table_header();
/// The footer of the work-precision tables: how t(e) is read off a sweep.
std::string problem_table_footer(TimeBase clock);
/// (e) per mechanism and method, the time to reach an error of 1e-3, 1e-6, 1e-9 (time_at), the
/// best error and the constraint residual |C| at the end of the most accurate run.
std::string mechanism_table(const MechanismResult& r);
/// The column headings and the footer of the mechanisms' tables.
std::string mechanism_table_header();
std::string mechanism_table_footer(TimeBase clock);
/// The tolerance ladder and methods of study (e), from the options (--tolerances, --methods).
MechanismPlan mechanism_plan(const Options& o);

/// (c) cost per right-hand side and per BDF step against the number of bodies, with slopes.
std::string scaling_table(const std::vector<ScalingRow>& rows);
/// (d) runs per second of an ensemble against threads and processes, the per-run cost against
/// serial loops, memory and allocations per run, and the targets they are held to.
std::string ensemble_table(const EnsembleResult& r, const EnsemblePlan& plan);

// ---- csv -------------------------------------------------------------------------------------

void write_runs_csv(const std::filesystem::path& path, const std::vector<Row>& rows);
void write_scaling_csv(const std::filesystem::path& path, const std::vector<ScalingRow>& rows);
void write_ensemble_csv(const std::filesystem::path& path, const EnsembleResult& r);
/// Every run of a mechanism of study (e): mechanism_<id>.csv.
void write_mechanism_csv(const std::filesystem::path& path, const MechanismResult& r);
/// Each mechanism's title, error measure and reference: mechanisms.csv.
void write_mechanisms_csv(const std::filesystem::path& path,
                          const std::vector<MechanismResult>& results);
void write_problems_csv(const std::filesystem::path& path, const std::vector<Problem>& problems);
/// Reads "benchmark,cpu_ns" (micro/summarize.py --csv); empty when the file is not there.
MicroTimes read_micro_csv(const std::filesystem::path& path);

// ---- tools -----------------------------------------------------------------------------------

/// Runs the short list of tumble_micro (through micro/summarize.py) with every raw output in
/// `out`: micro.json, micro.txt (Google Benchmark's console table), micro_summary.txt (ratios),
/// micro_times.csv. Returns the times, or nullopt with `note` saying why there are none.
std::optional<MicroTimes> run_micro(const Options& o, const std::filesystem::path& out,
                                    std::string& note);
/// Draws the PNG diagrams from the CSVs in `out` (main/plot.py); returns "" on success,
/// else why not.
std::string draw_plots(const Options& o, const std::filesystem::path& out);
/// Whether tumble_bench_mpi (the ensemble study over MPI ranks) was built with tumble_bench.
bool ensemble_mpi_built();
/// Runs tumble_bench_mpi under mpiexec with `ranks` processes and the arguments `args`, both its
/// output streams into `log`; returns "" on success, else why not.
std::string run_ensemble_mpi(int ranks, const std::string& args, const std::filesystem::path& log);

}  // namespace tumble::bench
