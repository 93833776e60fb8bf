#pragma once
// The steps of extract_crack_graph (crack_graph.cpp), private to the exemplar module:
//   1. label_regions        crack pixels inside the ROI, background regions, specks filled
//   2. thin_to_skeleton     (skeleton.hpp)
//   3. find_skeleton_nodes  end pixels and junction clusters
//   4. trace_cracks         pixel chains between nodes, then closed loops meeting nothing
//   5. prune_graph          spurs, specks, tiny loops, degree-2 splices, close junction pairs
//   6. collect_fragments    regions large enough, cut by the ROI edge, crack pixels assigned
// and the polyline clean-up (smooth, simplify) applied to each final crack.

#include "fissure/exemplar/crack_graph.hpp"
#include "fissure/base/huge_pages.hpp"

#include <opencv2/core.hpp>

#include <cstdint>
#include <functional>
#include <unordered_map>
#include <vector>

namespace fissure::detail {

// Ring order of the 8 neighbours, clockwise from north.
inline constexpr int kDx[8] = {0, 1, 1, 1, 0, -1, -1, -1};
inline constexpr int kDy[8] = {-1, -1, 0, 1, 1, 1, 0, -1};

/// Step 1: the crack pixels that count and the 4-connected background regions around them.
struct CrackRegions {
  std::vector<std::uint8_t> crack;  ///< 1 = crack inside the ROI, specks filled
  cv::Mat labels, stats, centroids; ///< connectedComponentsWithStats of the background (specks relabelled 0)
  /// The pixels of `labels` (4 bytes a pixel, 67 MB at 4096²), on huge pages (huge_pages.hpp).
  std::vector<std::int32_t, HugePageAllocator<std::int32_t>> label_storage;
  int region_count = 0;
  std::vector<std::uint8_t> small;  ///< per label: a speck below the minimum fragment area
};

/// Background specks smaller than `min_fragment_area` are holes in a crack stroke, not regions
/// the cracks enclose: filled (thinning would keep a tiny loop around each, read as false
/// junctions). Counts them in diag.small_fragments_dropped and the crack pixels in diag.crack_pixels.
CrackRegions label_regions(const CrackMask& mask, double min_fragment_area, CrackGraphDiagnostics& diag);

struct RawEdge {
  std::vector<Eigen::Vector2d> points;
  int a = -1, b = -1;
  bool alive = true;
  double length() const;
};

struct RawNode {
  Eigen::Vector2d position;
  bool is_end = false;  // a skeleton end pixel (else a junction cluster)
  bool alive = true;
};

/// The graph under pruning: nodes, edges (closed loops have a = b = −1) and a node → edges index
/// rebuilt when needed.
struct PruningGraph {
  std::vector<RawNode> nodes;
  std::vector<RawEdge> edges;
  std::vector<std::vector<int>> incidence() const;
};

/// Step 3: per skeleton pixel its kind (0 none, 1 path, 2 end, 3 junction) and, for node pixels,
/// their node. A hash map instead of an int per pixel: 4 bytes × 16.7 M pixels was a quarter of a
/// 4096² analysis.
struct SkeletonNodes {
  std::vector<std::uint8_t> kind;
  std::unordered_map<std::size_t, int> ids;
  int node_of(std::size_t p) const {
    if (kind[p] < 2) return -1;
    const auto it = ids.find(p);
    return it == ids.end() ? -1 : it->second;
  }
};

/// Classifies the skeleton's pixels (removing isolated ones from `skeleton`) and adds a node to
/// `graph` for each end pixel and each 8-connected cluster of junction pixels.
SkeletonNodes find_skeleton_nodes(std::vector<std::uint8_t>& skeleton, int width, int height, PruningGraph& graph,
                                  CrackGraphDiagnostics& diag);

/// Step 4: the cracks as pixel chains from node to node, then the closed cracks that meet nothing.
void trace_cracks(const std::vector<std::uint8_t>& skeleton, int width, int height, const SkeletonNodes& nodes,
                  PruningGraph& graph);

/// Step 5: prunes until nothing changes (lengths in diag: spur, merge); `near_border` tells
/// whether a point is within the border tolerance of the fractured area's edge.
void prune_graph(PruningGraph& graph, const std::function<bool(const Eigen::Vector2d&)>& near_border,
                 CrackGraphDiagnostics& diag);

/// Step 6: fragments from the labelled regions (≥ min_area), flagged when cut by the frame or the
/// ROI edge, with each crack pixel given to its nearest fragment when `assign_crack_pixels`.
/// `fragment_of` receives, per region label, its fragment index or −1; regions.labels is updated
/// with the crack pixels' labels.
std::vector<Fragment> collect_fragments(const CrackMask& mask, CrackRegions& regions, double min_area,
                                        bool assign_crack_pixels, std::vector<std::int32_t>& fragment_of,
                                        CrackGraphDiagnostics& diag);

/// Moving average over ±`half` chain points (fewer near the ends, which stay fixed).
std::vector<Eigen::Vector2d> smooth(const std::vector<Eigen::Vector2d>& points, int half);
/// Douglas–Peucker simplification keeping the end points.
std::vector<Eigen::Vector2d> simplify(const std::vector<Eigen::Vector2d>& points, double tolerance);

}  // namespace fissure::detail
