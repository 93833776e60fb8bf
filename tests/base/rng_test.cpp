#include "fissure/base/rng.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <vector>

namespace fissure {
namespace {

TEST(Rng, SameSeedGivesSameSequence) {
  Rng a(42), b(42);
  for (int i = 0; i < 1000; ++i) ASSERT_EQ(a.next_u64(), b.next_u64());
}

TEST(Rng, DifferentSeedsDiffer) {
  Rng a(1), b(2);
  int equal = 0;
  for (int i = 0; i < 1000; ++i) equal += a.next_u64() == b.next_u64();
  EXPECT_EQ(equal, 0);
}

TEST(Rng, DerivedStreamsDependOnEveryPart) {
  std::set<std::uint64_t> firsts;
  for (std::uint64_t seed : {0ULL, 1ULL}) {
    for (const char* purpose : {"resistance", "load_position"}) {
      for (std::uint64_t index : {0ULL, 1ULL, 2ULL}) {
        firsts.insert(Rng::derive(seed, purpose, index).next_u64());
      }
    }
  }
  EXPECT_EQ(firsts.size(), 12u);
  EXPECT_EQ(Rng::derive(7, "trial", 1234).next_u64(), Rng::derive(7, "trial", 1234).next_u64());
}

// Known-answer test: the sequence is fixed by this file, not by the standard library, so results
// are the same on every platform. If this fails, saved seeds reproduce different patterns.
TEST(Rng, KnownAnswer) {
  Rng r(0);
  const std::uint64_t first = r.next_u64();
  Rng again(0);
  EXPECT_EQ(again.next_u64(), first);
  // xoshiro256** seeded by SplitMix64(0): state words are SplitMix64's first four outputs.
  // Reference value from an independent Python transcription of the published algorithms
  // (Vigna, prng.di.unimi.it).
  EXPECT_EQ(first, 0x99ec5f36cb75f2b4ULL);
}

// Moments of 1e5 draws. Standard errors: uniform mean 0.289/√n = 9.1e-4, normal mean 1/√n =
// 3.2e-3, normal variance √2/√n = 4.5e-3. Bounds at ~5 standard errors: a false alarm has
// probability < 1e-6 per check.
TEST(Rng, UniformAndNormalMoments) {
  Rng r(123);
  const int n = 100000;
  double su = 0, sn = 0, sn2 = 0;
  for (int i = 0; i < n; ++i) {
    const double u = r.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    su += u;
    const double z = r.normal();
    sn += z;
    sn2 += z * z;
  }
  EXPECT_NEAR(su / n, 0.5, 5 * 9.1e-4);
  EXPECT_NEAR(sn / n, 0.0, 5 * 3.2e-3);
  EXPECT_NEAR(sn2 / n, 1.0, 5 * 4.5e-3);
}

TEST(Rng, UniformIndexCoversRangeEvenly) {
  Rng r(5);
  std::vector<int> counts(7, 0);
  const int n = 70000;
  for (int i = 0; i < n; ++i) ++counts[r.uniform_index(7)];
  // Binomial(70000, 1/7): mean 10000, sd 92.6; 6 sd bound.
  for (int c : counts) EXPECT_NEAR(c, 10000, 6 * 92.6);
}

}  // namespace
}  // namespace fissure
