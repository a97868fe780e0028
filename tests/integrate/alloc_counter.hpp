#pragma once
// Counting heap allocations in the test executable test_integrate (tests/integrate/*.test.cpp and
// tests/scene/*.test.cpp link into one program): the replaceable global operator new/delete are
// replaced once for the whole program, in alloc_counter.test.cpp, and count while an
// AllocationCounter is alive. Eigen's own heap allocations go through malloc, not operator new:
// they are caught by Eigen's runtime check (EIGEN_RUNTIME_NO_MALLOC), which every file that
// includes this header must define before its first include. Allocations by C code (SUNDIALS'
// malloc) are not seen.
//
// Usage:
//   solver.advance(0.1);             // finish the setup
//   AllocationCounter counter;       // count from here
//   solver.advance(10.0);
//   CHECK(counter.stop() == 0);

#ifndef EIGEN_RUNTIME_NO_MALLOC
#error "define EIGEN_RUNTIME_NO_MALLOC before any include in a file that uses alloc_counter.hpp"
#endif

#include <Eigen/Core>

namespace tumble::test {

/// Number of calls of the global operator new (all forms) since the last reset, counted only
/// while counting is on. Defined in alloc_counter.test.cpp.
long allocation_count() noexcept;
void reset_allocation_count() noexcept;
void set_allocation_counting(bool on) noexcept;

/// Counts operator new calls, and makes Eigen assert on a heap allocation, while alive.
class AllocationCounter {
 public:
  AllocationCounter() {
    reset_allocation_count();
    Eigen::internal::set_is_malloc_allowed(false);
    set_allocation_counting(true);
  }
  AllocationCounter(const AllocationCounter&) = delete;
  AllocationCounter& operator=(const AllocationCounter&) = delete;
  ~AllocationCounter() { stop(); }

  /// Stops counting (idempotent) and returns the number of operator new calls seen.
  long stop() noexcept {
    set_allocation_counting(false);
    Eigen::internal::set_is_malloc_allowed(true);
    return allocation_count();
  }
};

}  // namespace tumble::test
