#pragma once
// Ensemble: many runs of one scene, across cores. The scene is the model, shared read-only by
// every run; each run has its own initial state and its own result, kept per run:
//
//   auto make = [](const Scene& s, double t0, const SceneState& y0) {
//     return OdeintIntegrator<Scene, 13>(s, t0, y0, options);    // or SceneIntegrator (CVODE)
//   };
//   Ensemble ensemble(scene, make, {.threads = 2});
//   std::vector<RunOutcome<double>> r = ensemble.integrate<double>(
//       n, [&](std::size_t i) { return dispersed_state(i); }, 0.0, times,
//       [](double& err, std::size_t i, double t, const SceneState& s) { err = ...; });
//
// - Any integrator of the library (EnsembleIntegrator, detail/run.hpp), made by the user's
//   factory make(scene, t0, s0): its options, its method, its size template argument stay the
//   user's. A run is the integrator's own integrate() over the output times: it computes what a
//   serial integrate() computes, to the bit, whatever the method and the output times.
// - One integrator per thread, kept from one call to the next: each thread makes one on its
//   first run and reset()s it for the next, so a run costs no construction (no CVODE memory, no
//   Odeint buffers) and allocates only what reset() does; after a failed run the thread's
//   integrator is dropped and made anew. They live as long as the ensemble: the factory is called
//   once per thread, not once per call (an ensemble whose factory should make other integrators
//   is a new Ensemble). A call made while another call of the same ensemble runs (from another
//   thread) makes integrators of its own.
// - A factory that takes the run's index, make(scene, t0, s0, run), gives each run integrator
//   options of its own (a step budget, a tolerance): it is called for every run, and the run's
//   integrator lives for that run only.
// - The observer is called at each output time with the run's result R (value-initialized at
//   the run's start), the run's index, the time, the state and, if it takes a fifth argument,
//   the scene (for the observables, scene/observables.hpp); what it keeps in R is all that is
//   kept of a run, so memory grows with the results, not with the steps or the states.
// - Results do not depend on the thread count, to the bit: a run's result depends only on the
//   scene, its initial state, the factory and the times (reset() leaves nothing of an earlier
//   run), each run writes only its own slot, and fold_runs (outcome.hpp) combines them in run
//   order. Ensemble::fold folds them block by block, in run order too, for ensembles whose
//   results are not all kept.
// - A run that throws (the integrator, a load, an event, initial(i) or the observer) gets a
//   RunError with its index and message; the other runs go on and keep their results.
// - threads() says how many threads the runs are spread over (EnsembleOptions::threads, at most
//   the cores the process may use); statistics() what the last call ran.
// The factory, initial(i), the observer and the scene's loads and events are called concurrently
// from several threads: they must only read shared data. Per-run scenes (dispersed inertia,
// loads): variants.hpp.

#include <algorithm>
#include <cstddef>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <vector>

#include "tumble/ensemble/detail/run.hpp"
#include "tumble/ensemble/options.hpp"
#include "tumble/ensemble/outcome.hpp"
#include "tumble/ensemble/parallel.hpp"
#include "tumble/scene/state.hpp"

namespace tumble {

template <class SceneT, class MakeIntegrator> class MpiEnsemble;

/// What the last call of an Ensemble (integrate or fold) ran.
struct EnsembleStatistics {
  std::size_t runs = 0;    ///< runs done
  std::size_t failed = 0;  ///< of which failed (a RunError)
  int threads = 0;         ///< the threads the runs were spread over (Ensemble::threads())
  int threads_used = 0;    ///< of which did at least one run (fewer when TBB gave fewer)
};

/// One scene, many runs. MakeIntegrator: make(const SceneT&, double t0, const SceneState& s0)
/// returns an integrator of the scene starting at (t0, s0); or make(..., std::size_t run), which
/// is called for every run (per-run options).
template <class SceneT, class MakeIntegrator> class Ensemble {
 public:
  using Integrator = detail::FactoryIntegrator<MakeIntegrator, SceneT>;
  static_assert(EnsembleIntegrator<Integrator>,
                "the factory must return an integrator with integrate(times, observer) and "
                "reset(t, state)");
  /// True when the factory takes the run index: an integrator per run, not per thread.
  static constexpr bool per_run_factory = detail::factory_takes_run<MakeIntegrator, SceneT>;

  /// The scene must outlive the ensemble; it is only read.
  Ensemble(const SceneT& scene, MakeIntegrator make, EnsembleOptions options = {})
      : scene_(&scene), make_(std::move(make)), options_(options) {
    validate(options_);
  }
  Ensemble(SceneT&&, MakeIntegrator, EnsembleOptions = {}) = delete;
  /// A copy has the scene, the factory and the options, and integrators of its own.
  Ensemble(const Ensemble& o) : scene_(o.scene_), make_(o.make_), options_(o.options_) {}
  Ensemble& operator=(const Ensemble& o) {
    if (this != &o) {
      scene_ = o.scene_;
      make_ = o.make_;
      options_ = o.options_;
      kept_ = std::make_unique<Kept>();
    }
    return *this;
  }
  Ensemble(Ensemble&&) noexcept = default;
  Ensemble& operator=(Ensemble&&) noexcept = default;
  ~Ensemble() = default;

  /// Runs 0, ..., runs-1, run i from (t0, initial(i)) over `times` (finite, non-decreasing, not
  /// before t0) with its integrator's integrate(), calling observe(R& result, std::size_t run,
  /// double t, const SceneState& [, const SceneT&]) at each. initial(i) returns the run's
  /// SceneState (a copy or a reference), e.g. the scene's initial state with dispersed rates.
  ///
  /// \returns one RunOutcome per run, in run order: its R, or its RunError.
  /// \throws std::invalid_argument for bad output times (before any run).
  template <class R, class Initial, class Times, class Observer>
  std::vector<RunOutcome<R>> integrate(std::size_t runs, Initial&& initial, double t0,
                                       const Times& times, Observer&& observe) const {
    detail::check_output_times(t0, times);
    std::vector<RunOutcome<R>> out(runs);
    EnsembleStatistics stats{runs, 0, threads(), 0};
    with_pool([&](Pool& pool) {
      stats.threads_used = pool.for_each(0, runs, [&](Slot& integrator, std::size_t i) {
        out[i] = run<R>(integrator, i, initial, t0, times, observe);
      });
    });
    for (const RunOutcome<R>& o : out) {
      stats.failed += o.failed() ? 1 : 0;
    }
    record(stats);
    return out;
  }

  /// The runs of integrate(), their results folded as they come, acc = combine(acc, run, value),
  /// in run order (the same to the bit for any thread count), instead of kept: the runs are done
  /// `block` at a time, and only one block's results are held. For ensembles whose results
  /// together would not fit (a histogram, a mean and a maximum of 10^6 runs).
  ///
  /// \returns the folded value and the errors of the failed runs, in run order.
  template <class R, class T, class Initial, class Times, class Observer, class Fold>
  FoldedRuns<T> fold(std::size_t runs, Initial&& initial, double t0, const Times& times,
                     Observer&& observe, T init, Fold&& combine, std::size_t block = 4096) const {
    detail::check_output_times(t0, times);
    if (block == 0) {
      throw std::invalid_argument("tumble::Ensemble::fold: block must be >= 1");
    }
    FoldedRuns<T> folded{std::move(init), {}, 0};
    std::vector<RunOutcome<R>> out(std::min(block, runs));
    EnsembleStatistics stats{runs, 0, threads(), 0};
    with_pool([&](Pool& pool) {  // one integrator per thread for all blocks
      for (std::size_t first = 0; first < runs; first += block) {
        const std::size_t last = std::min(runs, first + block);
        const int used = pool.for_each(first, last, [&](Slot& integrator, std::size_t i) {
          out[i - first] = run<R>(integrator, i, initial, t0, times, observe);
        });
        stats.threads_used = std::max(stats.threads_used, used);
        for (std::size_t i = first; i < last; ++i) {
          RunOutcome<R>& o = out[i - first];
          if (o.ok()) {
            folded.value = combine(std::move(folded.value), i, o.value());
            ++folded.completed;
          } else {
            folded.errors.push_back(o.error());
          }
          o = RunOutcome<R>();
        }
      }
    });
    stats.failed = folded.errors.size();
    record(stats);
    return folded;
  }

  [[nodiscard]] const SceneT& scene() const { return *scene_; }
  [[nodiscard]] const EnsembleOptions& options() const { return options_; }
  /// The threads the runs are spread over: EnsembleOptions::threads (0: TBB's choice), at most
  /// the cores this process may use (ensemble_threads, parallel.hpp).
  [[nodiscard]] int threads() const { return ensemble_threads(options_); }
  /// What the last call that finished ran (zeros before the first).
  [[nodiscard]] EnsembleStatistics statistics() const {
    if (!kept_) {
      return {};
    }
    const std::lock_guard lock(kept_->stats_mutex);
    return kept_->stats;
  }

 private:
  // The same runs over MPI ranks (mpi.hpp), each rank on this class's threads and runs.
  template <class, class> friend class MpiEnsemble;

  using Slot = std::optional<Integrator>;  ///< a thread's integrator, made on its first run
  using Pool = RunPool<Slot>;

  /// The threads' integrators, kept from one call to the next, and the last call's statistics.
  struct Kept {
    std::mutex mutex;  ///< held by the call using `pool`
    std::unique_ptr<Pool> pool;
    std::mutex stats_mutex;
    EnsembleStatistics stats;
  };

  /// f(pool) on the kept pool, or, while another call holds it (or after a move), on a pool of
  /// this call's own.
  template <class F> void with_pool(F&& f) const {
    std::unique_lock<std::mutex> lock;
    if (kept_) {
      lock = std::unique_lock<std::mutex>(kept_->mutex, std::try_to_lock);
    }
    if (lock.owns_lock()) {
      if (!kept_->pool) {
        kept_->pool = std::make_unique<Pool>(options_);
      }
      f(*kept_->pool);
    } else {
      Pool pool(options_);
      f(pool);
    }
  }

  void record(const EnsembleStatistics& stats) const {
    if (kept_) {
      const std::lock_guard lock(kept_->stats_mutex);
      kept_->stats = stats;
    }
  }

  /// Run i on the thread's integrator: reset to (t0, initial(i)), or made there on the thread's
  /// first run or after a failed one; with a factory that takes the run index, made for the run.
  template <class R, class Initial, class Times, class Observer>
  RunOutcome<R> run(Slot& integrator, std::size_t i, Initial& initial, double t0,
                    const Times& times, Observer& observe) const {
    return detail::guarded_run<R>(i, [&] {
      const auto& s0 = initial(i);  // a reference, or a temporary kept alive here
      if constexpr (per_run_factory) {
        Integrator own = detail::make_for_run(make_, *scene_, t0, s0, i);
        return detail::observe_run<R>(*scene_, own, i, times, observe);
      } else {
        try {
          if (integrator) {
            integrator->reset(t0, s0);
          } else {
            integrator.emplace(detail::make_for_run(make_, *scene_, t0, s0, i));
          }
          return detail::observe_run<R>(*scene_, *integrator, i, times, observe);
        } catch (...) {
          integrator.reset();  // nothing of a failed run is carried into the next
          throw;
        }
      }
    });
  }

  const SceneT* scene_;
  MakeIntegrator make_;
  EnsembleOptions options_;
  std::unique_ptr<Kept> kept_ = std::make_unique<Kept>();
};

}  // namespace tumble
