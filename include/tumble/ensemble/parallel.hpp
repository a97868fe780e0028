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
#include <optional>
#include <utility>

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/enumerable_thread_specific.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include "tumble/ensemble/options.hpp"

namespace tumble {

/// Threads for the runs of an ensemble, and one `Worker` per thread that takes part: default-
/// constructed on the thread's first run and passed to every run that thread does, so that what
/// it holds (an integrator, scratch) is made once per thread, not once per run, and kept from one
/// for_each() to the next.
template <class Worker> class RunPool {
 public:
  explicit RunPool(const EnsembleOptions& options)
      : options_((validate(options), options)),
        arena_(options.threads == 0 ? oneapi::tbb::task_arena::automatic : options.threads) {}

  /// Calls run(worker, i) for every i in [begin, end), in blocks of options.grain runs spread
  /// over options.threads threads. With threads == 1, or no more runs than one block, the runs
  /// are done in order in the calling thread (no TBB task is made).
  /// run must not throw for a run's own failure (catch it and record it): an exception that
  /// leaves run cancels the runs not yet started and is rethrown here (TBB's propagation).
  template <class Run> void for_each(std::size_t begin, std::size_t end, Run&& run) {
    if (end <= begin) {
      return;
    }
    if (options_.threads == 1 || end - begin <= options_.grain) {
      if (!serial_) {
        serial_.emplace();
      }
      for (std::size_t i = begin; i < end; ++i) {
        run(*serial_, i);
      }
      return;
    }
    arena_.execute([&] {
      oneapi::tbb::parallel_for(oneapi::tbb::blocked_range<std::size_t>(begin, end, options_.grain),
                                [&](const oneapi::tbb::blocked_range<std::size_t>& r) {
                                  Worker& worker = workers_.local();
                                  for (std::size_t i = r.begin(); i != r.end(); ++i) {
                                    run(worker, i);
                                  }
                                });
    });
  }

  [[nodiscard]] const EnsembleOptions& options() const { return options_; }

 private:
  EnsembleOptions options_;
  std::optional<Worker> serial_;   ///< the calling thread's, for the serial path
  oneapi::tbb::task_arena arena_;  ///< initialized on first use only
  oneapi::tbb::enumerable_thread_specific<Worker> workers_;
};

/// run(worker, i) for every i in [0, n) on a RunPool of its own (see RunPool::for_each).
template <class Worker, class Run>
void for_each_run(std::size_t n, const EnsembleOptions& options, Run&& run) {
  RunPool<Worker> pool(options);
  pool.for_each(0, n, std::forward<Run>(run));
}

}  // namespace tumble
