#pragma once
// Exceptions of tumble. Bad input is rejected with std::invalid_argument (mass properties,
// options) whose message says what is wrong; a computation that meets a non-finite value throws
// NonFiniteError instead of returning a silent NaN.

#include <stdexcept>
#include <string>

namespace tumble {

/// A non-finite value was met (non-finite state or load, or an attitude exactly at a singularity
/// of its chart). Inside time integration it is recoverable: CVODE retries with a smaller step.
class NonFiniteError : public std::domain_error {
 public:
  explicit NonFiniteError(const std::string& what) : std::domain_error(what) {}
};

}  // namespace tumble
