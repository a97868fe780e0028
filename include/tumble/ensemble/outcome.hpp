#pragma once
// The result of one run of an ensemble: the value its observer built, or the error that stopped
// it (the run's index and the exception's message). A failed run does not stop the others.

#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace tumble {

/// Why a run of an ensemble failed: its index and what() of the exception it threw (from the
/// integrator, the scene's loads or events, or the user's initial-state or observer callables).
struct RunError {
  std::size_t run = 0;
  std::string message;
};

/// One run's result R, or its RunError (C++23's std::expected, reduced to what an ensemble needs).
template <class R> class RunOutcome {
 public:
  /// Not run (yet): neither a value nor an error. An ensemble's results never hold one.
  RunOutcome() = default;
  explicit RunOutcome(R value) : v_(std::in_place_index<1>, std::move(value)) {}
  explicit RunOutcome(RunError error) : v_(std::in_place_index<2>, std::move(error)) {}

  /// True when the run finished and has a value.
  [[nodiscard]] bool ok() const noexcept { return v_.index() == 1; }
  [[nodiscard]] bool failed() const noexcept { return v_.index() == 2; }

  /// The run's value. \throws std::logic_error naming the run's error if it has none.
  [[nodiscard]] const R& value() const {
    if (!ok()) {
      throw std::logic_error(failed() ? "tumble::RunOutcome: run " + std::to_string(error().run) +
                                            " failed: " + error().message
                                      : std::string("tumble::RunOutcome: the run has no result"));
    }
    return std::get<1>(v_);
  }
  /// The run's error. \throws std::logic_error if it did not fail.
  [[nodiscard]] const RunError& error() const {
    if (!failed()) {
      throw std::logic_error("tumble::RunOutcome: the run did not fail");
    }
    return std::get<2>(v_);
  }

 private:
  std::variant<std::monostate, R, RunError> v_;
};

/// What Ensemble::fold returns: the values of the successful runs folded in run order, how many
/// there were, and the errors of the others, in run order.
template <class T> struct FoldedRuns {
  T value;
  std::vector<RunError> errors;
  std::size_t completed = 0;
};

/// The errors of the failed runs, in run order.
template <class R> std::vector<RunError> failures(const std::vector<RunOutcome<R>>& outcomes) {
  std::vector<RunError> errors;
  for (const auto& o : outcomes) {
    if (o.failed()) {
      errors.push_back(o.error());
    }
  }
  return errors;
}

/// Folds the values of the successful runs in run order, acc = fold(acc, run, value), whatever
/// the threads that computed them: the same sum to the last bit for any thread count.
template <class R, class T, class Fold>
T fold_runs(const std::vector<RunOutcome<R>>& outcomes, T init, Fold&& fold) {
  for (std::size_t i = 0; i < outcomes.size(); ++i) {
    if (outcomes[i].ok()) {
      init = fold(std::move(init), i, outcomes[i].value());
    }
  }
  return init;
}

}  // namespace tumble
