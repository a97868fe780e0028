// tumble::detail::format_double (include/tumble/core/format.hpp), the numbers of every message:
// each prints as printf's %.17g, and reads back as the same double.

#include "tumble/core/format.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "support/catch.hpp"

TEST_CASE("format: numbers in messages read back as the double they are", "[core][format]") {
  using tumble::detail::format_double;
  CHECK(format_double(1.5) == "1.5");
  CHECK(format_double(0.0) == "0");
  CHECK(format_double(-2.0) == "-2");
  CHECK(format_double(0.1) == "0.10000000000000001");  // every digit: the double, not 1/10
  CHECK(format_double(1e-300) == "1e-300");            // %g: the exponent form for small and large
  CHECK(format_double(std::numeric_limits<double>::infinity()) == "inf");
  CHECK(format_double(std::nan("")).find("nan") != std::string::npos);
  for (const double x : {1.0 / 3.0, 2.0 / 3.0 * 1e10, 1.0 + std::numeric_limits<double>::epsilon(),
                         std::numeric_limits<double>::max(), std::numeric_limits<double>::min()}) {
    CHECK(std::stod(format_double(x)) == x);
  }
}
