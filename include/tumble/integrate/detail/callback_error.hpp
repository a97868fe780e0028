#pragma once
// How an exception thrown by one of the scene's (or system's) callbacks stops an integration, in
// the same words for both integrators: the IntegrationError has reason() callback, time() the
// time the integrator had reached, cause() the exception itself, and what() says "<where> threw
// at t = <t>: <the cause's what()>", where is the callback as CVODE's core names it ("rhs()" for
// the right-hand side: the loads and forces; "roots()" for event functions).
//
// CVODE's core (detail/cvode_core.hpp) stores the exception inside its C callbacks and builds
// the CvodeError from it (detail/cvode_report.hpp). The explicit integrator
// (explicit_integrator.hpp) catches where it calls the scene: guard_callbacks() below, or a
// handler of its own that calls throw_callback_error(). Neither wraps the exceptions of the
// user's observer or of an event's action, which are not called from inside a step.

#include <exception>
#include <string>
#include <utility>

#include "tumble/core/errors.hpp"
#include "tumble/core/format.hpp"
#include "tumble/integrate/errors.hpp"

namespace tumble::detail {

/// what() of the exception e, or words for one not derived from std::exception.
inline std::string exception_message(const std::exception_ptr& e) {
  try {
    std::rethrow_exception(e);
  } catch (const std::exception& x) {
    return x.what();
  } catch (...) {
    return "an exception not derived from std::exception";
  }
}

/// "<where> threw at t = <t>: <what() of e>": the words of both integrators.
inline std::string callback_threw(const char* where, double t, const std::exception_ptr& e) {
  return std::string(where) + " threw at t = " + format_double(t) + ": " + exception_message(e);
}

/// Called in a handler (catch (...)) of the explicit integrator around a call of the scene's
/// callback `where` at time t: throws the ExplicitIntegrationError whose cause() is the exception
/// being handled, with time() = reached, the time the integrator had reached.
[[noreturn]] inline void throw_callback_error(const char* who, const char* where, double t,
                                              double reached) {
  std::exception_ptr cause = std::current_exception();
  std::string what = std::string(who) + ": stopped at t = " + format_double(reached) + ": " +
                     callback_threw(where, t, cause);
  throw ExplicitIntegrationError(what, IntegrationFailure::callback, reached, std::move(cause));
}

/// f(), a call of the scene's callback `where` at time t; what it throws becomes an
/// ExplicitIntegrationError (throw_callback_error), but for NonFiniteError, which goes on
/// unchanged: the integrator handles it (a shorter step, or its own message).
template <class F>
decltype(auto) guard_callbacks(const char* who, const char* where, double t, double reached,
                               F&& f) {
  try {
    return std::forward<F>(f)();
  } catch (const NonFiniteError&) {
    throw;
  } catch (...) {
    throw_callback_error(who, where, t, reached);
  }
}

}  // namespace tumble::detail
