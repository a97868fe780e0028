// tumble_bench: the programs it runs, each with its own output kept in the results folder so
// that the terminal shows only the tables:
//  - tumble_micro (Google Benchmark), through micro/summarize.py --quick: the short list of
//    per-call benchmarks; its raw console table goes to micro.txt, the JSON to micro.json, the
//    medians to micro_times.csv (which the report reads) and the ratios to micro_summary.txt;
//  - main/plot.py (matplotlib): the PNG diagrams from the CSVs; its log to plots.log;
//  - tumble_bench_mpi under mpiexec (built when tumble::mpi exists): the ensemble study's runs
//    over MPI processes; its output to ensemble_mpi_np<ranks>.txt, which the study parses.
//    mpiexec's path, its process-count flag and its flags (Open MPI: --oversubscribe, --bind-to
//    none, as the MPI tests use) come from CMake's FindMPI (main/tumble_bench.cmake); Open MPI
//    refuses to start as root unless OMPI_ALLOW_RUN_AS_ROOT(_CONFIRM) say so.

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

#include "main/driver.hpp"

#ifndef TUMBLE_BENCH_PLOT_SCRIPT
#define TUMBLE_BENCH_PLOT_SCRIPT "main/plot.py"
#endif
#ifndef TUMBLE_BENCH_MICRO
#define TUMBLE_BENCH_MICRO ""
#endif
#ifndef TUMBLE_BENCH_MICRO_SCRIPT
#define TUMBLE_BENCH_MICRO_SCRIPT ""
#endif
#ifndef TUMBLE_BENCH_MPI
#define TUMBLE_BENCH_MPI ""
#endif
#ifndef TUMBLE_BENCH_MPIEXEC
#define TUMBLE_BENCH_MPIEXEC "mpiexec"
#endif
#ifndef TUMBLE_BENCH_MPIEXEC_NUMPROC_FLAG
#define TUMBLE_BENCH_MPIEXEC_NUMPROC_FLAG "-n"
#endif
#ifndef TUMBLE_BENCH_MPIEXEC_PREFLAGS
#define TUMBLE_BENCH_MPIEXEC_PREFLAGS ""
#endif

namespace tumble::bench {
namespace {

std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char ch : s) {
    if (ch == '\'') {
      q += "'\\''";
    } else {
      q += ch;
    }
  }
  return q + "'";
}

int shell(const std::string& command) {
  std::fflush(stdout);
  std::fflush(stderr);
  return std::system(command.c_str());
}

}  // namespace

std::optional<MicroTimes> run_micro(const Options& o, const std::filesystem::path& out,
                                    std::string& note) {
  const std::string micro = TUMBLE_BENCH_MICRO, script = TUMBLE_BENCH_MICRO_SCRIPT;
  if (micro.empty() || !std::filesystem::exists(micro)) {
    note = "skipped: tumble_micro was not built (Google Benchmark missing?)";
    return std::nullopt;
  }
  if (script.empty() || !std::filesystem::exists(script)) {
    note = "skipped: micro/summarize.py not found";
    return std::nullopt;
  }
  const std::filesystem::path times = out / "micro_times.csv";
  std::filesystem::remove(times);
  const std::string cmd =
      shell_quote(o.python) + " " + shell_quote(script) + " --run " + shell_quote(micro) +
      " --quick --out " + shell_quote((out / "micro.json").string()) + " --csv " +
      shell_quote(times.string()) + " > " + shell_quote((out / "micro_summary.txt").string()) +
      " 2> " + shell_quote((out / "micro.txt").string());
  if (shell(cmd) != 0) {
    note = "FAILED: see " + (out / "micro.txt").string();
    return std::nullopt;
  }
  MicroTimes ns = read_micro_csv(times);
  if (ns.empty()) {
    note = "FAILED: no times in " + times.string();
    return std::nullopt;
  }
  return ns;
}

std::string draw_plots(const Options& o, const std::filesystem::path& out) {
  const std::string script = TUMBLE_BENCH_PLOT_SCRIPT;
  if (!std::filesystem::exists(script)) {
    return "skipped: the script " + script + " is not there";
  }
  if (shell(shell_quote(o.python) + " -c 'import matplotlib' >/dev/null 2>&1") != 0) {
    return "skipped: matplotlib is not available to " + o.python +
           " (install python3-matplotlib, or pass --python)";
  }
  const std::string log = (out / "plots.log").string();
  if (shell(shell_quote(o.python) + " " + shell_quote(script) + " " + shell_quote(out.string()) +
            " > " + shell_quote(log) + " 2>&1") != 0) {
    return "FAILED: see " + log;
  }
  return "";
}

bool ensemble_mpi_built() {
  const std::string program = TUMBLE_BENCH_MPI;
  return !program.empty() && std::filesystem::exists(program);
}

std::string run_ensemble_mpi(int ranks, const std::string& args, const std::filesystem::path& log) {
  if (!ensemble_mpi_built()) {
    return "tumble_bench_mpi was not built";
  }
  // The flags are a list that the shell splits (from CMake's MPIEXEC_PREFLAGS and ours). An MPI
  // that cannot start its processes may wait forever: coreutils' timeout, where there is one,
  // stops it after 10 minutes and the main job goes on without the MPI rows.
  const std::string cmd = "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 "
                          "$(command -v timeout >/dev/null 2>&1 && echo timeout 600) " +
                          shell_quote(TUMBLE_BENCH_MPIEXEC) + " " +
                          TUMBLE_BENCH_MPIEXEC_NUMPROC_FLAG + " " + std::to_string(ranks) + " " +
                          TUMBLE_BENCH_MPIEXEC_PREFLAGS + " " + shell_quote(TUMBLE_BENCH_MPI) +
                          " " + args + " > " + shell_quote(log.string()) + " 2>&1";
  if (shell(cmd) != 0) {
    return "FAILED: see " + log.string();
  }
  return "";
}

}  // namespace tumble::bench
