// Consumer check for tumble::ensemble (oneTBB): builds against the installed package and runs an
// ensemble on two threads with a stand-in integrator of y' = -k y, whose exact solution
// y0 exp(-k t) is also the expectation: every run's result equal to it (the same expression, so
// to the bit), and the one run whose initial state the integrator refuses reported with its index.
// Exit status 0 when every check holds.

#include <cmath>
#include <cstddef>
#include <cstdio>
#include <stdexcept>
#include <vector>

#include "tumble/ensemble/ensemble.hpp"

namespace {

struct Decay {  // the "scene": the model, shared read-only
  double k = 0.5;
};

/// Advances y' = -k y exactly; refuses a negative initial state.
class DecayIntegrator {
 public:
  DecayIntegrator(const Decay& d, double t0, const tumble::SceneState& s0) : k_(d.k) {
    reset(t0, s0);
  }
  void advance(double t) { state_.y[0] = y0_ * std::exp(-k_ * (t - t0_)); }
  const tumble::SceneState& state() const { return state_; }
  /// observer(t, state) at each output time (what an Ensemble's run calls).
  template <class Times, class Observer> void integrate(const Times& times, Observer&& observer) {
    for (const double t : times) {
      advance(t);
      observer(t, state_);
    }
  }
  void reset(double t0, const tumble::SceneState& s0) {
    if (s0.y[0] < 0.0) {
      throw std::invalid_argument("negative initial state");
    }
    t0_ = t0;
    y0_ = s0.y[0];
    state_ = s0;
  }

 private:
  double k_, t0_ = 0.0, y0_ = 0.0;
  tumble::SceneState state_;
};

}  // namespace

int main() {
  const Decay decay;
  const auto make = [](const Decay& d, double t0, const tumble::SceneState& s0) {
    return DecayIntegrator(d, t0, s0);
  };
  const auto initial = [](std::size_t i) {
    tumble::SceneState s;
    s.y = Eigen::VectorXd::Constant(1, i == 7 ? -1.0 : static_cast<double>(i));
    return s;
  };
  const std::vector<double> times{1.0, 2.0};
  const tumble::Ensemble ensemble(decay, make, {.threads = 2});
  const auto runs = ensemble.integrate<double>(
      100, initial, 0.0, times,
      [](double& y, std::size_t, double, const tumble::SceneState& s) { y = s.y[0]; });
  int failed = 0;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const bool ok = i == 7 ? runs[i].failed() && runs[i].error().run == 7
                           : runs[i].ok() && runs[i].value() ==
                                                 static_cast<double>(i) * std::exp(-decay.k * 2.0);
    failed += ok ? 0 : 1;
  }
  std::printf("tumble::ensemble: %zu runs, %d wrong\n", runs.size(), failed);
  return failed == 0 ? 0 : 1;
}
