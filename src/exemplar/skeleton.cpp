#include "fissure/exemplar/skeleton.hpp"

#include "fissure/base/huge_pages.hpp"

#include <array>

namespace fissure {
namespace {

// Neighbour bits, clockwise from north: P2 = N (bit 0), P3 = NE, P4 = E, P5 = SE, P6 = S,
// P7 = SW, P8 = W, P9 = NW (bit 7).
constexpr int kDx[8] = {0, 1, 1, 1, 0, -1, -1, -1};
constexpr int kDy[8] = {-1, -1, 0, 1, 1, 1, 0, -1};

// deletable[s][code]: Zhang–Suen conditions for sub-iteration s: 2 ≤ B ≤ 6 neighbours, exactly
// one 0→1 transition around P2…P9, and P2·P4·P6 = P4·P6·P8 = 0 (s = 0) or
// P2·P4·P8 = P2·P6·P8 = 0 (s = 1).
std::array<std::array<std::uint8_t, 256>, 2> make_tables() {
  std::array<std::array<std::uint8_t, 256>, 2> table{};
  for (int code = 0; code < 256; ++code) {
    auto p = [&](int k) { return (code >> (k - 2)) & 1; };  // P2..P9
    int b = 0, a = 0;
    for (int k = 2; k <= 9; ++k) {
      b += p(k);
      const int next = k == 9 ? 2 : k + 1;
      a += p(k) == 0 && p(next) == 1;
    }
    const bool common = b >= 2 && b <= 6 && a == 1;
    table[0][static_cast<std::size_t>(code)] = common && p(2) * p(4) * p(6) == 0 && p(4) * p(6) * p(8) == 0;
    table[1][static_cast<std::size_t>(code)] = common && p(2) * p(4) * p(8) == 0 && p(2) * p(6) * p(8) == 0;
  }
  return table;
}

// simple[code]: deleting the centre changes no connectivity (one 8-connected group of set
// neighbours, one 4-connected background group touching the centre's 4-neighbours) and the
// centre is not a line end (≥ 2 set neighbours).
std::array<std::uint8_t, 256> make_simple_table() {
  std::array<std::uint8_t, 256> table{};
  for (int code = 0; code < 256; ++code) {
    auto set = [&](int k) { return (code >> (k & 7)) & 1; };
    // 8-connected components of set neighbours on the ring: consecutive ring pixels touch, and
    // so do orthogonal pixels two steps apart (N and E touch diagonally).
    int parent[8];
    for (int k = 0; k < 8; ++k) parent[k] = k;
    auto find = [&](int a) {
      while (parent[a] != a) a = parent[a] = parent[parent[a]];
      return a;
    };
    int count = 0;
    for (int k = 0; k < 8; ++k) {
      count += set(k);
      if (!set(k)) continue;
      if (set(k + 1)) parent[find(k)] = find((k + 1) & 7);
      if (k % 2 == 0 && set(k + 2)) parent[find(k)] = find((k + 2) & 7);
    }
    int foreground = 0;
    for (int k = 0; k < 8; ++k) foreground += set(k) && find(k) == k;
    // 4-connected background components that touch an orthogonal neighbour of the centre:
    // orthogonal background pixels connect through the corner between them when it is
    // background too.
    int background = 0;
    bool seen[8] = {};
    for (int k = 0; k < 8; k += 2) {
      if (set(k) || seen[k]) continue;
      ++background;
      // Walk the background ring both ways through background pixels.
      for (int dir : {1, -1}) {
        int j = k;
        while (true) {
          seen[j] = true;
          const int next = (j + dir + 8) & 7;
          if (set(next) || next == k) break;
          j = next;
        }
      }
    }
    table[static_cast<std::size_t>(code)] = count >= 2 && foreground == 1 && background == 1;
  }
  return table;
}

}  // namespace

std::vector<std::uint8_t> thin_to_skeleton(const std::vector<std::uint8_t>& mask, int width, int height) {
  static const auto table = make_tables();
  // Work on a copy padded by one background pixel, so neighbour reads need no bounds checks.
  const int pw = width + 2;
  // Working arrays on huge pages: three bytes a pixel, 50 MB at 4096², would otherwise cost a
  // 4 KiB page fault each (huge_pages.hpp).
  using Bytes = std::vector<std::uint8_t, HugePageAllocator<std::uint8_t>>;
  Bytes img(static_cast<std::size_t>(pw) * (height + 2), 0);
  std::vector<int> candidates;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      if (mask[static_cast<std::size_t>(y) * width + x]) {
        const int i = (y + 1) * pw + x + 1;
        img[static_cast<std::size_t>(i)] = 1;
        candidates.push_back(i);
      }
  int offset[8];
  for (int k = 0; k < 8; ++k) offset[k] = kDy[k] * pw + kDx[k];
  auto code_of = [&](int i) {
    int code = 0;
    for (int k = 0; k < 8; ++k) code |= img[static_cast<std::size_t>(i + offset[k])] << k;
    return code;
  };

  // A pixel's verdict depends only on its 3×3 neighbourhood and the sub-iteration, so after the
  // first pass only the neighbours of deleted pixels need re-examining, separately per
  // sub-iteration: lists[s] holds the pixels to test in sub-iteration s.
  std::array<std::vector<int>, 2> lists{candidates, candidates};
  std::array<Bytes, 2> queued{Bytes(img.size(), 0), Bytes(img.size(), 0)};
  std::vector<int> deletions;
  int quiet_steps = 0;
  for (int step = 0; quiet_steps < 2; step ^= 1) {
    auto& list = lists[static_cast<std::size_t>(step)];
    // Decide every deletion of this sub-iteration on the image as it stood before it.
    deletions.clear();
    for (int i : list) {
      queued[static_cast<std::size_t>(step)][static_cast<std::size_t>(i)] = 0;
      if (img[static_cast<std::size_t>(i)] && table[static_cast<std::size_t>(step)][static_cast<std::size_t>(code_of(i))]) {
        deletions.push_back(i);
      }
    }
    list.clear();
    for (int i : deletions) img[static_cast<std::size_t>(i)] = 0;
    for (int i : deletions) {
      for (int k = 0; k < 8; ++k) {
        const int j = i + offset[k];
        if (!img[static_cast<std::size_t>(j)]) continue;
        for (int s = 0; s < 2; ++s) {
          if (!queued[static_cast<std::size_t>(s)][static_cast<std::size_t>(j)]) {
            queued[static_cast<std::size_t>(s)][static_cast<std::size_t>(j)] = 1;
            lists[static_cast<std::size_t>(s)].push_back(j);
          }
        }
      }
    }
    quiet_steps = deletions.empty() ? quiet_steps + 1 : 0;
  }
  // Zhang–Suen leaves pixels that connect nothing (staircase corners, two-pixel-thick diagonal
  // runs that read as tiny loops). Remove them one at a time, in raster order, while they stay
  // simple: the skeleton becomes 8-thin without changing its topology or its ends.
  static const auto simple = make_simple_table();
  bool removed = true;
  while (removed) {
    removed = false;
    for (int y = 1; y <= height; ++y)
      for (int x = 1; x <= width; ++x) {
        const int i = y * pw + x;
        if (img[static_cast<std::size_t>(i)] && simple[static_cast<std::size_t>(code_of(i))]) {
          img[static_cast<std::size_t>(i)] = 0;
          removed = true;
        }
      }
  }
  std::vector<std::uint8_t> out(static_cast<std::size_t>(width) * height, 0);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) out[static_cast<std::size_t>(y) * width + x] = img[static_cast<std::size_t>((y + 1) * pw + x + 1)];
  return out;
}

}  // namespace fissure
