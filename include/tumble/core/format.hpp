#pragma once
// Numbers in the messages of tumble's exceptions: every digit a double has (%.17g), so that a
// time or a tolerance quoted in a message reads back as the value that was given, and two
// different values never print alike.

#include <cstdio>
#include <string>

namespace tumble::detail {

/// x with 17 significant digits, the shortest of %f and %e (printf's %.17g): "0.1" prints as
/// 0.10000000000000001, the double it is.
inline std::string format_double(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

}  // namespace tumble::detail
