#pragma once
// Exceptions of tumble's time integration, shared by both integrators (CVODE's SceneIntegrator and
// Cvode<System>, Boost.Odeint's OdeintIntegrator) and the front door (integrate/auto.hpp).
//
// This header needs neither SUNDIALS, Boost nor Eigen, so that a system written against the
// Eigen-only core (a scene's right-hand side) can throw RecoverableError without depending on an
// integrator.
//
//  - RecoverableError: thrown by a system's right-hand side (or Jacobian, projection,
//    preconditioner) when it was asked to evaluate at a state it cannot handle, e.g. a trial
//    state near a parameterization's singularity. The integrator retries with a smaller step
//    (CVODE user guide, "ODE right-hand side": a positive return value is a recoverable error).
//  - IntegrationError: an integrator could not go on. Every integrator throws it or a class
//    derived from it, with the same reason() codes and time(), so one catch clause serves both:
//      CvodeError                CVODE stopped with a failure flag (flag(), flag_name())
//      ExplicitIntegrationError  the explicit integrator stopped
//      StiffSceneError           ... because the scene looks stiff (it names the remedy, BDF)
//    Bad input (options, states, output times) is std::invalid_argument before anything is
//    integrated, in both. An exception thrown by a callback the integrator calls inside a step
//    (a scene's load or force: "rhs()", an event function: "roots()") stops both alike:
//    reason() callback, cause() that exception, what() "<where> threw at t = <t>: <its what()>"
//    (detail/callback_error.hpp). The user's observer and an event's action run between steps:
//    their exceptions arrive unchanged, in both.

#include <exception>
#include <stdexcept>
#include <string>
#include <utility>

namespace tumble {

/// Thrown by a system's callback to ask the integrator to retry with a smaller step.
class RecoverableError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Why an integration stopped: the same codes for every integrator.
enum class IntegrationFailure {
  step_budget,  ///< the step budget of one advance (max_steps) was spent
  step_size,    ///< the step size fell to the rounding level of t (a singularity, a stall)
  stiff,        ///< an explicit method met a stiff scene (StiffSceneError): use BDF
  error_test,   ///< the error test failed repeatedly at the minimum step (CVODE)
  convergence,  ///< the Newton or fixed-point iteration did not converge (CVODE)
  callback,     ///< a callback (right-hand side, Jacobian, event, ...) failed: see cause()
  solver,       ///< another failure of the solver (CVODE's linear solver, projection, ...)
};

/// An integrator stopped: what() says where and why; reason() classifies it, time() is the
/// time it had reached, cause() the exception a callback threw when that is what stopped it.
class IntegrationError : public std::runtime_error {
 public:
  IntegrationError(const std::string& what, IntegrationFailure reason, double time,
                   std::exception_ptr cause = nullptr)
      : std::runtime_error(what), reason_(reason), time_(time), cause_(std::move(cause)) {}

  [[nodiscard]] IntegrationFailure reason() const noexcept { return reason_; }
  /// The time the integrator had reached when it stopped.
  [[nodiscard]] double time() const noexcept { return time_; }
  /// The exception a callback threw, when that is what stopped the integration (else null).
  [[nodiscard]] const std::exception_ptr& cause() const noexcept { return cause_; }

 private:
  IntegrationFailure reason_;
  double time_;
  std::exception_ptr cause_;
};

/// CVODE returned a failure flag: the flag and its name beside the shared reason().
class CvodeError : public IntegrationError {
 public:
  CvodeError(const std::string& what, int flag, std::string flag_name, IntegrationFailure reason,
             double time, std::exception_ptr cause = nullptr)
      : IntegrationError(what, reason, time, std::move(cause)),
        flag_(flag),
        flag_name_(std::move(flag_name)) {}

  /// The CVODE return flag (negative), e.g. CV_TOO_MUCH_WORK == -1.
  [[nodiscard]] int flag() const noexcept { return flag_; }
  /// The flag's name as CVODE spells it, e.g. "CV_TOO_MUCH_WORK".
  [[nodiscard]] const std::string& flag_name() const noexcept { return flag_name_; }

 private:
  int flag_;
  std::string flag_name_;
};

/// The explicit integrator (OdeintIntegrator) stopped.
class ExplicitIntegrationError : public IntegrationError {
 public:
  using IntegrationError::IntegrationError;
};

/// The explicit integrator's steps were held at its stability bound with frequent rejections:
/// the scene looks stiff. what() names the remedy, the CVODE SceneIntegrator with BDF; the
/// front door (integrate/auto.hpp) switches to it by itself.
class StiffSceneError : public ExplicitIntegrationError {
 public:
  StiffSceneError(const std::string& what, double time)
      : ExplicitIntegrationError(what, IntegrationFailure::stiff, time) {}
};

}  // namespace tumble
