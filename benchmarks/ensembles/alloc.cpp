// tumble_bench: the global operator new and delete, replaced for the whole program so that the
// ensemble study can count heap allocations per run (allocation_count, common/bench.hpp).
// Counting is off except around the runs it counts: otherwise a replacement costs one relaxed
// atomic load over malloc. Every form of new is replaced, so every form of delete is too, and
// they all pair with malloc/aligned_alloc and free. (tests/integrate/alloc_counter.test.cpp does
// the same for the test programs; a program can hold only one set, so each has its own.)

#include <atomic>
#include <cstddef>
#include <cstdlib>
#include <new>

#include "common/bench.hpp"

namespace {

std::atomic<long> g_allocations{0};
std::atomic<bool> g_counting{false};

void count() noexcept {
  if (g_counting.load(std::memory_order_relaxed)) {
    g_allocations.fetch_add(1, std::memory_order_relaxed);
  }
}

void* allocate(std::size_t n) noexcept {
  count();
  return std::malloc(n == 0 ? 1 : n);
}

void* allocate(std::size_t n, std::align_val_t a) noexcept {
  count();
  const auto al = static_cast<std::size_t>(a);
  return std::aligned_alloc(al, ((n == 0 ? 1 : n) + al - 1) / al * al);
}

void* or_throw(void* p) {
  if (p == nullptr) {
    throw std::bad_alloc();
  }
  return p;
}

// Out of line, so that GCC does not see free() applied to the result of an inlined operator new
// (-Wmismatched-new-delete): the pairs are malloc/free by construction.
[[gnu::noinline]] void release(void* p) noexcept { std::free(p); }

}  // namespace

namespace tumble::bench {

long allocation_count() noexcept { return g_allocations.load(std::memory_order_relaxed); }
void reset_allocation_count() noexcept { g_allocations.store(0, std::memory_order_relaxed); }
void set_allocation_counting(bool on) noexcept { g_counting.store(on, std::memory_order_relaxed); }

}  // namespace tumble::bench

void* operator new(std::size_t n) { return or_throw(allocate(n)); }
void* operator new[](std::size_t n) { return or_throw(allocate(n)); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept { return allocate(n); }
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept { return allocate(n); }
void* operator new(std::size_t n, std::align_val_t a) { return or_throw(allocate(n, a)); }
void* operator new[](std::size_t n, std::align_val_t a) { return or_throw(allocate(n, a)); }
void* operator new(std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept {
  return allocate(n, a);
}
void* operator new[](std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept {
  return allocate(n, a);
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
