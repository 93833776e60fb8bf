#pragma once
/// Memory for large working arrays, backed by 2 MiB pages where the kernel allows. On the KVM
/// guests we run on, a first touch of a 4 KiB page costs ~10 µs, so filling a fresh 64 MB array
/// costs more in page faults than most passes over it (docs/BENCHMARKS.md); transparent huge pages
/// are granted only on request (madvise mode), one fault per 2 MiB.

#include <cstddef>
#include <new>

namespace fissure {

/// `bytes` of memory: from 2 MiB boundaries, with MADV_HUGEPAGE, when bytes ≥ 2 MiB; else from
/// operator new. Throws std::bad_alloc. Release with release_huge(p, bytes).
void* allocate_huge(std::size_t bytes);
void release_huge(void* p, std::size_t bytes) noexcept;

/// A std allocator over allocate_huge, for std::vector of large, short-lived arrays.
template <class T>
struct HugePageAllocator {
  using value_type = T;
  HugePageAllocator() = default;
  template <class U>
  HugePageAllocator(const HugePageAllocator<U>&) noexcept {}
  T* allocate(std::size_t n) {
    if (n > static_cast<std::size_t>(-1) / sizeof(T)) throw std::bad_alloc();
    return static_cast<T*>(allocate_huge(n * sizeof(T)));
  }
  void deallocate(T* p, std::size_t n) noexcept { release_huge(p, n * sizeof(T)); }
  template <class U>
  bool operator==(const HugePageAllocator<U>&) const noexcept { return true; }
};

}  // namespace fissure
