#pragma once
// Exceptions of tumble's time integration (include/tumble/integrate/cvode.hpp).
//
// This header needs neither SUNDIALS nor Eigen, so that a system written against the Eigen-only
// core (a scene's right-hand side) can throw RecoverableError without depending on CVODE.
//
//  - RecoverableError: thrown by a system's right-hand side (or Jacobian, projection,
//    preconditioner) when it was asked to evaluate at a state it cannot handle, e.g. a trial
//    state near a parameterization's singularity. CVODE then retries with a smaller step
//    (CVODE user guide, "ODE right-hand side": a positive return value is a recoverable error).
//  - IntegrationError: CVODE stopped with a failure flag. It carries the flag, its name
//    (CV_TOO_MUCH_WORK, ...), the time reached, and, when the failure was caused by an exception
//    thrown inside a callback, that exception (cause()).
//  - ExplicitIntegrationError: the explicit integrator (OdeintIntegrator, explicit_integrator.hpp)
//    could not go on: its step size fell to the rounding level of t, or one advance() used up its
//    step budget. StiffSceneError, derived from it, says that the budget was spent the way an
//    explicit method spends it on a stiff scene, and names the remedy (BDF).

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

/// CVODE returned a failure flag. what() names the flag, the time and the cause in words.
class IntegrationError : public std::runtime_error {
 public:
  IntegrationError(const std::string& what, int flag, std::string flag_name, double time,
                   std::exception_ptr cause = nullptr)
      : std::runtime_error(what),
        flag_(flag),
        flag_name_(std::move(flag_name)),
        time_(time),
        cause_(std::move(cause)) {}

  /// The CVODE return flag (negative), e.g. CV_TOO_MUCH_WORK == -1.
  [[nodiscard]] int flag() const noexcept { return flag_; }
  /// The flag's name as CVODE spells it, e.g. "CV_TOO_MUCH_WORK".
  [[nodiscard]] const std::string& flag_name() const noexcept { return flag_name_; }
  /// The time the integrator had reached when it failed.
  [[nodiscard]] double time() const noexcept { return time_; }
  /// The exception a callback threw, when that is what stopped the integration (else null).
  [[nodiscard]] const std::exception_ptr& cause() const noexcept { return cause_; }

 private:
  int flag_;
  std::string flag_name_;
  double time_;
  std::exception_ptr cause_;
};

/// The explicit integrator stopped: what() says where and why; time() is the time it reached.
class ExplicitIntegrationError : public std::runtime_error {
 public:
  ExplicitIntegrationError(const std::string& what, double time)
      : std::runtime_error(what), time_(time) {}
  /// The time the integrator had reached when it stopped.
  [[nodiscard]] double time() const noexcept { return time_; }

 private:
  double time_;
};

/// The explicit integrator spent its step budget with steps far shorter than the accuracy asks
/// for and frequent rejections: the scene looks stiff. what() names the remedy, the CVODE
/// SceneIntegrator with BDF.
class StiffSceneError : public ExplicitIntegrationError {
 public:
  using ExplicitIntegrationError::ExplicitIntegrationError;
};

}  // namespace tumble
