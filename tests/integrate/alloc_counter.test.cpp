// The counting global operator new/delete of the test executable test_integrate (see
// alloc_counter.hpp), and the test that the counter sees an allocation.
//
// The replacements must exist once per program, so they live here and nowhere else; the other
// files of the executable use tumble::test::AllocationCounter.

// Must precede every Eigen include (see alloc_counter.hpp).
#define EIGEN_RUNTIME_NO_MALLOC

#include "integrate/alloc_counter.hpp"

#include <atomic>
#include <cstddef>
#include <cstdlib>
#include <new>

#include "support/catch.hpp"

namespace {
std::atomic<long> g_news{0};
std::atomic<bool> g_counting{false};

void* counted_malloc(std::size_t n) noexcept {
  if (g_counting.load(std::memory_order_relaxed)) {
    g_news.fetch_add(1, std::memory_order_relaxed);
  }
  return std::malloc(n == 0 ? 1 : n);
}
void* counted_aligned(std::size_t n, std::align_val_t a) noexcept {
  if (g_counting.load(std::memory_order_relaxed)) {
    g_news.fetch_add(1, std::memory_order_relaxed);
  }
  const auto al = static_cast<std::size_t>(a);
  const std::size_t size = ((n == 0 ? 1 : n) + al - 1) / al * al;
  return std::aligned_alloc(al, size);
}

// Out of line, so that GCC does not see free() applied to the result of an inlined operator new
// (-Wmismatched-new-delete): the replacements below pair malloc with free by construction.
[[gnu::noinline]] void release(void* p) noexcept { std::free(p); }
}  // namespace

namespace tumble::test {
long allocation_count() noexcept { return g_news.load(); }
void reset_allocation_count() noexcept { g_news = 0; }
void set_allocation_counting(bool on) noexcept { g_counting = on; }
}  // namespace tumble::test

void* operator new(std::size_t n) {
  if (void* p = counted_malloc(n)) {
    return p;
  }
  throw std::bad_alloc();
}
void* operator new[](std::size_t n) {
  if (void* p = counted_malloc(n)) {
    return p;
  }
  throw std::bad_alloc();
}
void* operator new(std::size_t n, const std::nothrow_t&) noexcept { return counted_malloc(n); }
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept { return counted_malloc(n); }
void* operator new(std::size_t n, std::align_val_t a) {
  if (void* p = counted_aligned(n, a)) {
    return p;
  }
  throw std::bad_alloc();
}
void* operator new[](std::size_t n, std::align_val_t a) {
  if (void* p = counted_aligned(n, a)) {
    return p;
  }
  throw std::bad_alloc();
}
void* operator new(std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept {
  return counted_aligned(n, a);
}
void* operator new[](std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept {
  return counted_aligned(n, a);
}
void operator delete(void* p) noexcept { release(p); }
void operator delete[](void* p) noexcept { release(p); }
void operator delete(void* p, std::size_t) noexcept { release(p); }
void operator delete[](void* p, std::size_t) noexcept { release(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { release(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { release(p); }
void operator delete(void* p, std::align_val_t) noexcept { release(p); }
void operator delete[](void* p, std::align_val_t) noexcept { release(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { release(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { release(p); }
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept { release(p); }
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept { release(p); }

using tumble::test::AllocationCounter;

TEST_CASE("the counting operator new sees allocations", "[integrate][alloc_counter]") {
  SECTION("operator new") {
    AllocationCounter counter;
    // A direct call of the replaceable function (a new-expression may legally be elided), kept
    // alive through a volatile pointer.
    void* volatile p = ::operator new(16);
    const long n = counter.stop();
    ::operator delete(p);
    CHECK(n == 1);
  }
  SECTION("aligned and array forms") {
    AllocationCounter counter;
    void* volatile a = ::operator new (64, std::align_val_t{64});
    void* volatile b = ::operator new[](8);
    const long n = counter.stop();
    ::operator delete (a, std::align_val_t{64});
    ::operator delete[](b);
    CHECK(n == 2);
  }
  SECTION("nothing counted once stopped") {
    AllocationCounter counter;
    CHECK(counter.stop() == 0);
    void* volatile p = ::operator new(16);
    ::operator delete(p);
    CHECK(tumble::test::allocation_count() == 0);
  }
}
