#include "fissure/exemplar/crack_graph.hpp"

#include "crack_graph_steps.hpp"

#include "fissure/base/error.hpp"
#include "fissure/base/number_text.hpp"
#include "fissure/exemplar/skeleton.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

namespace fissure {

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
  using namespace detail;
  options.validate();
  CrackGraphDiagnostics diag;
  const int w = mask.width, h = mask.height;
  const std::size_t n = static_cast<std::size_t>(w) * h;
  if (w < 1 || h < 1 || mask.crack.size() != n || (!mask.roi.empty() && mask.roi.size() != n)) {
    throw InvalidInput(mask.source + ": crack mask of " + std::to_string(w) + " x " + std::to_string(h) + " holds " +
                       std::to_string(mask.crack.size()) + " crack and " + std::to_string(mask.roi.size()) + " ROI pixels");
  }

  // 1–4: regions, skeleton, nodes, cracks.
  const double min_fragment_area = std::max<double>(options.min_fragment_px, 1.0);
  CrackRegions regions = label_regions(mask, min_fragment_area, diag);
  std::vector<std::uint8_t> skel = thin_to_skeleton(regions.crack, w, h);
  PruningGraph g;
  const SkeletonNodes nodes = find_skeleton_nodes(skel, w, h, g, diag);
  trace_cracks(skel, w, h, nodes, g);

  // The crack width and the lengths that scale with it.
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

  // 5: pruning.
  prune_graph(g, near_border, diag);

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

  // 6: fragments, the 4-connected regions of non-crack pixels inside the fractured area that are
  // large enough. A crack pixel separates regions even where the skeleton was pruned, as in the
  // tracing itself.
  const double min_area = std::max(min_fragment_area, std::pow(options.fragment_width_factor * width, 2));
  std::vector<std::int32_t> fragment_of;
  std::vector<Fragment> fragments =
      collect_fragments(mask, regions, min_area, options.assign_crack_pixels, fragment_of, diag);
  if (labels_out) {
    labels_out->assign(n, -1);
    const int* label = regions.labels.ptr<int>(0);
    for (std::size_t i = 0; i < n; ++i) {
      const int l = label[i];
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
