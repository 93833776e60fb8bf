#pragma once
/// The seeded random generator of Fissure. There is no global generator: every random draw comes
/// from an Rng passed in. Streams are derived from (seed, purpose, index), so trial 1234 of a fit
/// draws the same numbers whichever thread runs it.

#include <cstdint>
#include <limits>
#include <string_view>

namespace fissure {

/// xoshiro256** seeded through SplitMix64. Fast, 2^256 period, and fully specified here, so the
/// sequence is the same on every platform and standard library (std distributions are not).
class Rng {
public:
  using result_type = std::uint64_t;

  explicit Rng(std::uint64_t seed);

  /// An independent stream for one unit of work: `purpose` names the use ("resistance",
  /// "load_position", …), `index` the item (trial number, element, …).
  static Rng derive(std::uint64_t seed, std::string_view purpose, std::uint64_t index = 0);

  static constexpr result_type min() { return 0; }
  static constexpr result_type max() { return std::numeric_limits<result_type>::max(); }
  result_type operator()() { return next_u64(); }

  std::uint64_t next_u64();
  /// Uniform in [0, 1) with 53 random bits.
  double uniform();
  /// Uniform in [lo, hi).
  double uniform(double lo, double hi);
  /// Uniform integer in [0, n). n > 0. Unbiased (rejection).
  std::uint64_t uniform_index(std::uint64_t n);
  /// Standard normal (Box–Muller, both values used in turn).
  double normal();
  double normal(double mean, double stddev) { return mean + stddev * normal(); }

private:
  std::uint64_t m_state[4];
  double m_spare_normal = 0.0;
  bool m_has_spare_normal = false;
};

}  // namespace fissure
