#pragma once
// Runs i = 0, ..., n-1 of an ensemble across threads with oneTBB, each thread with a worker of
// its own (for ensembles: an integrator, made on the thread's first run and reset for the next).
//
// Why oneTBB, and not OpenMP or the C++17 parallel algorithms:
// - work stealing: runs of one ensemble differ in cost (a run that tumbles through more chart
//   switches, or one that fails at once); idle threads take the remaining ranges from busy ones,
//   without tuning a static or dynamic OpenMP schedule;
// - it composes: a task arena bounds this ensemble's threads (EnsembleOptions::threads) without
//   touching a global setting (omp_set_num_threads) or another library's parallel regions, and
//   enumerable_thread_specific gives the per-thread workers that let an integrator be reused;
// - it is a library, not a compiler mode: headers and a shared library (Debian's libtbb-dev,
//   CMake's TBB::tbb), the same with GCC and Clang; std::execution::par gives no thread count, no
//   per-thread state, and on GCC runs on TBB anyway (or serially without it);
// - it is well kept (oneAPI, Apache 2.0, regular releases) and packaged by every distribution.
// Determinism does not come from the scheduler: each run writes only its own result, and a run's
// result depends only on its inputs (the integrators' reset() leaves nothing of an earlier run).

#include <cstddef>

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/enumerable_thread_specific.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include "tumble/ensemble/options.hpp"

namespace tumble {

/// Calls run(worker, i) for every i in [0, n), in blocks of options.grain runs spread over
/// options.threads threads (EnsembleOptions). `Worker` is default-constructed once per thread
/// that takes part, on its first block, and passed to every run that thread does, so that what
/// it holds (an integrator, scratch) is made once per thread, not once per run. With
/// threads == 1, or no more runs than one block, the runs are done in order in the calling
/// thread with one worker.
/// run must not throw for a run's own failure (catch it and record it); an exception that leaves
/// run cancels the runs not yet started and is rethrown here (TBB's exception propagation).
template <class Worker, class Run>
void for_each_run(std::size_t n, const EnsembleOptions& options, Run&& run) {
  validate(options);
  if (options.threads == 1 || n <= options.grain) {
    Worker worker{};
    for (std::size_t i = 0; i < n; ++i) {
      run(worker, i);
    }
    return;
  }
  oneapi::tbb::enumerable_thread_specific<Worker> workers;
  oneapi::tbb::task_arena arena(options.threads == 0 ? oneapi::tbb::task_arena::automatic
                                                     : options.threads);
  arena.execute([&] {
    oneapi::tbb::parallel_for(oneapi::tbb::blocked_range<std::size_t>(0, n, options.grain),
                              [&](const oneapi::tbb::blocked_range<std::size_t>& r) {
                                Worker& worker = workers.local();
                                for (std::size_t i = r.begin(); i != r.end(); ++i) {
                                  run(worker, i);
                                }
                              });
  });
}

}  // namespace tumble
