#pragma once
// How an ensemble (ensemble.hpp, variants.hpp) spreads its runs over threads. No TBB here: the
// options read without it.

#include <cstddef>
#include <stdexcept>
#include <string>

namespace tumble {

/// Threads and task size of an ensemble. The results never depend on them (each run is
/// independent and deterministic, and each writes only its own result): they set the speed only.
struct EnsembleOptions {
  /// At most this many threads: 1 runs the ensemble serially in the calling thread (no TBB task
  /// is made); n > 1 runs it in a task arena of n threads, or of as many as TBB allows this
  /// process (the cores it may use) if fewer (Ensemble::threads() says which); 0 lets TBB choose
  /// (the cores this process may use).
  int threads = 0;
  /// Runs per task (TBB's grain size): larger amortizes the scheduling over many short runs,
  /// 1 balances best when runs differ much in cost (a run that switches charts or fails early).
  std::size_t grain = 1;
};

/// \throws std::invalid_argument for threads < 0 or grain == 0.
inline void validate(const EnsembleOptions& o) {
  if (o.threads < 0) {
    throw std::invalid_argument("tumble::EnsembleOptions: threads = " + std::to_string(o.threads) +
                                " must be >= 0 (0: TBB's choice, 1: serial)");
  }
  if (o.grain == 0) {
    throw std::invalid_argument("tumble::EnsembleOptions: grain must be >= 1");
  }
}

}  // namespace tumble
