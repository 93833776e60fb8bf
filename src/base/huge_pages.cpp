#include "fissure/base/huge_pages.hpp"

#include <cstdlib>

#include <sys/mman.h>

namespace fissure {

namespace {
constexpr std::size_t kHugePage = std::size_t{2} << 20;
}

void* allocate_huge(std::size_t bytes) {
  if (bytes < kHugePage) return ::operator new(bytes);
  const std::size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
  void* p = std::aligned_alloc(kHugePage, rounded);
  if (!p) throw std::bad_alloc();
  // Advice only: without transparent huge pages the memory still works, in 4 KiB pages.
  madvise(p, rounded, MADV_HUGEPAGE);
  return p;
}

void release_huge(void* p, std::size_t bytes) noexcept {
  if (!p) return;
  if (bytes < kHugePage) {
    ::operator delete(p);
  } else {
    std::free(p);
  }
}

}  // namespace fissure
