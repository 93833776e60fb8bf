#include "fissure/base/huge_pages.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include <sys/resource.h>

namespace fissure {
namespace {

long minor_faults() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_minflt;
}

TEST(HugePages, SmallAndLargeAllocationsHoldTheirBytes) {
  for (std::size_t bytes : {std::size_t{100}, std::size_t{3} << 20}) {
    auto* p = static_cast<unsigned char*>(allocate_huge(bytes));
    std::memset(p, 0x5a, bytes);
    EXPECT_EQ(p[bytes - 1], 0x5a);
    if (bytes >= (std::size_t{2} << 20)) {
      EXPECT_EQ(reinterpret_cast<std::uintptr_t>(p) % (std::size_t{2} << 20), 0u);
    }
    release_huge(p, bytes);
  }
  std::vector<int, HugePageAllocator<int>> v(1 << 20, 7);
  EXPECT_EQ(v.back(), 7);
}

// The point of it: filling 64 MB takes a fault per 2 MiB instead of one per 4 KiB (16,384).
// A quarter of that bound leaves room for pages the kernel could not make huge.
TEST(HugePages, FillingSixtyFourMegabytesTakesFewFaults) {
  std::ifstream thp("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string setting((std::istreambuf_iterator<char>(thp)), std::istreambuf_iterator<char>());
  if (setting.find("[never]") != std::string::npos || setting.empty()) GTEST_SKIP() << "no transparent huge pages";
#if defined(__SANITIZE_ADDRESS__)
  // ASan's memset checks the shadow of all 64 MB, itself 8 MB on 4 KiB pages: 4,707 faults in the
  // CI's sanitizer pass, none of them the allocation's.
  GTEST_SKIP() << "AddressSanitizer's shadow memory faults on its own pages";
#endif
  const std::size_t bytes = std::size_t{64} << 20;
  const long before = minor_faults();
  auto* p = static_cast<unsigned char*>(allocate_huge(bytes));
  std::memset(p, 1, bytes);
  const long faults = minor_faults() - before;
  release_huge(p, bytes);
  EXPECT_LT(faults, 4096);
}

}  // namespace
}  // namespace fissure
