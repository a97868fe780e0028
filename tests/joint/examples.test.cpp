// The mechanism examples run as tests too: each checks itself against its closed form (and exits
// with status 1 when it misses), so ctest catches what a user would see.

#include "support/catch.hpp"

#define main slider_crank_main
#include "../../examples/slider_crank.cpp"  // NOLINT(bugprone-suspicious-include)
#undef main

TEST_CASE("examples/slider_crank.cpp: the slider on the loop's closed form, energy kept",
          "[joint][example]") {
  CHECK(slider_crank_main() == 0);
}
