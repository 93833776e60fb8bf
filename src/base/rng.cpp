#include "fissure/base/rng.hpp"

#include <cassert>
#include <cmath>
#include <numbers>

namespace fissure {
namespace {

std::uint64_t splitmix64(std::uint64_t& x) {
  std::uint64_t z = (x += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

}  // namespace

Rng::Rng(std::uint64_t seed) {
  std::uint64_t s = seed;
  for (auto& word : m_state) word = splitmix64(s);
}

Rng Rng::derive(std::uint64_t seed, std::string_view purpose, std::uint64_t index) {
  // FNV-1a over the purpose, then SplitMix64 mixing of (seed, purpose, index): distinct triples
  // give unrelated SplitMix64 seeds, hence independent xoshiro states.
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (char c : purpose) {
    h ^= static_cast<unsigned char>(c);
    h *= 0x100000001b3ULL;
  }
  std::uint64_t mix = seed;
  std::uint64_t a = splitmix64(mix);
  mix ^= h;
  std::uint64_t b = splitmix64(mix);
  mix ^= index * 0xd6e8feb86659fd93ULL;
  std::uint64_t c = splitmix64(mix);
  return Rng(a ^ rotl(b, 21) ^ rotl(c, 42));
}

std::uint64_t Rng::next_u64() {
  const std::uint64_t result = rotl(m_state[1] * 5, 7) * 9;
  const std::uint64_t t = m_state[1] << 17;
  m_state[2] ^= m_state[0];
  m_state[3] ^= m_state[1];
  m_state[1] ^= m_state[2];
  m_state[0] ^= m_state[3];
  m_state[2] ^= t;
  m_state[3] = rotl(m_state[3], 45);
  return result;
}

double Rng::uniform() { return static_cast<double>(next_u64() >> 11) * 0x1.0p-53; }

double Rng::uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

std::uint64_t Rng::uniform_index(std::uint64_t n) {
  assert(n > 0 && "uniform_index needs a non-empty range");
  if (n == 0) return 0;
  // Lemire-free simple rejection: reject the top partial block so every residue is equally likely.
  const std::uint64_t limit = max() - (max() % n);
  std::uint64_t x;
  do {
    x = next_u64();
  } while (x >= limit);
  return x % n;
}

double Rng::normal() {
  if (m_has_spare_normal) {
    m_has_spare_normal = false;
    return m_spare_normal;
  }
  double u1;
  do {
    u1 = uniform();
  } while (u1 <= 0.0);
  const double u2 = uniform();
  const double r = std::sqrt(-2.0 * std::log(u1));
  const double theta = 2.0 * std::numbers::pi * u2;
  m_spare_normal = r * std::sin(theta);
  m_has_spare_normal = true;
  return r * std::cos(theta);
}

}  // namespace fissure
