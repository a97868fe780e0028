#pragma once
// tumble::Cvode: a generic C++ front end to SUNDIALS CVODE for y' = f(t, y), y in R^n.
//
// CVODE integrates with variable-order, variable-step linear multistep methods: Adams-Moulton
// (orders 1-12, nonstiff, here with fixed-point iteration) or BDF (orders 1-5, stiff, here with
// Newton iteration and a dense, band or matrix-free GMRES linear solver). Source: the CVODE user
// guide (SUNDIALS 6.4 / 7.x), "Mathematical considerations" and "Using CVODE for IVP solution".
//
// This header holds the Cvode<System> class only; the rest is one concern per header:
//   integrate/system.hpp             what a system provides: CvodeSystem and the optional members
//   integrate/options.hpp            CvodeOptions, CvodeStatistics, validate()
//   integrate/errors.hpp             IntegrationError, RecoverableError
//   integrate/detail/cvode_core.hpp  the CVODE machinery: setup, callbacks, stepping, errors
//
// Callbacks never let an exception cross into C: a RecoverableError, or a non-finite derivative,
// makes CVODE retry with a smaller step; any other exception stops it, and advance()/step() throw
// an IntegrationError whose cause() is the original exception.
//
// \warning The state views handed to callbacks are only valid during the call.
// \warning If on_root() or on_step() changes y it must return true: the integrator then restarts
//          CVODE from the changed state (CVodeReInit). A change without `true` is overwritten.

#include <concepts>
#include <initializer_list>
#include <memory>
#include <ranges>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

#include <Eigen/Core>

#include "tumble/integrate/detail/cvode_core.hpp"
#include "tumble/integrate/errors.hpp"
#include "tumble/integrate/options.hpp"
#include "tumble/integrate/system.hpp"

namespace tumble {

/// CVODE integrator of a system y' = f(t, y) (see CvodeSystem and the optional
/// members in integrate/system.hpp).
///
/// `System` is held by value (the integrator owns the system; reach it through system()), or by
/// reference when instantiated as Cvode<MySystem&>. Cvode is move-only; a moved-from Cvode may
/// only be destroyed or assigned to.
template <class System>
requires CvodeSystem<System>
class Cvode {
 public:
  using SystemType = std::remove_cvref_t<System>;

  /// Validates the options and the initial state (std::invalid_argument on a bad one), then
  /// creates and initializes CVODE at (t0, y0).
  Cvode(System system, double t0, const Eigen::Ref<const Eigen::VectorXd>& y0,
        CvodeOptions options = {}) {
    const int n = static_cast<int>(std::as_const(system).size());
    validate(options, n, t0);
    if (y0.size() != n) {
      throw std::invalid_argument("tumble::Cvode: the initial state has size " +
                                  std::to_string(y0.size()) + " but the system has size " +
                                  std::to_string(n));
    }
    if (!y0.allFinite()) {
      throw std::invalid_argument("tumble::Cvode: the initial state has a non-finite component");
    }
    if (options.projection && !CvodeHasProjection<SystemType>) {
      throw std::invalid_argument("tumble::CvodeOptions: 'projection' is on but the system has no "
                                  "project(t, y, corr, epsProj, err)");
    }
    if constexpr (CvodeHasRoots<SystemType>) {
      const int count = static_cast<int>(std::as_const(system).root_count());
      if (count < 0) {
        throw std::invalid_argument("tumble::Cvode: root_count() must be >= 0 (got " +
                                    std::to_string(count) + ")");
      }
      if constexpr (CvodeHasRootDirections<SystemType>) {
        int k = 0;
        for (const auto& d : std::as_const(system).root_directions()) {
          const int v = static_cast<int>(d);
          if (v < -1 || v > 1) {
            throw std::invalid_argument(
                "tumble::Cvode: root_directions() entries must be -1, 0 or +1 (got " +
                std::to_string(v) + ")");
          }
          ++k;
        }
        if (k != count) {
          throw std::invalid_argument("tumble::Cvode: root_directions() has " + std::to_string(k) +
                                      " entries for " + std::to_string(count) + " root functions");
        }
      }
    }
    core_ = std::make_unique<detail::CvodeCore<System>>(std::forward<System>(system), t0, y0,
                                                        std::move(options));
  }

  Cvode(const Cvode&) = delete;
  Cvode& operator=(const Cvode&) = delete;
  Cvode(Cvode&&) noexcept = default;
  Cvode& operator=(Cvode&&) noexcept = default;
  ~Cvode() = default;

  /// Integrates to t_out (CV_NORMAL: CVODE steps past t_out and interpolates) and returns the
  /// state there. Events on the way call on_root(). t_out must not be behind time() nor after
  /// the stop time. Throws IntegrationError when CVODE fails.
  ConstVectorMap advance(double t_out) { return core_->advance(t_out); }

  /// Takes one internal step (CV_ONE_STEP), or stops at a root or the stop time; returns the
  /// time reached. The state there is state().
  double step() { return core_->step(); }

  /// Advances to each output time in turn and calls observer(t, state()) there. The times must
  /// be increasing, the first not behind time() (it may equal it); all are checked before
  /// integrating (std::invalid_argument).
  template <class Times, class Observer>
  requires std::ranges::forward_range<const Times&> &&
      std::convertible_to < std::ranges::range_value_t<const Times&>,
  double > &&std::invocable<Observer&, double, ConstVectorMap> void integrate(const Times& times,
                                                                              Observer&& observer) {
    core_->integrate(times, observer);
  }
  template <class Observer>
  requires std::invocable<Observer&, double, ConstVectorMap>
  void integrate(std::initializer_list<double> times, Observer&& observer) {
    core_->integrate(times, observer);
  }

  /// The current state (a view of CVODE's vector; valid until the next call on this Cvode).
  [[nodiscard]] ConstVectorMap state() const noexcept { return core_->state(); }
  /// The current time.
  [[nodiscard]] double time() const noexcept { return core_->time(); }
  /// Restarts the integration from (t, y) (CVodeReInit), e.g. after the user changed the state.
  void reset(double t, const Eigen::Ref<const Eigen::VectorXd>& y) { core_->reset(t, y); }
  /// Counters since construction, summed over reinitializations.
  [[nodiscard]] CvodeStatistics statistics() const { return core_->statistics(); }

  [[nodiscard]] const CvodeOptions& options() const noexcept { return core_->options(); }
  [[nodiscard]] int size() const noexcept { return core_->size(); }
  [[nodiscard]] SystemType& system() noexcept { return core_->system(); }
  [[nodiscard]] const SystemType& system() const noexcept { return core_->system(); }
  /// CVODE's memory block, for CVodeSet*/CVodeGet* calls tumble does not wrap.
  [[nodiscard]] void* cvode_memory() const noexcept { return core_->memory(); }

 private:
  std::unique_ptr<detail::CvodeCore<System>> core_;
};

}  // namespace tumble
