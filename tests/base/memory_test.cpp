#include "fissure/base/error.hpp"
#include "fissure/base/memory.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>

namespace fissure {
namespace {

TEST(Memory, FormatsBytes) {
  EXPECT_EQ(format_bytes(512), "512 B");
  EXPECT_EQ(format_bytes(12'345), "12.3 kB");
  EXPECT_EQ(format_bytes(38.2e9), "38.2 GB");
}

TEST(Memory, RefusesEstimatesAboveTheLimit) {
  EXPECT_GT(physical_memory_bytes(), 100'000'000u);  // every machine Fissure runs on has > 100 MB
  EXPECT_NO_THROW(require_memory(1e6, 2'000'000, "meshing"));
  try {
    require_memory(3e9, 2'000'000'000, "meshing 50000000 tets");
    FAIL() << "not refused";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("meshing 50000000 tets needs about 3 GB, more than the 2 GB allowed"),
              std::string::npos)
        << e.what();
  }
  // 0 = the machine's memory; UINT64_MAX allows anything.
  EXPECT_THROW(require_memory(1e30, 0, "x"), InvalidInput);
  EXPECT_NO_THROW(require_memory(1e18, std::numeric_limits<std::uint64_t>::max(), "x"));
}

}  // namespace
}  // namespace fissure
