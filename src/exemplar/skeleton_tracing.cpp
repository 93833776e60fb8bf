// Steps 3 and 4 of extract_crack_graph: nodes and cracks from the skeleton (crack_graph_steps.hpp).

#include "crack_graph_steps.hpp"

#include <array>
#include <map>

namespace fissure::detail {
namespace {

// Crossing number: 0→1 transitions around the ring N, NE, …, NW (Zhang–Suen's A). A skeleton
// pixel with A ≥ 3 is where three or more branches meet; A = 1 is a tip. (Counting connected
// neighbour groups instead misses the junctions of thinned skeletons, whose three arms are
// diagonal neighbours of each other.)
std::array<std::uint8_t, 256> make_crossing_table() {
  std::array<std::uint8_t, 256> table{};
  for (int code = 0; code < 256; ++code) {
    int transitions = 0;
    for (int k = 0; k < 8; ++k) transitions += !((code >> k) & 1) && ((code >> ((k + 1) & 7)) & 1);
    table[static_cast<std::size_t>(code)] = static_cast<std::uint8_t>(transitions);
  }
  return table;
}

// The skeleton with bounds-checked access.
struct Skeleton {
  const std::vector<std::uint8_t>& pixels;
  int w, h;
  bool at(int x, int y) const { return x >= 0 && y >= 0 && x < w && y < h && pixels[static_cast<std::size_t>(y) * w + x]; }
};

}  // namespace

double RawEdge::length() const { return polyline_length(points); }

std::vector<std::vector<int>> PruningGraph::incidence() const {
  std::vector<std::vector<int>> inc(nodes.size());
  for (std::size_t e = 0; e < edges.size(); ++e) {
    if (!edges[e].alive) continue;
    if (edges[e].a >= 0) inc[static_cast<std::size_t>(edges[e].a)].push_back(static_cast<int>(e));
    if (edges[e].b >= 0) inc[static_cast<std::size_t>(edges[e].b)].push_back(static_cast<int>(e));
  }
  return inc;
}

SkeletonNodes find_skeleton_nodes(std::vector<std::uint8_t>& skel, int w, int h, PruningGraph& g, CrackGraphDiagnostics& diag) {
  static const auto crossing_table = make_crossing_table();
  const std::size_t n = static_cast<std::size_t>(w) * h;
  const Skeleton s{skel, w, h};
  SkeletonNodes nodes;
  std::vector<std::uint8_t>& kind = nodes.kind;
  kind.assign(n, 0);  // 0 none, 1 path, 2 end, 3 junction
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * w + x;
      if (!skel[i]) continue;
      ++diag.skeleton_pixels;
      int c = 0;
      for (int k = 0; k < 8; ++k) c |= s.at(x + kDx[k], y + kDy[k]) << k;
      const int neighbours = __builtin_popcount(static_cast<unsigned>(c));
      // The skeleton is 8-thin (no pixel can go without changing connectivity), so three or more
      // neighbours mean branches meet here; a 2×2 block at an X crossing has no pixel with three
      // separate runs of neighbours, which is why the crossing number alone misses it.
      if (neighbours == 0) {
        skel[i] = 0;  // an isolated pixel: a speck, not a crack
      } else if (neighbours == 1) {
        kind[i] = 2;
      } else if (neighbours >= 3 || crossing_table[static_cast<std::size_t>(c)] >= 3) {
        kind[i] = 3;
      } else {
        kind[i] = 1;
      }
    }

  // Nodes: each end pixel, and each 8-connected cluster of junction pixels.
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * w + x;
      if (kind[i] < 2 || nodes.node_of(i) >= 0) continue;
      const int id = static_cast<int>(g.nodes.size());
      Eigen::Vector2d sum = Eigen::Vector2d::Zero();
      int count = 0;
      std::vector<std::size_t> stack{i};
      nodes.ids[i] = id;
      while (!stack.empty()) {
        const std::size_t p = stack.back();
        stack.pop_back();
        const int px = static_cast<int>(p % w), py = static_cast<int>(p / w);
        sum += Eigen::Vector2d(px, py);
        ++count;
        if (kind[p] != 3) continue;  // ends do not cluster
        for (int k = 0; k < 8; ++k) {
          const int qx = px + kDx[k], qy = py + kDy[k];
          if (!s.at(qx, qy)) continue;
          const std::size_t q = static_cast<std::size_t>(qy) * w + qx;
          if (kind[q] == 3 && nodes.node_of(q) < 0) {
            nodes.ids[q] = id;
            stack.push_back(q);
          }
        }
      }
      g.nodes.push_back(RawNode{sum / count, kind[i] == 2, true});
      (kind[i] == 2 ? diag.raw_end_nodes : diag.raw_junction_clusters)++;
    }
  return nodes;
}

void trace_cracks(const std::vector<std::uint8_t>& skel, int w, int h, const SkeletonNodes& nodes, PruningGraph& g) {
  const std::size_t n = static_cast<std::size_t>(w) * h;
  const Skeleton s{skel, w, h};
  auto node_of = [&](std::size_t p) { return nodes.node_of(p); };
  std::vector<std::uint8_t> visited(n, 0);
  std::map<std::pair<std::size_t, std::size_t>, bool> direct_links;  // node pixel ↔ node pixel steps
  auto pixel_point = [&](std::size_t p) { return Eigen::Vector2d(static_cast<double>(p % w), static_cast<double>(p / w)); };
  auto neighbours_of = [&](std::size_t p, std::array<std::size_t, 8>& out) {
    int count = 0;
    const int px = static_cast<int>(p % w), py = static_cast<int>(p / w);
    // Orthogonal neighbours first: at an L-shaped step the diagonal is a shortcut.
    for (int k : {0, 2, 4, 6, 1, 3, 5, 7}) {
      const int qx = px + kDx[k], qy = py + kDy[k];
      if (s.at(qx, qy)) out[static_cast<std::size_t>(count++)] = static_cast<std::size_t>(qy) * w + qx;
    }
    return count;
  };
  auto touches_node = [&](std::size_t p, int node) {
    const int px = static_cast<int>(p % w), py = static_cast<int>(p / w);
    for (int k = 0; k < 8; ++k) {
      const int qx = px + kDx[k], qy = py + kDy[k];
      if (s.at(qx, qy) && node_of(static_cast<std::size_t>(qy) * w + qx) == node) return true;
    }
    return false;
  };
  for (std::size_t start = 0; start < n; ++start) {
    if (!skel[start] || node_of(start) < 0) continue;
    const int origin = node_of(start);
    std::array<std::size_t, 8> first{};
    const int first_count = neighbours_of(start, first);
    for (int f = 0; f < first_count; ++f) {
      const std::size_t p = first[static_cast<std::size_t>(f)];
      if (node_of(p) == origin) continue;
      if (node_of(p) >= 0) {
        // Two node pixels side by side: a one-step crack, traced once.
        const auto key = std::minmax(start, p);
        if (direct_links.emplace(key, true).second) {
          g.edges.push_back(RawEdge{{pixel_point(start), pixel_point(p)}, origin, node_of(p), true});
        }
        continue;
      }
      if (visited[p]) continue;  // traced from its other end already
      RawEdge edge;
      edge.a = origin;
      edge.points = {pixel_point(start), pixel_point(p)};
      visited[p] = 1;
      std::size_t prev = start, cur = p;
      while (true) {
        std::array<std::size_t, 8> next{};
        const int count = neighbours_of(cur, next);
        std::size_t chosen = n;
        bool reached_node = false;
        // Prefer stepping onto a node; never straight back into the origin cluster.
        for (int k = 0; k < count && !reached_node; ++k) {
          const std::size_t q = next[static_cast<std::size_t>(k)];
          if (q == prev || node_of(q) < 0) continue;
          if (node_of(q) == origin && edge.points.size() < 3) continue;
          chosen = q;
          reached_node = true;
        }
        // Leaving a junction, skip pixels that also touch it: they start its other branches
        // (the arms of a thinned junction are diagonal neighbours of each other).
        const bool leaving = touches_node(cur, origin);
        for (int k = 0; k < count && chosen == n; ++k) {
          const std::size_t q = next[static_cast<std::size_t>(k)];
          if (q == prev || node_of(q) >= 0 || visited[q]) continue;
          if (leaving && touches_node(q, origin)) continue;
          chosen = q;
        }
        if (chosen == n) break;  // a dead end that is not an end pixel (should not happen)
        edge.points.push_back(pixel_point(chosen));
        if (reached_node) {
          edge.b = node_of(chosen);
          break;
        }
        visited[chosen] = 1;
        prev = cur;
        cur = chosen;
      }
      if (edge.b >= 0) g.edges.push_back(std::move(edge));
    }
  }
  // Closed cracks meeting nothing: cycles of unvisited path pixels.
  for (std::size_t start = 0; start < n; ++start) {
    if (!skel[start] || node_of(start) >= 0 || visited[start]) continue;
    RawEdge loop;
    std::size_t cur = start;
    while (true) {
      visited[cur] = 1;
      loop.points.push_back(pixel_point(cur));
      std::array<std::size_t, 8> next{};
      const int count = neighbours_of(cur, next);
      std::size_t chosen = n;
      for (int k = 0; k < count && chosen == n; ++k) {
        const std::size_t q = next[static_cast<std::size_t>(k)];
        if (!visited[q] && node_of(q) < 0) chosen = q;
      }
      if (chosen == n) break;
      cur = chosen;
    }
    if (loop.points.size() >= 3) {
      loop.points.push_back(loop.points.front());
      g.edges.push_back(std::move(loop));
    }
  }
}

}  // namespace fissure::detail
