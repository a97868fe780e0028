#pragma once
// Memory that one thread writes at every evaluation (a workspace's scratch): whole cache lines of
// its own, aligned to and padded out to kCacheLine bytes, so that it shares no line with anything
// another thread reads or writes, whatever the allocator puts next to it.
//
// Why an allocator and not alignas: the scratch of a scene has a size known only at run time
// (per body), so it lives on the heap, and the heap puts blocks of different threads side by side
// when one thread frees what another allocated. glibc's per-thread cache (tcache) takes a block
// freed by the thread that frees it, whichever thread allocated it, and hands it out to that
// thread next: an ensemble's per-thread integrators, freed by the calling thread at the end of a
// call, became the calling thread's integrator of the next call, in the other thread's heap and
// next to the blocks that thread was given at the same time. Two threads writing the same line at
// every step of the right-hand side made calls 3-4x slower (docs/benchmarks/ensembles.md).

#include <cstddef>
#include <limits>
#include <new>
#include <vector>

namespace tumble {

/// The unit of the padding, bytes: two 64-byte lines, since x86 cores fetch lines in adjacent
/// pairs (the spatial prefetcher), the padding oneTBB and folly use too. A constant, not
/// std::hardware_destructive_interference_size, whose value GCC warns may change with -mtune.
inline constexpr std::size_t kCacheLine = 128;

/// A standard allocator of whole, aligned kCacheLine blocks (std::vector<T,
/// CacheLineAllocator<T>>): what it returns shares no cache line with any other allocation.
/// Stateless; all compare equal.
template <class T> struct CacheLineAllocator {
  using value_type = T;

  CacheLineAllocator() noexcept = default;
  template <class U> CacheLineAllocator(const CacheLineAllocator<U>&) noexcept {}

  [[nodiscard]] T* allocate(std::size_t n) {
    if (n > std::numeric_limits<std::size_t>::max() / sizeof(T) - kCacheLine) {
      throw std::bad_array_new_length();
    }
    return static_cast<T*>(::operator new (padded(n), std::align_val_t{kCacheLine}));
  }
  /// The unsized aligned delete: the sized one needs -fsized-deallocation, off by default in
  /// Clang 14.
  void deallocate(T* p, std::size_t /*n*/) noexcept {
    ::operator delete (p, std::align_val_t{kCacheLine});
  }

  /// n T's in bytes, rounded up to whole kCacheLine blocks.
  static constexpr std::size_t padded(std::size_t n) noexcept {
    return (n * sizeof(T) + kCacheLine - 1) / kCacheLine * kCacheLine;
  }
};

template <class T, class U>
bool operator==(const CacheLineAllocator<T>&, const CacheLineAllocator<U>&) noexcept {
  return true;
}

/// A std::vector on whole cache lines of its own: for buffers one thread writes at every step or
/// evaluation (a workspace's scratch, an integrator's state and stage vectors).
template <class T> using CacheLineVector = std::vector<T, CacheLineAllocator<T>>;

}  // namespace tumble
