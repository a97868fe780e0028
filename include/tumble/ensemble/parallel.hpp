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

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <utility>

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/enumerable_thread_specific.h>
#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include "tumble/ensemble/options.hpp"

namespace tumble {

/// The threads an ensemble with these options runs on: options.threads, or TBB's choice for 0,
/// at most the parallelism TBB allows this process (the cores it may use, or a lower
/// tbb::global_control limit). Asking for more runs this many, without TBB's warning.
inline int ensemble_threads(const EnsembleOptions& options) {
  const auto allowed = static_cast<int>(
      std::min<std::size_t>(oneapi::tbb::global_control::active_value(
                                oneapi::tbb::global_control::max_allowed_parallelism),
                            static_cast<std::size_t>(oneapi::tbb::info::default_concurrency())));
  const int limit = std::max(1, allowed);
  return options.threads == 0 ? limit : std::min(options.threads, limit);
}

/// Threads for the runs of an ensemble, and one `Worker` per thread that takes part: default-
/// constructed on the thread's first run and passed to every run that thread does, so that what
/// it holds (an integrator, scratch) is made once per thread, not once per run, and kept from one
/// for_each() to the next. A worker is used by its thread only, and lives in cache lines of its
/// own (TBB pads each thread's element), so that no two threads write the same line.
template <class Worker> class RunPool {
 public:
  explicit RunPool(const EnsembleOptions& options)
      : options_((validate(options), options)),
        threads_(ensemble_threads(options)),
        arena_(threads_) {}

  /// Calls run(worker, i) for every i in [begin, end), in blocks of options.grain runs spread
  /// over threads() threads. With one thread, or no more runs than one block, the runs are done
  /// in order in the calling thread (no TBB task is made).
  /// run must not throw for a run's own failure (catch it and record it): an exception that
  /// leaves run cancels the runs not yet started and is rethrown here (TBB's propagation).
  /// \returns the number of threads that did at least one run.
  template <class Run> int for_each(std::size_t begin, std::size_t end, Run&& run) {
    if (end <= begin) {
      return 0;
    }
    if (threads_ == 1 || end - begin <= options_.grain) {
      if (!serial_) {
        serial_.emplace();
      }
      for (std::size_t i = begin; i < end; ++i) {
        run(*serial_, i);
      }
      return 1;
    }
    const std::uint64_t call = ++calls_;
    std::atomic<int> used{0};
    arena_.execute([&] {
      oneapi::tbb::parallel_for(oneapi::tbb::blocked_range<std::size_t>(begin, end, options_.grain),
                                [&](const oneapi::tbb::blocked_range<std::size_t>& r) {
                                  Local& local = workers_.local();
                                  if (local.call != call) {
                                    local.call = call;
                                    used.fetch_add(1, std::memory_order_relaxed);
                                  }
                                  // Isolated: should a run wait inside (an observer calling a TBB
                                  // algorithm), this thread takes no other run meanwhile, which
                                  // would reuse its worker mid-run.
                                  oneapi::tbb::this_task_arena::isolate([&] {
                                    for (std::size_t i = r.begin(); i != r.end(); ++i) {
                                      run(local.worker, i);
                                    }
                                  });
                                });
    });
    return used.load();
  }

  [[nodiscard]] const EnsembleOptions& options() const { return options_; }
  /// The threads the runs are spread over (ensemble_threads(options)).
  [[nodiscard]] int threads() const { return threads_; }

 private:
  struct Local {
    Worker worker{};
    std::uint64_t call = 0;  ///< the last for_each() this thread took part in
  };

  EnsembleOptions options_;
  int threads_;
  std::optional<Worker> serial_;   ///< the calling thread's, for the serial path
  oneapi::tbb::task_arena arena_;  ///< initialized on first use only
  oneapi::tbb::enumerable_thread_specific<Local> workers_;
  std::uint64_t calls_ = 0;
};

/// run(worker, i) for every i in [0, n) on a RunPool of its own (see RunPool::for_each).
/// \returns the number of threads that did at least one run.
template <class Worker, class Run>
int for_each_run(std::size_t n, const EnsembleOptions& options, Run&& run) {
  RunPool<Worker> pool(options);
  return pool.for_each(0, n, std::forward<Run>(run));
}

}  // namespace tumble
