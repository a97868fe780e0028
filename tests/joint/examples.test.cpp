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

#define main pendulum_main
#include "../../examples/pendulum.cpp"  // NOLINT(bugprone-suspicious-include)
#undef main

TEST_CASE("examples/pendulum.cpp: IFToMM A01 on its closed form, energy kept", "[joint][example]") {
  CHECK(pendulum_main() == 0);
}

#define main four_bar_main
#include "../../examples/four_bar.cpp"  // NOLINT(bugprone-suspicious-include)
#undef main

TEST_CASE("examples/four_bar.cpp: IFToMM A02 on its closed form, energy kept", "[joint][example]") {
  char name[] = "four_bar";
  char* argv[] = {name, nullptr};
  CHECK(four_bar_main(1, argv) == 0);
}
