#include "fissure/exemplar/crack_graph.hpp"

#include "fissure/exemplar/skeleton.hpp"

#include "fissure/base/error.hpp"
#include "fissure/base/number_text.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <unordered_map>

namespace fissure {
namespace {

// Ring order of the 8 neighbours, clockwise from north.
constexpr int kDx[8] = {0, 1, 1, 1, 0, -1, -1, -1};
constexpr int kDy[8] = {-1, -1, 0, 1, 1, 1, 0, -1};

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

struct RawEdge {
  std::vector<Eigen::Vector2d> points;
  int a = -1, b = -1;
  bool alive = true;
  double length() const {
    double l = 0.0;
    for (std::size_t i = 1; i < points.size(); ++i) l += (points[i] - points[i - 1]).norm();
    return l;
  }
};

struct RawNode {
  Eigen::Vector2d position;
  bool is_end = false;  // a skeleton end pixel (else a junction cluster)
  bool alive = true;
};

// The graph under pruning: nodes, edges and a node → edges index rebuilt when needed.
class PruningGraph {
public:
  std::vector<RawNode> nodes;
  std::vector<RawEdge> edges;
  std::vector<std::vector<int>> loops;  // closed cracks that meet nothing (point lists kept in edges with a = b = -1)

  std::vector<std::vector<int>> incidence() const {
    std::vector<std::vector<int>> inc(nodes.size());
    for (std::size_t e = 0; e < edges.size(); ++e) {
      if (!edges[e].alive) continue;
      if (edges[e].a >= 0) inc[static_cast<std::size_t>(edges[e].a)].push_back(static_cast<int>(e));
      if (edges[e].b >= 0) inc[static_cast<std::size_t>(edges[e].b)].push_back(static_cast<int>(e));
    }
    return inc;
  }
};

// Moving average over ±`half` chain points (fewer near the ends, which stay fixed): turns the
// 8-connected staircase of a slanted skeleton into its straight line while keeping bends that
// span more than a few pixels.
std::vector<Eigen::Vector2d> smooth(const std::vector<Eigen::Vector2d>& points, int half) {
  if (points.size() < 3 || half < 1) return points;
  std::vector<Eigen::Vector2d> out(points.size());
  const int n = static_cast<int>(points.size());
  for (int i = 0; i < n; ++i) {
    const int k = std::min({half, i, n - 1 - i});
    Eigen::Vector2d sum = Eigen::Vector2d::Zero();
    for (int j = i - k; j <= i + k; ++j) sum += points[static_cast<std::size_t>(j)];
    out[static_cast<std::size_t>(i)] = sum / (2 * k + 1);
  }
  return out;
}

// Douglas–Peucker simplification keeping the end points (iterative: cracks can be long).
std::vector<Eigen::Vector2d> simplify(const std::vector<Eigen::Vector2d>& points, double tolerance) {
  if (tolerance <= 0.0 || points.size() < 3) return points;
  std::vector<char> keep(points.size(), 0);
  keep.front() = keep.back() = 1;
  std::vector<std::pair<std::size_t, std::size_t>> stack{{0, points.size() - 1}};
  while (!stack.empty()) {
    const auto [first, last] = stack.back();
    stack.pop_back();
    const Eigen::Vector2d a = points[first], b = points[last];
    const Eigen::Vector2d ab = b - a;
    const double length = ab.norm();
    double worst = -1.0;
    std::size_t index = first;
    for (std::size_t i = first + 1; i < last; ++i) {
      const Eigen::Vector2d ap = points[i] - a;
      const double d = length > 0.0 ? std::abs(ab.x() * ap.y() - ab.y() * ap.x()) / length : ap.norm();
      if (d > worst) {
        worst = d;
        index = i;
      }
    }
    if (worst > tolerance) {
      keep[index] = 1;
      stack.emplace_back(first, index);
      stack.emplace_back(index, last);
    }
  }
  std::vector<Eigen::Vector2d> out;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (keep[i]) out.push_back(points[i]);
  return out;
}

}  // namespace

std::vector<std::string> CrackGraphOptions::problems() const {
  std::vector<std::string> out;
  for (const auto& [name, value] : {std::pair{"spur_factor", spur_factor}, std::pair{"spur_min_px", spur_min_px},
                                    std::pair{"merge_factor", merge_factor}, std::pair{"fragment_width_factor", fragment_width_factor},
                                    std::pair{"simplify_px", simplify_px}}) {
    if (!std::isfinite(value) || value < 0.0) out.push_back(std::string(name) + " " + format_number(value) + " is negative or not finite");
  }
  if (min_fragment_px < 0) out.push_back("min_fragment_px " + std::to_string(min_fragment_px) + " is negative");
  if (border_px < 0) out.push_back("border_px " + std::to_string(border_px) + " is negative");
  if (smoothing_points < 0 || smoothing_points > kMaxSmoothingPoints) {
    out.push_back("smoothing_points " + std::to_string(smoothing_points) + " is outside [0, " + std::to_string(kMaxSmoothingPoints) + "]");
  }
  return out;
}

void CrackGraphOptions::validate() const { throw_if_problems("crack graph options", problems()); }

PlanarCrackGraph extract_crack_graph(const CrackMask& mask, const CrackGraphOptions& options,
                                     CrackGraphDiagnostics* diagnostics_out, std::vector<std::uint8_t>* skeleton_out,
                                     std::vector<std::int32_t>* labels_out) {
  options.validate();
  static const auto crossing_table = make_crossing_table();
  CrackGraphDiagnostics diag;
  const int w = mask.width, h = mask.height;
  const std::size_t n = static_cast<std::size_t>(w) * h;
  if (w < 1 || h < 1 || mask.crack.size() != n || (!mask.roi.empty() && mask.roi.size() != n)) {
    throw InvalidInput(mask.source + ": crack mask of " + std::to_string(w) + " x " + std::to_string(h) + " holds " +
                       std::to_string(mask.crack.size()) + " crack and " + std::to_string(mask.roi.size()) + " ROI pixels");
  }

  // Cracks outside the region of interest do not count.
  std::vector<std::uint8_t> crack(n);
  for (std::size_t i = 0; i < n; ++i) {
    crack[i] = mask.crack[i] && mask.inside(static_cast<std::int64_t>(i));
  }
  // Background specks smaller than a fragment are holes in a crack stroke, not regions the
  // cracks enclose: fill them, or thinning keeps a tiny loop around each (which then reads as
  // false junctions). The small fragments this drops are counted below.
  const double min_fragment_area = std::max<double>(options.min_fragment_px, 1.0);
  cv::Mat labels, stats, centroids;  // 4-connected background regions: the fragments, later
  int region_count = 0;
  {
    cv::Mat background(h, w, CV_8U);
    for (int y = 0; y < h; ++y) {
      std::uint8_t* row = background.ptr<std::uint8_t>(y);
      for (int x = 0; x < w; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * w + x;
        row[x] = mask.inside(static_cast<std::int64_t>(i)) && !crack[i] ? 255 : 0;
      }
    }
    region_count = cv::connectedComponentsWithStats(background, labels, stats, centroids, 4, CV_32S);
  }
  std::vector<std::uint8_t> small(static_cast<std::size_t>(region_count), 0);
  for (int label = 1; label < region_count; ++label) {
    small[static_cast<std::size_t>(label)] = stats.at<int>(label, cv::CC_STAT_AREA) < min_fragment_area;
    diag.small_fragments_dropped += small[static_cast<std::size_t>(label)];
  }
  for (int y = 0; y < h; ++y) {
    int* row = labels.ptr<int>(y);
    for (int x = 0; x < w; ++x) {
      if (row[x] > 0 && small[static_cast<std::size_t>(row[x])]) {
        crack[static_cast<std::size_t>(y) * w + x] = 1;
        row[x] = 0;
      }
    }
  }
  for (std::uint8_t c : crack) diag.crack_pixels += c;
  std::vector<std::uint8_t> skel = thin_to_skeleton(crack, w, h);

  auto at = [&](int x, int y) -> bool { return x >= 0 && y >= 0 && x < w && y < h && skel[static_cast<std::size_t>(y) * w + x]; };
  std::vector<std::uint8_t> kind(n, 0);  // 0 none, 1 path, 2 end, 3 junction
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * w + x;
      if (!skel[i]) continue;
      ++diag.skeleton_pixels;
      int c = 0;
      for (int k = 0; k < 8; ++k) c |= at(x + kDx[k], y + kDy[k]) << k;
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
  PruningGraph g;
  // Node ids of node pixels (ends and junction clusters); every other pixel has none. A hash map
  // instead of an int per pixel: 4 bytes × 16.7 M pixels was a quarter of a 4096² analysis.
  std::unordered_map<std::size_t, int> node_ids;
  auto node_of = [&](std::size_t p) -> int {
    if (kind[p] < 2) return -1;
    const auto it = node_ids.find(p);
    return it == node_ids.end() ? -1 : it->second;
  };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * w + x;
      if (kind[i] < 2 || node_of(i) >= 0) continue;
      const int id = static_cast<int>(g.nodes.size());
      Eigen::Vector2d sum = Eigen::Vector2d::Zero();
      int count = 0;
      std::vector<std::size_t> stack{i};
      node_ids[i] = id;
      while (!stack.empty()) {
        const std::size_t p = stack.back();
        stack.pop_back();
        const int px = static_cast<int>(p % w), py = static_cast<int>(p / w);
        sum += Eigen::Vector2d(px, py);
        ++count;
        if (kind[p] != 3) continue;  // ends do not cluster
        for (int k = 0; k < 8; ++k) {
          const int qx = px + kDx[k], qy = py + kDy[k];
          if (!at(qx, qy)) continue;
          const std::size_t q = static_cast<std::size_t>(qy) * w + qx;
          if (kind[q] == 3 && node_of(q) < 0) {
            node_ids[q] = id;
            stack.push_back(q);
          }
        }
      }
      g.nodes.push_back(RawNode{sum / count, kind[i] == 2, true});
      (kind[i] == 2 ? diag.raw_end_nodes : diag.raw_junction_clusters)++;
    }

  // Trace cracks from every node along path pixels.
  std::vector<std::uint8_t> visited(n, 0);
  std::map<std::pair<std::size_t, std::size_t>, bool> direct_links;  // node pixel ↔ node pixel steps
  auto pixel_point = [&](std::size_t p) { return Eigen::Vector2d(static_cast<double>(p % w), static_cast<double>(p / w)); };
  auto neighbours_of = [&](std::size_t p, std::array<std::size_t, 8>& out) {
    int count = 0;
    const int px = static_cast<int>(p % w), py = static_cast<int>(p / w);
    // Orthogonal neighbours first: at an L-shaped step the diagonal is a shortcut.
    for (int k : {0, 2, 4, 6, 1, 3, 5, 7}) {
      const int qx = px + kDx[k], qy = py + kDy[k];
      if (at(qx, qy)) out[static_cast<std::size_t>(count++)] = static_cast<std::size_t>(qy) * w + qx;
    }
    return count;
  };
  auto touches_node = [&](std::size_t p, int node) {
    const int px = static_cast<int>(p % w), py = static_cast<int>(p / w);
    for (int k = 0; k < 8; ++k) {
      const int qx = px + kDx[k], qy = py + kDy[k];
      if (at(qx, qy) && node_of(static_cast<std::size_t>(qy) * w + qx) == node) return true;
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
  diag.raw_cracks = static_cast<int>(g.edges.size());
  double skeleton_length = 0.0;
  for (const RawEdge& e : g.edges) skeleton_length += e.length();
  diag.crack_width_px = skeleton_length > 0.0 ? static_cast<double>(diag.crack_pixels) / skeleton_length : 1.0;
  const double width = diag.crack_width_px;
  diag.spur_length_px = std::max(options.spur_min_px, options.spur_factor * width);
  diag.merge_length_px = options.merge_factor * width;
  diag.border_tolerance_px = std::max<double>(options.border_px, std::ceil(width / 2.0) + 2.0);

  // Distance to the edge of the fractured area: the frame, or the ROI's edge (distance transform
  // only when there is an ROI: it costs 4 bytes a pixel).
  cv::Mat roi_distance;
  if (!mask.roi.empty()) {
    cv::Mat region(h, w, CV_8U);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) region.at<std::uint8_t>(y, x) = mask.inside(static_cast<std::int64_t>(y) * w + x) ? 255 : 0;
    cv::Mat padded;
    cv::copyMakeBorder(region, padded, 1, 1, 1, 1, cv::BORDER_CONSTANT, 0);
    cv::distanceTransform(padded, roi_distance, cv::DIST_L2, 3);
  }
  auto near_border = [&](const Eigen::Vector2d& p) {
    const int x = std::clamp(static_cast<int>(std::lround(p.x())), 0, w - 1);
    const int y = std::clamp(static_cast<int>(std::lround(p.y())), 0, h - 1);
    const double to_frame = std::min({x + 1, y + 1, w - x, h - y});
    const double d = roi_distance.empty() ? to_frame : roi_distance.at<float>(y + 1, x + 1);
    return d <= diag.border_tolerance_px;
  };

  // Prune until nothing changes: spurs and specks, tiny loops, then contract close junctions.
  bool changed = true;
  while (changed) {
    changed = false;
    auto inc = g.incidence();
    auto degree = [&](int v) { return v < 0 ? 0 : static_cast<int>(inc[static_cast<std::size_t>(v)].size()); };
    auto free_end = [&](int v) { return v >= 0 && degree(v) == 1 && !near_border(g.nodes[static_cast<std::size_t>(v)].position); };
    for (std::size_t e = 0; e < g.edges.size(); ++e) {
      RawEdge& edge = g.edges[e];
      if (!edge.alive || edge.a < 0) continue;
      const double length = edge.length();
      if (edge.a == edge.b) {
        if (length < 2.0 * diag.spur_length_px) {
          edge.alive = false;
          ++diag.tiny_loops_removed;
          changed = true;
        }
        continue;
      }
      const bool a_free = free_end(edge.a), b_free = free_end(edge.b);
      if ((a_free || b_free) && length < diag.spur_length_px) {
        if (a_free && b_free) {
          ++diag.specks_removed;
        } else if (degree(a_free ? edge.b : edge.a) >= 3) {
          ++diag.spurs_pruned;
        } else {
          continue;  // a short crack from a free end to the border: keep it
        }
        edge.alive = false;
        changed = true;
      }
    }
    if (changed) {
      inc = g.incidence();
    }
    // Splice nodes left with two crack ends, drop nodes left with none.
    for (std::size_t v = 0; v < g.nodes.size(); ++v) {
      if (!g.nodes[v].alive) continue;
      const auto& list = inc[v];
      if (list.empty()) {
        g.nodes[v].alive = false;
        continue;
      }
      if (list.size() != 2 || list[0] == list[1] || g.nodes[v].is_end) continue;
      const int list_first = list[0], list_second = list[1];
      RawEdge& first = g.edges[static_cast<std::size_t>(list_first)];
      RawEdge& second = g.edges[static_cast<std::size_t>(list_second)];
      // Orient first to end at v and second to start at v, then concatenate.
      if (first.b != static_cast<int>(v)) {
        std::reverse(first.points.begin(), first.points.end());
        std::swap(first.a, first.b);
      }
      if (second.a != static_cast<int>(v)) {
        std::reverse(second.points.begin(), second.points.end());
        std::swap(second.a, second.b);
      }
      first.points.insert(first.points.end(), second.points.begin() + 1, second.points.end());
      first.b = second.b;
      second.alive = false;
      g.nodes[v].alive = false;
      if (first.a == static_cast<int>(v) && first.b == static_cast<int>(v)) first.a = first.b = -1;  // now a closed loop
      // Update the index in place (a rebuild per splice made pruning quadratic in the cracks):
      // v loses both edges, and second's far end now ends `first` instead.
      inc[v].clear();
      if (first.b >= 0) {
        auto& far = inc[static_cast<std::size_t>(first.b)];
        std::replace(far.begin(), far.end(), list_second, list_first);
      }
      changed = true;
    }
    // Contract junction pairs joined by a crack shorter than the crack width, in one sweep that
    // keeps the node → edges index current (restarting the sweep after each contraction, and
    // relabelling over all edges, made dense networks quadratic: 207 s for a 4096² grid).
    for (std::size_t e = 0; e < g.edges.size(); ++e) {
      RawEdge& edge = g.edges[e];
      if (!edge.alive || edge.a < 0 || edge.a == edge.b) continue;
      if (degree(edge.a) < 3 || degree(edge.b) < 3 || edge.length() >= diag.merge_length_px) continue;
      const int from = edge.b, to = edge.a;
      RawNode& keep = g.nodes[static_cast<std::size_t>(to)];
      RawNode& gone = g.nodes[static_cast<std::size_t>(from)];
      keep.position = 0.5 * (keep.position + gone.position);
      gone.alive = false;
      edge.alive = false;
      auto& at_to = inc[static_cast<std::size_t>(to)];
      auto& at_from = inc[static_cast<std::size_t>(from)];
      at_to.erase(std::find(at_to.begin(), at_to.end(), static_cast<int>(e)));
      at_from.erase(std::find(at_from.begin(), at_from.end(), static_cast<int>(e)));
      for (int o : at_from) {
        RawEdge& other = g.edges[static_cast<std::size_t>(o)];
        if (other.a == from) other.a = to;
        if (other.b == from) other.b = to;
      }
      at_to.insert(at_to.end(), at_from.begin(), at_from.end());
      at_from.clear();
      for (int o : at_to) {
        RawEdge& other = g.edges[static_cast<std::size_t>(o)];
        if (other.a == to) other.points.front() = keep.position;
        if (other.b == to) other.points.back() = keep.position;
      }
      ++diag.junctions_contracted;
      changed = true;
    }
  }

  // The final graph, through the builder: node degrees and kinds follow from the cracks.
  std::int64_t total_area = 0;
  if (mask.roi.empty()) {
    total_area = static_cast<std::int64_t>(n);
  } else {
    for (std::uint8_t r : mask.roi) total_area += r != 0;
  }
  PlanarCrackGraphBuilder builder(Eigen::Vector2d(-0.5, -0.5), Eigen::Vector2d(w - 0.5, h - 0.5),
                                  static_cast<double>(total_area), mask.source);
  builder.set_crack_width(width);
  const auto inc = g.incidence();
  std::vector<int> new_id(g.nodes.size(), -1);
  for (std::size_t v = 0; v < g.nodes.size(); ++v) {
    if (!g.nodes[v].alive || inc[v].empty()) continue;
    new_id[v] = builder.add_node(g.nodes[v].position, near_border(g.nodes[v].position));
  }
  for (const RawEdge& e : g.edges) {
    if (!e.alive) continue;
    std::vector<Eigen::Vector2d> points = e.points;
    const int start = e.a >= 0 ? new_id[static_cast<std::size_t>(e.a)] : -1;
    const int end = e.b >= 0 ? new_id[static_cast<std::size_t>(e.b)] : -1;
    if (e.a >= 0) points.front() = g.nodes[static_cast<std::size_t>(e.a)].position;
    if (e.b >= 0) points.back() = g.nodes[static_cast<std::size_t>(e.b)].position;
    builder.add_crack(simplify(smooth(points, options.smoothing_points), options.simplify_px), start, end);
  }

  // Fragments: the 4-connected regions of non-crack pixels inside the fractured area that are
  // large enough (labelled above). A crack pixel separates regions even where the skeleton was
  // pruned, as in the tracing itself.
  std::vector<Fragment> fragments;
  const double min_area = std::max(min_fragment_area, std::pow(options.fragment_width_factor * width, 2));
  std::vector<std::int32_t> fragment_of(static_cast<std::size_t>(region_count), -1);
  for (int label = 1; label < region_count; ++label) {
    const int area = stats.at<int>(label, cv::CC_STAT_AREA);
    if (small[static_cast<std::size_t>(label)]) continue;
    if (area < min_area) {
      ++diag.small_fragments_dropped;
      continue;
    }
    Fragment f;
    f.area = area;
    f.centroid = Eigen::Vector2d(centroids.at<double>(label, 0), centroids.at<double>(label, 1));
    const int left = stats.at<int>(label, cv::CC_STAT_LEFT), top = stats.at<int>(label, cv::CC_STAT_TOP);
    const int right = left + stats.at<int>(label, cv::CC_STAT_WIDTH) - 1;
    const int bottom = top + stats.at<int>(label, cv::CC_STAT_HEIGHT) - 1;
    f.touches_border = left == 0 || top == 0 || right == w - 1 || bottom == h - 1;
    fragment_of[static_cast<std::size_t>(label)] = static_cast<std::int32_t>(fragments.size());
    fragments.push_back(f);
  }
  auto fragment_at = [&](std::size_t i) { return fragment_of[static_cast<std::size_t>(labels.ptr<int>(0)[i])]; };
  if (!mask.roi.empty()) {
    // A fragment next to a pixel outside the ROI is cut by the ROI edge.
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const int id = fragment_at(static_cast<std::size_t>(y) * w + x);
        if (id < 0 || fragments[static_cast<std::size_t>(id)].touches_border) continue;
        for (int k = 0; k < 8; k += 2) {
          const int qx = x + kDx[k], qy = y + kDy[k];
          if (qx >= 0 && qy >= 0 && qx < w && qy < h && !mask.inside(static_cast<std::int64_t>(qy) * w + qx)) {
            fragments[static_cast<std::size_t>(id)].touches_border = true;
          }
        }
      }
  }
  if (options.assign_crack_pixels && !fragments.empty()) {
    // Crack pixels go to the nearest fragment, found by a breadth-first flood from the
    // fragments' edges across the strokes (4-neighbour steps, neighbours in a fixed order, so
    // ties resolve the same way every time). Memory: one queue of crack pixels, no distance map.
    int* label = labels.ptr<int>(0);
    std::vector<std::size_t> queue;
    auto claim = [&](std::size_t i, int from) {
      label[i] = from;
      fragments[static_cast<std::size_t>(fragment_of[static_cast<std::size_t>(from)])].area += 1.0;
      queue.push_back(i);
    };
    const int step[4] = {-w, 1, w, -1};
    auto neighbours_ok = [&](std::size_t i, int k) {
      const int x = static_cast<int>(i % w), y = static_cast<int>(i / w);
      return (k == 0 && y > 0) || (k == 1 && x < w - 1) || (k == 2 && y < h - 1) || (k == 3 && x > 0);
    };
    for (std::size_t i = 0; i < n; ++i) {
      if (!crack[i] || !mask.inside(static_cast<std::int64_t>(i))) continue;
      for (int k = 0; k < 4; ++k) {
        if (!neighbours_ok(i, k)) continue;
        const std::size_t j = static_cast<std::size_t>(static_cast<std::ptrdiff_t>(i) + step[k]);
        if (!crack[j] && label[j] > 0 && fragment_of[static_cast<std::size_t>(label[j])] >= 0) {
          claim(i, label[j]);
          break;
        }
      }
    }
    for (std::size_t head = 0; head < queue.size(); ++head) {
      const std::size_t i = queue[head];
      for (int k = 0; k < 4; ++k) {
        if (!neighbours_ok(i, k)) continue;
        const std::size_t j = static_cast<std::size_t>(static_cast<std::ptrdiff_t>(i) + step[k]);
        if (crack[j] && label[j] <= 0 && mask.inside(static_cast<std::int64_t>(j))) claim(j, label[i]);
      }
    }
  }
  if (labels_out) {
    labels_out->assign(n, -1);
    for (std::size_t i = 0; i < n; ++i) {
      const int l = labels.ptr<int>(0)[i];
      (*labels_out)[i] = l > 0 ? fragment_of[static_cast<std::size_t>(l)] : -1;
    }
  }
  for (Fragment& f : fragments) builder.add_fragment(std::move(f));
  PlanarCrackGraph graph = std::move(builder).build();
  if (skeleton_out) *skeleton_out = std::move(skel);
  if (diagnostics_out) *diagnostics_out = diag;
  return graph;
}

}  // namespace fissure
