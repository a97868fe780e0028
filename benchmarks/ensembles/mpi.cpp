// tumble_bench_mpi: the ensemble study's runs (ensembles/runs.hpp) over MPI processes,
// with tumble::MpiEnsemble, for tumble_bench, which launches it under mpiexec with 1 and 2
// processes (main/tools.cpp) and reads what rank 0 prints:
//   seconds S      one line per repetition: the wall time of MpiEnsemble::integrate at rank 0,
//                  from a barrier to the results of every run gathered there (MPI's start-up
//                  and the first integrator's construction are outside it or in it alike for
//                  every repetition, the median is taken);
//   cpu C          one line per repetition: the CPU time of every rank in it, summed (how many
//                  cores the ranks had: below their number, the machine was busy);
//   sum X          the runs' values summed in run order, as a hexadecimal float (exact), which
//                  tumble_bench compares with its threads' sum: the same runs, bit for bit.
// Usage: tumble_bench_mpi --runs N --reps R --tol T [--threads K]   (threads per rank, default 1)

#include "tumble/ensemble/mpi.hpp"

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

#include <mpi.h>
#include <time.h>

#include "ensembles/runs.hpp"

namespace {

using namespace tumble::bench::ensemble;

/// The CPU time of this process, all its threads, s.
double process_cpu() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

struct Args {
  std::size_t runs = 2000;
  int reps = 3;
  double tol = 1e-8;
  int threads = 1;
};

Args parse(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string k = argv[i];
    if (i + 1 >= argc) {
      throw std::invalid_argument(k + " needs a value");
    }
    const std::string v = argv[++i];
    if (k == "--runs") {
      a.runs = static_cast<std::size_t>(std::stoul(v));
    } else if (k == "--reps") {
      a.reps = std::max(1, std::stoi(v));
    } else if (k == "--tol") {
      a.tol = std::stod(v);
    } else if (k == "--threads") {
      a.threads = std::stoi(v);
    } else {
      throw std::invalid_argument("unknown option " + k);
    }
  }
  return a;
}

int run(const Args& a) {
  const Tumbling t;
  const tumble::MpiEnsemble ensemble(t.scene, MakeIntegrator{odeint_options(a.tol)},
                                     {.threads = a.threads});
  const std::vector<double> times{kEnd};
  const auto initial = [&](std::size_t i) { return t.initial(i); };
  int status = 0;
  for (int r = 0; r < a.reps; ++r) {
    MPI_Barrier(ensemble.communicator());
    const double cpu0 = process_cpu();
    const auto start = std::chrono::steady_clock::now();
    const auto out = ensemble.integrate<double>(a.runs, initial, 0.0, times, KeepAngle{&t});
    const double s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double cpu = process_cpu() - cpu0;
    double cpu_all = 0;  // the CPU time of every rank in this repetition
    MPI_Reduce(&cpu, &cpu_all, 1, MPI_DOUBLE, MPI_SUM, 0, ensemble.communicator());
    if (ensemble.rank() == 0) {
      const auto failed = tumble::failures(out);
      if (!failed.empty()) {
        std::printf("failed %zu runs, run %zu: %s\n", failed.size(), failed.front().run,
                    failed.front().message.c_str());
        status = 1;
      }
      std::printf("seconds %.9g\ncpu %.9g\n", s, cpu_all);
      if (r + 1 == a.reps) {
        const double sum =
            tumble::fold_runs(out, 0.0, [](double acc, std::size_t, double v) { return acc + v; });
        std::printf("sum %a\nranks %d threads %d runs %zu tol %.17g\n", sum, ensemble.ranks(),
                    a.threads, a.runs, a.tol);
      }
      std::fflush(stdout);
    }
  }
  return status;
}

}  // namespace

int main(int argc, char** argv) {
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  int status = 0;
  try {
    status = run(parse(argc, argv));
  } catch (const std::exception& e) {
    // The same arguments on every rank fail alike; anything else must not leave a rank waiting.
    std::fprintf(stderr, "tumble_bench_mpi: %s\n", e.what());
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  MPI_Finalize();
  return status;
}
