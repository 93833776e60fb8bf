#include "fissure/exemplar/overlay.hpp"

#include "fissure/base/error.hpp"
#include "fissure/base/rng.hpp"

#include "bgr_png.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>

namespace fissure {

void write_overlay(const std::filesystem::path& path, const ExemplarAnalysis& a, int min_side) {
  const CrackMask& m = a.mask;
  // The analysis is plain data a caller can assemble: check that its layers fit one another.
  a.graph.validate();
  const std::size_t n = m.crack.size();
  const auto fits = [n](std::size_t size) { return size == 0 || size == n; };
  if (m.width < 1 || m.height < 1 || n != static_cast<std::size_t>(m.width) * static_cast<std::size_t>(m.height) ||
      !fits(m.roi.size()) || !fits(a.skeleton.size()) || !fits(a.fragment_labels.size())) {
    throw InvalidInput(path.string() + ": cannot draw the overlay: the analysis' pixel layers do not match its " +
                       std::to_string(m.width) + " x " + std::to_string(m.height) + " mask");
  }
  for (const JunctionStat& j : a.stats.junctions) {
    if (j.node < 0 || static_cast<std::size_t>(j.node) >= a.graph.nodes.size()) {
      throw InvalidInput(path.string() + ": cannot draw the overlay: a junction names node " + std::to_string(j.node) +
                         " of a graph of " + std::to_string(a.graph.nodes.size()));
    }
  }
  for (const std::int32_t label : a.fragment_labels) {
    if (label < -1 || label >= static_cast<std::int32_t>(a.graph.fragments.size())) {
      throw InvalidInput(path.string() + ": cannot draw the overlay: a pixel names fragment " + std::to_string(label) +
                         " of " + std::to_string(a.graph.fragments.size()));
    }
  }
  if (min_side < 1) throw InvalidInput(path.string() + ": overlay side " + std::to_string(min_side) + " is not positive");
  const int scale = std::max(1, (min_side + std::min(m.width, m.height) - 1) / std::min(m.width, m.height));
  // Base layer at image resolution: fragments in pastel colours (seeded: the same picture every
  // time), crack pixels grey, outside the ROI dark, skeleton black.
  cv::Mat base(m.height, m.width, CV_8UC3);
  for (int y = 0; y < m.height; ++y)
    for (int x = 0; x < m.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * m.width + x;
      cv::Vec3b colour(235, 235, 235);
      const int fragment = a.fragment_labels.empty() ? -1 : a.fragment_labels[i];
      if (!m.inside(static_cast<std::int64_t>(i))) {
        colour = cv::Vec3b(40, 40, 40);
      } else if (m.crack[i]) {
        colour = cv::Vec3b(150, 150, 150);
      } else if (fragment >= 0) {
        Rng rng = Rng::derive(0, "overlay colour", static_cast<std::uint64_t>(fragment));
        colour = cv::Vec3b(static_cast<std::uint8_t>(150 + rng.uniform_index(100)), static_cast<std::uint8_t>(150 + rng.uniform_index(100)),
                           static_cast<std::uint8_t>(150 + rng.uniform_index(100)));
      }
      if (!a.skeleton.empty() && a.skeleton[i]) colour = cv::Vec3b(60, 60, 60);
      base.at<cv::Vec3b>(y, x) = colour;
    }
  cv::Mat picture;
  cv::resize(base, picture, cv::Size(m.width * scale, m.height * scale), 0, 0, cv::INTER_NEAREST);
  auto to_px = [&](const Eigen::Vector2d& p) {
    return cv::Point(static_cast<int>((p.x() + 0.5) * scale), static_cast<int>((p.y() + 0.5) * scale));
  };
  // Cracks as thin dark-green polylines over the skeleton.
  for (const Crack& c : a.graph.cracks) {
    std::vector<cv::Point> points;
    for (const Eigen::Vector2d& p : c.points) points.push_back(to_px(p));
    cv::polylines(picture, points, false, cv::Scalar(40, 110, 40), std::max(1, scale / 2), cv::LINE_AA);
  }
  const int radius = std::max(3, 2 * scale);
  std::vector<JunctionType> type_of(a.graph.nodes.size(), JunctionType::Y);
  for (const JunctionStat& j : a.stats.junctions) type_of[static_cast<std::size_t>(j.node)] = j.type;
  for (std::size_t v = 0; v < a.graph.nodes.size(); ++v) {
    const CrackNode& node = a.graph.nodes[v];
    cv::Scalar colour(0, 200, 255);  // free end: yellow (BGR)
    if (node.kind == CrackNode::Kind::Border) colour = cv::Scalar(0, 170, 0);
    if (node.kind == CrackNode::Kind::Junction) {
      const JunctionType type = type_of[v];
      colour = type == JunctionType::T ? cv::Scalar(0, 0, 230) : type == JunctionType::Y ? cv::Scalar(230, 60, 0)
                                                                                      : cv::Scalar(200, 0, 200);
    }
    cv::circle(picture, to_px(node.position), radius, colour, cv::FILLED, cv::LINE_AA);
    cv::circle(picture, to_px(node.position), radius, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  }
  detail::write_bgr_png(path, picture);
}

}  // namespace fissure
