#include "fissure/base/parallel.hpp"
#include "fissure/base/rng.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

namespace fissure {
namespace {

std::vector<double> draws(int threads) {
  std::vector<double> out(1000);
  parallel_for(out.size(), threads, [&](std::size_t i) {
    Rng rng = Rng::derive(99, "test", i);
    out[i] = rng.normal();
  });
  return out;
}

TEST(ParallelFor, ThreadCountDoesNotChangeResults) {
  const auto one = draws(1);
  EXPECT_EQ(one, draws(2));
  EXPECT_EQ(one, draws(7));
}

TEST(ParallelFor, RethrowsLowestFailingIndex) {
  try {
    parallel_for(100, 4, [](std::size_t i) {
      if (i == 30 || i == 80) throw std::runtime_error("item " + std::to_string(i));
    });
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "item 30");
  }
}

TEST(ParallelFor, EmptyAndSingle) {
  int calls = 0;
  parallel_for(0, 4, [&](std::size_t) { ++calls; });
  EXPECT_EQ(calls, 0);
  parallel_for(1, 4, [&](std::size_t) { ++calls; });
  EXPECT_EQ(calls, 1);
}

}  // namespace
}  // namespace fissure
