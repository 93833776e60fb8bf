#include "fissure/base/content_hash.hpp"

#include <cstring>

namespace fissure {
namespace {

std::uint64_t fmix64(std::uint64_t k) {
  k ^= k >> 33;
  k *= 0xff51afd7ed558ccdULL;
  k ^= k >> 33;
  k *= 0xc4ceb9fe1a85ec53ULL;
  k ^= k >> 33;
  return k;
}

std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

enum Tag : std::uint64_t { kBytes = 1, kText = 2, kInt = 3, kDouble = 4, kMatrixD = 5, kMatrixI = 6 };

}  // namespace

std::string Hash128::hex() const {
  static const char* digits = "0123456789abcdef";
  std::string out(32, '0');
  for (int i = 0; i < 16; ++i) {
    out[15 - i] = digits[(hi >> (4 * i)) & 0xf];
    out[31 - i] = digits[(lo >> (4 * i)) & 0xf];
  }
  return out;
}

void ContentHasher::absorb(std::uint64_t word) {
  // Two lanes with different multipliers and rotations (MurmurHash3-style mixing of each word).
  m_a ^= fmix64(word * 0x87c37b91114253d5ULL);
  m_a = rotl(m_a, 27) * 5 + 0x52dce729;
  m_b ^= fmix64(word * 0x4cf5ad432745937fULL + 0x9e3779b97f4a7c15ULL);
  m_b = rotl(m_b, 31) * 5 + 0x38495ab5;
  m_length += 8;
}

void ContentHasher::absorb_tail(const unsigned char* data, std::size_t size) {
  std::size_t i = 0;
  for (; i + 8 <= size; i += 8) {
    std::uint64_t w;
    std::memcpy(&w, data + i, 8);
    absorb(w);
  }
  if (i < size) {
    std::uint64_t w = 0;
    std::memcpy(&w, data + i, size - i);
    absorb(w ^ (static_cast<std::uint64_t>(size - i) << 56));
  }
}

ContentHasher& ContentHasher::add_bytes(const void* data, std::size_t size) {
  absorb(kBytes);
  absorb(size);
  absorb_tail(static_cast<const unsigned char*>(data), size);
  return *this;
}

ContentHasher& ContentHasher::add(std::string_view text) {
  absorb(kText);
  absorb(text.size());
  absorb_tail(reinterpret_cast<const unsigned char*>(text.data()), text.size());
  return *this;
}

ContentHasher& ContentHasher::add(std::int64_t value) {
  absorb(kInt);
  absorb(static_cast<std::uint64_t>(value));
  return *this;
}

ContentHasher& ContentHasher::add(double value) {
  if (value == 0.0) value = 0.0;  // +0 and -0 describe the same input
  std::uint64_t bits;
  std::memcpy(&bits, &value, 8);
  absorb(kDouble);
  absorb(bits);
  return *this;
}

ContentHasher& ContentHasher::add(const Eigen::Ref<const Eigen::MatrixXd>& values) {
  absorb(kMatrixD);
  absorb(static_cast<std::uint64_t>(values.rows()));
  absorb(static_cast<std::uint64_t>(values.cols()));
  for (Eigen::Index c = 0; c < values.cols(); ++c) {
    for (Eigen::Index r = 0; r < values.rows(); ++r) {
      double v = values(r, c);
      if (v == 0.0) v = 0.0;
      std::uint64_t bits;
      std::memcpy(&bits, &v, 8);
      absorb(bits);
    }
  }
  return *this;
}

ContentHasher& ContentHasher::add(const Eigen::Ref<const Eigen::MatrixXi>& values) {
  absorb(kMatrixI);
  absorb(static_cast<std::uint64_t>(values.rows()));
  absorb(static_cast<std::uint64_t>(values.cols()));
  for (Eigen::Index c = 0; c < values.cols(); ++c) {
    for (Eigen::Index r = 0; r < values.rows(); ++r) {
      absorb(static_cast<std::uint64_t>(static_cast<std::int64_t>(values(r, c))));
    }
  }
  return *this;
}

Hash128 ContentHasher::finish() const {
  std::uint64_t a = m_a ^ m_length;
  std::uint64_t b = m_b ^ m_length;
  a += b;
  b += a;
  a = fmix64(a);
  b = fmix64(b);
  a += b;
  b += a;
  return Hash128{a, b};
}

}  // namespace fissure
