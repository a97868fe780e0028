#pragma once
// Catch2 v2 (single header, Debian's 2.13) or v3 (split headers), behind one include.
#if TUMBLE_CATCH_V3
#include <catch2/catch_approx.hpp>
#include <catch2/catch_template_test_macros.hpp>
#include <catch2/catch_test_macros.hpp>
#include <catch2/matchers/catch_matchers_string.hpp>
using Catch::Approx;
#else
#include <catch2/catch.hpp>
#endif

/// A matcher for "the message contains text", spelled alike in Catch2 v2 and v3.
#if TUMBLE_CATCH_V3
#define TUMBLE_CONTAINS(text) Catch::Matchers::ContainsSubstring(text)
#else
#define TUMBLE_CONTAINS(text) Catch::Contains(text)
#endif
