#pragma once
/// Content hashing for caches: a result is keyed by a hash of every input that determines it plus
/// a format version, so a stale cache entry can never be mistaken for a fresh one.

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace fissure {

/// A 128-bit digest. Not cryptographic; collisions between honest inputs are negligible.
struct Hash128 {
  std::uint64_t hi = 0;
  std::uint64_t lo = 0;
  /// 32 lowercase hex digits.
  std::string hex() const;
  friend bool operator==(const Hash128&, const Hash128&) = default;
};

/// Streaming hasher. Every add() is framed by its length and a type tag, so ("ab","c") and
/// ("a","bc") differ, and a double differs from the int64 of the same bits.
class ContentHasher {
public:
  ContentHasher& add_bytes(const void* data, std::size_t size);
  ContentHasher& add(std::string_view text);
  ContentHasher& add(std::int64_t value);
  ContentHasher& add(double value);
  ContentHasher& add(const Eigen::Ref<const Eigen::MatrixXd>& values);
  ContentHasher& add(const Eigen::Ref<const Eigen::MatrixXi>& values);
  Hash128 finish() const;

private:
  void absorb(std::uint64_t word);
  void absorb_tail(const unsigned char* data, std::size_t size);
  std::uint64_t m_a = 0x243f6a8885a308d3ULL;
  std::uint64_t m_b = 0x13198a2e03707344ULL;
  std::uint64_t m_length = 0;
};

}  // namespace fissure
