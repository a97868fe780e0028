#pragma once
// What the explicit integrator (explicit_integrator.hpp) knows about its own progress, and how it
// says why it stopped: the attempts one advance() or one stiffness window has spent (StepRun),
// the stiffness test on them, and the two failures they end in (a stiff scene, a spent step
// budget) with their messages. Kept apart from the step loop, which calls them only when a window
// is full or a budget is spent.

#include <string>

#include "tumble/core/format.hpp"
#include "tumble/integrate/errors.hpp"

namespace tumble::detail {

/// A spent budget is reported as stiffness when the mean step h and the estimated largest
/// eigenvalue rho of the Jacobian have h rho above this (the steps sit near the stability bound
/// of the method, about 3 to 5 along the negative real axis for these pairs, instead of being
/// set by the accuracy of the slow motion) and at least kStiffRejections of the attempts failed
/// the error test (the controller keeps stepping over the stability bound).
inline constexpr double kStiffHRho = 1.0;
inline constexpr double kStiffRejections = 0.1;

/// The step attempts since t_start: for the step budget (per advance or output interval) and
/// the stiffness test (per window).
struct StepRun {
  double t_start = 0.0;
  long attempts = 0;  ///< step attempts
  long accepted = 0;  ///< accepted steps
  long rejected = 0;  ///< of which failed Odeint's error test
  long relaxed = 0;   ///< accepted with the error test relaxed (a mechanism, near a singularity)
  int excused = 0;    ///< stiffness windows in a row that drew no verdict (excused_window)

  /// The mean accepted step from t_start to t (0 before the first).
  [[nodiscard]] double mean_step(double t) const {
    return accepted > 0 ? (t - t_start) / static_cast<double>(accepted) : 0.0;
  }
};

/// At most this many stiffness windows in a row within one run (an output interval, or an
/// advance) draw no verdict for their relaxed steps.
inline constexpr int kRelaxedWindows = 8;

/// Whether the stiffness window `window`, within `run`, draws no verdict: it has steps whose error
/// test was relaxed near a singular position of a mechanism's joints, where the rejections and
/// the Jacobian's modulus measure the constraint solve's conditioning, not stiffness. Counted in
/// run.excused, so that a run held at a crossing, making no way, still gets the verdict after
/// kRelaxedWindows such windows (never a hang).
inline bool excused_window(const StepRun& window, StepRun& run) {
  if (window.relaxed > 0 && run.excused < kRelaxedWindows) {
    ++run.excused;
    return true;
  }
  run.excused = 0;
  return false;
}

/// True when the attempts of r, which reached t, look like those of an explicit method on a stiff
/// scene: at least kStiffRejections of them failed the error test and the mean step h has
/// h rho > kStiffHRho, rho = spectral_radius() (called only then). Sets h rho.
template <class SpectralRadius>
bool looks_stiff(const StepRun& r, double t, SpectralRadius&& spectral_radius, double& h_rho) {
  h_rho = 0.0;
  if (static_cast<double>(r.rejected) < kStiffRejections * static_cast<double>(r.attempts)) {
    return false;  // no spectral radius needed: the test costs nothing
  }
  h_rho = r.mean_step(t) * spectral_radius();
  return h_rho > kStiffHRho;
}

/// The failure of a stiffness window (OdeintOptions::stiffness_window) that looks stiff at t.
[[noreturn]] inline void throw_stiff_window(const StepRun& window, double t, double h_rho,
                                            double t_out) {
  throw StiffSceneError(
      "tumble::OdeintIntegrator::advance: the scene looks stiff at t = " + format_double(t) +
          ": of " + std::to_string(window.attempts) + " step attempts since t = " +
          format_double(window.t_start) + ", " + std::to_string(window.rejected) +
          " failed the error test, and the mean step h times the largest eigenvalue modulus "
          "rho of the Jacobian is h rho = " +
          format_double(h_rho) +
          ": the steps are held at the method's stability bound, not set by the accuracy "
          "asked for (t_out = " +
          format_double(t_out) +
          "). Integrate it with tumble::SceneIntegrator and CvodeMethod::bdf (BDF, "
          "implicit), or let tumble::AutoIntegrator switch",
      t);
}

/// The failure of a spent step budget (OdeintOptions::max_steps) at t: StiffSceneError when the
/// run looks stiff (h_rho from looks_stiff), ExplicitIntegrationError otherwise.
[[noreturn]] inline void throw_out_of_budget(const StepRun& run, long max_steps, double t,
                                             double t_out, bool stiff, double h_rho) {
  const double mean_h = run.mean_step(t);
  const std::string what =
      "tumble::OdeintIntegrator::advance: " + std::to_string(run.attempts) + " step attempts (" +
      std::to_string(run.rejected) +
      " failed the error test; OdeintOptions::max_steps = " + std::to_string(max_steps) +
      ") took t from " + format_double(run.t_start) + " only to " + format_double(t) +
      " of t_out = " + format_double(t_out) + ", with steps of " + format_double(mean_h) +
      " on average";
  if (stiff) {
    throw StiffSceneError(
        what + ". The scene looks stiff: the Jacobian has an eigenvalue of modulus " +
            format_double(h_rho / mean_h) +
            ", so the steps are held near the method's stability bound (h rho = " +
            format_double(h_rho) +
            "), not set by the accuracy asked for, and the controller "
            "keeps stepping over it. Integrate it with tumble::SceneIntegrator and "
            "CvodeMethod::bdf (BDF, implicit)",
        t);
  }
  throw ExplicitIntegrationError(what + ". Raise OdeintOptions::max_steps for longer intervals "
                                        "(0: no limit), or integrate to intermediate times",
                                 IntegrationFailure::step_budget, t);
}

/// The stiffness test (looks_stiff) at t on a full window's attempts, or (`spent`) on those of
/// `run`, whose step budget max_steps is spent: throws StiffSceneError for a window that looks
/// stiff, throw_out_of_budget's failure for a spent budget, and otherwise starts the next window.
/// `excusable`: a window with relaxed steps (a mechanism's) may draw no verdict (excused_window).
template <class SpectralRadius>
void stiffness_test(StepRun& window, StepRun& run, double t, double t_out, long max_steps,
                    bool spent, bool excusable, SpectralRadius&& spectral_radius) {
  if (excusable && !spent && excused_window(window, run)) {
    window = StepRun{.t_start = t};
    return;
  }
  double h_rho = 0.0;
  const bool stiff = looks_stiff(spent ? run : window, t, spectral_radius, h_rho);
  if (spent) {
    throw_out_of_budget(run, max_steps, t, t_out, stiff, h_rho);
  }
  if (stiff) {
    throw_stiff_window(window, t, h_rho, t_out);
  }
  window = StepRun{.t_start = t};
}

}  // namespace tumble::detail
