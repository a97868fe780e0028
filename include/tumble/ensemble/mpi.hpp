#pragma once
// MpiEnsemble: the runs of an Ensemble (ensemble.hpp) partitioned over the ranks of an MPI
// communicator, each rank running its part on its own threads (RunPool), the results gathered
// at rank 0. The only header of tumble that includes <mpi.h> (link tumble::mpi).
//
//   MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);   // the user's, before
//   {
//     MpiEnsemble ensemble(scene, make, {.threads = 2});              // every rank, same arguments
//     auto r = ensemble.integrate<double>(n, initial, 0.0, times, observe);
//     if (ensemble.rank() == 0) { ... r holds all n runs, in run order ... }
//   }
//   MPI_Finalize();                                                   // the user's, after
//
// mpi_integrate_variants does the same for integrate_variants (variants.hpp: a scene per run).
//
// - Every rank calls the same functions with the same arguments (the same run count, times and
//   block); the scene, the factory, initial(i) and the observer must give each run the same
//   inputs on every rank. Run i's result is then the one a one-process Ensemble gives, to the bit.
// - Rank r runs one contiguous block of run indices (runs_of_rank); the blocks differ in length
//   by one run at most. Only the calling thread calls MPI (MPI_THREAD_FUNNELED is enough; plain
//   MPI_Init, MPI_THREAD_SINGLE, only with threads = 1).
// - Results travel as bytes: R must be trivially copyable (no pointers, no std::vector; a fixed
//   array or a struct of numbers). A failed run's RunError travels too, its message cut to
//   kMaxMessage characters.
// - A run that throws becomes its RunError on its rank and the collective calls still happen on
//   every rank: a failing run never stops or hangs the others. A failure outside any run (a
//   thread that cannot be started, memory) or arguments that differ between ranks make every
//   rank throw, never one rank alone.
// - statistics() says what the last call ran, as Ensemble::statistics() does: the runs and the
//   failed ones over all ranks (the same on every rank), the ranks and each rank's runs, and this
//   rank's part (its runs, failures, threads and the threads that took part).

#include <algorithm>
#include <climits>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <exception>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <mpi.h>

#include "tumble/ensemble/detail/run.hpp"
#include "tumble/ensemble/ensemble.hpp"
#include "tumble/ensemble/options.hpp"
#include "tumble/ensemble/outcome.hpp"
#include "tumble/ensemble/parallel.hpp"
#include "tumble/ensemble/variants.hpp"

namespace tumble {

namespace detail {

/// \throws std::runtime_error with MPI's text for an MPI error code (reached only when the
/// communicator's error handler returns errors instead of aborting, MPI_ERRORS_RETURN).
inline void mpi_check(int code, const char* call) {
  if (code != MPI_SUCCESS) {
    char text[MPI_MAX_ERROR_STRING];
    int length = 0;
    MPI_Error_string(code, text, &length);
    throw std::runtime_error(std::string("tumble::MpiEnsemble: ") + call +
                             " failed: " + std::string(text, static_cast<std::size_t>(length)));
  }
}

/// Runs [begin, end) of rank `rank` among `ranks`, when [0, runs) is cut into contiguous blocks:
/// the first runs % ranks ranks have one run more.
inline std::pair<std::size_t, std::size_t> mpi_block(std::size_t runs, int rank, int ranks) {
  const auto r = static_cast<std::size_t>(rank), n = static_cast<std::size_t>(ranks);
  const std::size_t base = runs / n, extra = runs % n;
  const std::size_t begin = r * base + std::min(r, extra);
  return {begin, begin + base + (r < extra ? 1 : 0)};
}

/// A RunError's message is cut to this many characters for the transfer to rank 0.
inline constexpr std::size_t kMpiMaxMessage = 1024;

/// A communicator checked for an ensemble, with this process's rank and the number of ranks.
struct MpiComm {
  MPI_Comm comm = MPI_COMM_NULL;
  int rank = 0;
  int ranks = 1;
};

/// \throws std::logic_error if MPI is not initialized or already finalized, or if threads != 1
///         and MPI was initialized without MPI_THREAD_FUNNELED (or higher);
///         std::invalid_argument for MPI_COMM_NULL or an intercommunicator.
inline MpiComm mpi_comm(MPI_Comm comm, int threads) {
  int flag = 0;
  mpi_check(MPI_Initialized(&flag), "MPI_Initialized");
  if (!flag) {
    throw std::logic_error("tumble::MpiEnsemble: MPI is not initialized: call MPI_Init_thread "
                           "(MPI_THREAD_FUNNELED) first");
  }
  mpi_check(MPI_Finalized(&flag), "MPI_Finalized");
  if (flag) {
    throw std::logic_error("tumble::MpiEnsemble: MPI is already finalized");
  }
  if (comm == MPI_COMM_NULL) {
    throw std::invalid_argument("tumble::MpiEnsemble: the communicator is MPI_COMM_NULL");
  }
  mpi_check(MPI_Comm_test_inter(comm, &flag), "MPI_Comm_test_inter");
  if (flag) {
    throw std::invalid_argument("tumble::MpiEnsemble: an intercommunicator has no rank 0 to "
                                "gather at: use an intracommunicator");
  }
  int provided = MPI_THREAD_SINGLE;
  mpi_check(MPI_Query_thread(&provided), "MPI_Query_thread");
  if (threads != 1 && provided < MPI_THREAD_FUNNELED) {
    throw std::logic_error("tumble::MpiEnsemble: threads != 1 needs MPI initialized with "
                           "MPI_Init_thread(..., MPI_THREAD_FUNNELED, ...) or higher; or set "
                           "EnsembleOptions::threads = 1");
  }
  MpiComm c{comm, 0, 1};
  mpi_check(MPI_Comm_rank(comm, &c.rank), "MPI_Comm_rank");
  mpi_check(MPI_Comm_size(comm, &c.ranks), "MPI_Comm_size");
  return c;
}

/// Checks the arguments, the same on every rank, before any run: every rank throws, or none.
template <class R, class Times>
void mpi_agree(const MpiComm& c, std::size_t runs, std::size_t per_gather, double t0,
               const Times& times) {
  static_assert(std::is_trivially_copyable_v<R> && std::is_default_constructible_v<R>,
                "tumble::MpiEnsemble: a run's result R travels between ranks as bytes: it must "
                "be trivially copyable and default-constructible");
  std::string invalid;
  try {
    check_output_times(t0, times);
    if (per_gather == 0) {
      throw std::invalid_argument("tumble::MpiEnsemble::fold: block must be >= 1");
    }
    if (std::min(runs, per_gather) > static_cast<std::size_t>(INT_MAX) / sizeof(R)) {
      throw std::invalid_argument("tumble::MpiEnsemble: the results of one gather exceed "
                                  "INT_MAX bytes: use fold() with a smaller block");
    }
  } catch (const std::exception& e) {
    invalid = e.what();
  }
  // Maxima of x and of ~x: equal on every rank iff x is. The last entry: any rank invalid.
  std::uint64_t m = 0;  // the number of output times, of any range Ensemble accepts
  for ([[maybe_unused]] const auto& t : times) {
    ++m;
  }
  const std::uint64_t n = runs, b = per_gather;
  std::uint64_t mine[7] = {n, ~n, b, ~b, m, ~m, invalid.empty() ? 0u : 1u}, all[7];
  mpi_check(MPI_Allreduce(mine, all, 7, MPI_UINT64_T, MPI_MAX, c.comm), "MPI_Allreduce");
  if (!invalid.empty()) {
    throw std::invalid_argument(invalid);
  }
  if (all[6] != 0) {
    throw std::invalid_argument("tumble::MpiEnsemble: the arguments are invalid on another rank");
  }
  if (all[0] != n || ~all[1] != n || all[2] != b || ~all[3] != b || all[4] != m || ~all[5] != m) {
    throw std::invalid_argument("tumble::MpiEnsemble: the ranks were called with different run "
                                "counts, blocks or numbers of output times");
  }
}

/// Rank 0 receives every rank's outcomes of runs [first, last): the values as bytes, a code
/// per run (0: a value; k > 0: an error whose message has k - 1 characters) and the messages.
template <class R>
std::vector<RunOutcome<R>> mpi_gather(const MpiComm& c, std::size_t first, std::size_t last,
                                      const std::vector<RunOutcome<R>>& mine) {
  std::vector<R> values(mine.size());  // a failed run's slot stays value-initialized
  std::vector<std::uint64_t> codes(mine.size(), 0);
  std::string text;
  const std::size_t text_cap = static_cast<std::size_t>(INT_MAX / c.ranks);
  for (std::size_t k = 0; k < mine.size(); ++k) {
    if (mine[k].ok()) {
      std::memcpy(static_cast<void*>(&values[k]), &mine[k].value(), sizeof(R));
    } else {
      const std::string& m = mine[k].error().message;
      const std::size_t len = std::min({m.size(), kMpiMaxMessage, text_cap - text.size()});
      text.append(m, 0, len);
      codes[k] = len + 1;
    }
  }
  const std::size_t n = last - first;
  const bool root = c.rank == 0;
  std::vector<int> counts(root ? c.ranks : 0), displs(root ? c.ranks : 0);
  const auto layout = [&](std::size_t unit) {
    for (int r = 0; r < (root ? c.ranks : 0); ++r) {
      const auto [b, e] = mpi_block(n, r, c.ranks);
      counts[r] = static_cast<int>((e - b) * unit);
      displs[r] = static_cast<int>(b * unit);
    }
  };
  std::vector<R> all_values(root ? n : 0);
  layout(sizeof(R));
  mpi_check(MPI_Gatherv(values.data(), static_cast<int>(values.size() * sizeof(R)), MPI_BYTE,
                        all_values.data(), counts.data(), displs.data(), MPI_BYTE, 0, c.comm),
            "MPI_Gatherv (results)");
  std::vector<std::uint64_t> all_codes(root ? n : 0);
  layout(1);
  mpi_check(MPI_Gatherv(codes.data(), static_cast<int>(codes.size()), MPI_UINT64_T,
                        all_codes.data(), counts.data(), displs.data(), MPI_UINT64_T, 0, c.comm),
            "MPI_Gatherv (codes)");
  const int text_size = static_cast<int>(text.size());
  mpi_check(MPI_Gather(&text_size, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, c.comm),
            "MPI_Gather (message sizes)");
  std::size_t total = 0;
  for (int r = 0; r < (root ? c.ranks : 0); ++r) {
    displs[r] = static_cast<int>(total);
    total += static_cast<std::size_t>(counts[r]);
  }
  std::string all_text(total, '\0');
  mpi_check(MPI_Gatherv(text.data(), text_size, MPI_CHAR, all_text.data(), counts.data(),
                        displs.data(), MPI_CHAR, 0, c.comm),
            "MPI_Gatherv (messages)");
  std::vector<RunOutcome<R>> out;
  if (!root) {
    return out;
  }
  out.reserve(n);
  std::size_t at = 0;  // the messages are in run order, as the ranks' blocks are
  for (std::size_t k = 0; k < n; ++k) {
    if (all_codes[k] == 0) {
      out.emplace_back(std::move(all_values[k]));
    } else {
      const auto len = static_cast<std::size_t>(all_codes[k] - 1);
      out.emplace_back(RunError{first + k, all_text.substr(at, len)});
      at += len;
    }
  }
  return out;
}

/// Runs [first, last) over the ranks: run(b, e, outcomes) does this rank's runs [b, e) on its
/// threads, an outcome each, catching each run's failure; the outcomes are gathered at rank 0
/// (empty elsewhere). Every rank makes the same collective calls whatever failed: a failure
/// outside the runs on any rank makes every rank throw. Adds this rank's failed runs to
/// `failed_here` and all ranks' to `failed_all` (in the reduction the failure check makes anyway).
template <class R, class Run>
std::vector<RunOutcome<R>> mpi_run_block(const MpiComm& c, std::size_t first, std::size_t last,
                                         Run&& run, std::size_t& failed_here,
                                         std::size_t& failed_all) {
  const auto [b, e] = mpi_block(last - first, c.rank, c.ranks);
  std::vector<RunOutcome<R>> mine(e - b);
  std::string fault;
  try {
    run(first + b, first + e, mine);
  } catch (const std::exception& x) {
    fault = x.what();
  } catch (...) {
    fault = "an exception not derived from std::exception";
  }
  std::uint64_t failed_runs = 0;
  for (const RunOutcome<R>& o : mine) {
    failed_runs += o.failed() ? 1 : 0;
  }
  // Summed over the ranks: the ranks that failed outside their runs, and the failed runs.
  std::uint64_t local[2] = {fault.empty() ? 0u : 1u, failed_runs}, sum[2] = {0, 0};
  mpi_check(MPI_Allreduce(local, sum, 2, MPI_UINT64_T, MPI_SUM, c.comm), "MPI_Allreduce");
  const bool failed = !fault.empty();
  failed_here += static_cast<std::size_t>(failed_runs);
  failed_all += static_cast<std::size_t>(sum[1]);
  if (sum[0] != 0) {
    throw std::runtime_error(failed ? "tumble::MpiEnsemble: rank " + std::to_string(c.rank) +
                                          " failed outside its runs: " + fault
                                    : "tumble::MpiEnsemble: another rank failed outside its "
                                      "runs (see its exception)");
  }
  return mpi_gather(c, first, last, mine);
}

}  // namespace detail

/// What the last call of an MpiEnsemble (integrate or fold) ran: EnsembleStatistics over the
/// ranks.
struct MpiEnsembleStatistics {
  std::size_t runs = 0;    ///< runs done, over all ranks
  std::size_t failed = 0;  ///< of which failed (a RunError), over all ranks; the same on each rank
  int ranks = 0;           ///< the ranks the runs were spread over (MpiEnsemble::ranks())
  std::vector<std::size_t> runs_per_rank;  ///< the runs each rank did, in rank order
  /// This rank's part: its runs, its failed runs, its threads (Ensemble::threads()) and those of
  /// them that did at least one run.
  EnsembleStatistics this_rank;
};

/// An Ensemble over the ranks of an MPI communicator (default MPI_COMM_WORLD). The user
/// initializes MPI before constructing one and finalizes it after the last call.
template <class SceneT, class MakeIntegrator> class MpiEnsemble {
 public:
  using Local = Ensemble<SceneT, MakeIntegrator>;
  /// A RunError's message is cut to this many characters for the transfer to rank 0.
  static constexpr std::size_t kMaxMessage = detail::kMpiMaxMessage;

  /// Collective in effect: every rank of `comm` constructs one. The scene must outlive it.
  /// \throws std::logic_error if MPI is not initialized or already finalized, or if threads != 1
  ///         and MPI was initialized without MPI_THREAD_FUNNELED (or higher);
  ///         std::invalid_argument for MPI_COMM_NULL, an intercommunicator or bad options.
  MpiEnsemble(const SceneT& scene, MakeIntegrator make, EnsembleOptions options = {},
              MPI_Comm comm = MPI_COMM_WORLD)
      : local_(scene, std::move(make), options), comm_(detail::mpi_comm(comm, options.threads)) {}
  MpiEnsemble(SceneT&&, MakeIntegrator, EnsembleOptions = {}, MPI_Comm = MPI_COMM_WORLD) = delete;

  /// Ensemble::integrate over the ranks. Collective: every rank calls it, with the same arguments.
  /// \returns at rank 0, one RunOutcome per run in run order (each R bitwise the one-process
  ///          Ensemble's); at the other ranks, an empty vector.
  /// \throws on every rank: std::invalid_argument for bad output times, arguments that differ
  ///         between ranks, or runs * sizeof(R) over INT_MAX bytes (MPI's counts; use fold);
  ///         std::runtime_error for a failure outside the runs on any rank.
  template <class R, class Initial, class Times, class Observer>
  std::vector<RunOutcome<R>> integrate(std::size_t runs, Initial&& initial, double t0,
                                       const Times& times, Observer&& observe) const {
    // One gather of all the runs: runs (at least 1) results at once.
    detail::mpi_agree<R>(comm_, runs, std::max<std::size_t>(runs, 1), t0, times);
    std::vector<RunOutcome<R>> out;
    MpiEnsembleStatistics stats = started(runs);
    local_.with_pool(
        [&](Pool& pool) { out = run_block<R>(pool, 0, runs, initial, t0, times, observe, stats); });
    stats_ = std::move(stats);
    return out;
  }

  /// Ensemble::fold over the ranks: the runs are done `block` at a time, each block spread over
  /// the ranks and its results folded at rank 0 in run order, so the value is the one-process
  /// Ensemble::fold's to the bit, for any number of ranks and threads. Collective.
  /// \returns at rank 0 the folded value, the count and the errors in run order; at the other
  ///          ranks {init, {}, 0}.
  /// \throws as integrate(), with block instead of runs in the size check, and for block == 0.
  template <class R, class T, class Initial, class Times, class Observer, class Fold>
  FoldedRuns<T> fold(std::size_t runs, Initial&& initial, double t0, const Times& times,
                     Observer&& observe, T init, Fold&& combine, std::size_t block = 4096) const {
    detail::mpi_agree<R>(comm_, runs, block, t0, times);
    FoldedRuns<T> folded{std::move(init), {}, 0};
    MpiEnsembleStatistics stats = started(runs);
    local_.with_pool([&](Pool& pool) {  // one integrator per thread for all blocks
      for (std::size_t first = 0; first < runs; first += block) {
        const std::size_t last = std::min(runs, first + block);
        std::vector<RunOutcome<R>> out =
            run_block<R>(pool, first, last, initial, t0, times, observe, stats);
        for (std::size_t k = 0; k < out.size(); ++k) {  // empty except at rank 0
          if (out[k].ok()) {
            folded.value = combine(std::move(folded.value), first + k, out[k].value());
            ++folded.completed;
          } else {
            folded.errors.push_back(out[k].error());
          }
        }
      }
    });
    stats_ = std::move(stats);
    return folded;
  }

  /// The runs [begin, end) that `rank` does of an ensemble of `runs` runs (integrate; fold cuts
  /// each of its blocks the same way).
  [[nodiscard]] std::pair<std::size_t, std::size_t> runs_of_rank(std::size_t runs, int rank) const {
    return detail::mpi_block(runs, rank, comm_.ranks);
  }
  [[nodiscard]] int rank() const { return comm_.rank; }
  [[nodiscard]] int ranks() const { return comm_.ranks; }
  [[nodiscard]] MPI_Comm communicator() const { return comm_.comm; }
  [[nodiscard]] const SceneT& scene() const { return local_.scene(); }
  [[nodiscard]] const EnsembleOptions& options() const { return local_.options(); }
  /// What the last call that finished ran (zeros before the first; a call that threw leaves the
  /// previous one's).
  [[nodiscard]] MpiEnsembleStatistics statistics() const { return stats_; }

 private:
  using Slot = typename Local::Slot;
  using Pool = typename Local::Pool;

  /// The statistics of a call of `runs` runs, before any run.
  MpiEnsembleStatistics started(std::size_t runs) const {
    MpiEnsembleStatistics s;
    s.runs = runs;
    s.ranks = comm_.ranks;
    s.runs_per_rank.assign(static_cast<std::size_t>(comm_.ranks), 0);
    s.this_rank.threads = local_.threads();
    return s;
  }

  /// Runs [first, last) over the ranks, this rank's part on its threads (detail::mpi_run_block),
  /// counted into stats.
  template <class R, class Initial, class Times, class Observer>
  std::vector<RunOutcome<R>> run_block(Pool& pool, std::size_t first, std::size_t last,
                                       Initial& initial, double t0, const Times& times,
                                       Observer& observe, MpiEnsembleStatistics& stats) const {
    for (int r = 0; r < comm_.ranks; ++r) {
      const auto [b, e] = detail::mpi_block(last - first, r, comm_.ranks);
      stats.runs_per_rank[static_cast<std::size_t>(r)] += e - b;
      if (r == comm_.rank) {
        stats.this_rank.runs += e - b;
      }
    }
    return detail::mpi_run_block<R>(
        comm_, first, last,
        [&](std::size_t b, std::size_t e, std::vector<RunOutcome<R>>& mine) {
          const int used = pool.for_each(b, e, [&](Slot& integrator, std::size_t i) {
            mine[i - b] = local_.template run<R>(integrator, i, initial, t0, times, observe);
          });
          stats.this_rank.threads_used = std::max(stats.this_rank.threads_used, used);
        },
        stats.this_rank.failed, stats.failed);
  }

  Local local_;
  detail::MpiComm comm_;
  /// The last call's; calls are collective, made by one thread of each rank (MPI's rule for a
  /// communicator), so no lock.
  mutable MpiEnsembleStatistics stats_;
};

/// integrate_variants (variants.hpp: a scene per run) over the ranks of `comm`: run i builds its
/// scene, make_scene(i), on the rank that runs it. Collective, with MpiEnsemble::integrate's
/// contract: at rank 0 one RunOutcome per run in run order, each R bitwise the one-process
/// integrate_variants' (R trivially copyable); an empty vector elsewhere; the same throws.
template <class R, class MakeScene, class MakeIntegrator, class Times, class Observer>
std::vector<RunOutcome<R>> mpi_integrate_variants(std::size_t runs, MakeScene&& make_scene,
                                                  MakeIntegrator&& make_integrator, double t0,
                                                  const Times& times, Observer&& observe,
                                                  const EnsembleOptions& options = {},
                                                  MPI_Comm comm = MPI_COMM_WORLD) {
  validate(options);
  const detail::MpiComm c = detail::mpi_comm(comm, options.threads);
  detail::mpi_agree<R>(c, runs, std::max<std::size_t>(runs, 1), t0, times);
  struct NoWorker {};
  RunPool<NoWorker> pool(options);
  std::size_t failed_here = 0, failed_all = 0;  // not reported: the outcomes say it
  return detail::mpi_run_block<R>(
      c, 0, runs,
      [&](std::size_t b, std::size_t e, std::vector<RunOutcome<R>>& mine) {
        pool.for_each(b, e, [&](NoWorker&, std::size_t i) {
          mine[i - b] = detail::variant_run<R>(i, make_scene, make_integrator, t0, times, observe);
        });
      },
      failed_here, failed_all);
}

}  // namespace tumble
