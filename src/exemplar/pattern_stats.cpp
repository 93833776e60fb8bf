#include "fissure/exemplar/pattern_stats.hpp"

#include "fissure/base/error.hpp"
#include "fissure/base/number_text.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>

namespace fissure {
namespace {

// The point at arc length `distance` along `points` (clamped to the polyline).
Eigen::Vector2d point_along(const std::vector<Eigen::Vector2d>& points, double distance) {
  double walked = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) {
    const double step = (points[i] - points[i - 1]).norm();
    if (walked + step >= distance && step > 0.0) {
      return points[i - 1] + (points[i] - points[i - 1]) * ((distance - walked) / step);
    }
    walked += step;
  }
  return points.back();
}

}  // namespace

std::vector<std::string> PatternStatsOptions::problems() const {
  std::vector<std::string> out;
  for (const auto& [name, value] : {std::pair{"probe_near_factor", probe_near_factor}, std::pair{"probe_far_factor", probe_far_factor},
                                    std::pair{"probe_min", probe_min}}) {
    if (!std::isfinite(value) || value < 0.0) out.push_back(std::string(name) + " " + format_number(value) + " is negative or not finite");
  }
  if (!(t_gap_deg > 0.0 && t_gap_deg <= 360.0)) out.push_back("t_gap_deg " + format_number(t_gap_deg) + " is outside (0, 360]");
  if (density_windows < 1 || density_windows > kMaxDensityWindows) {
    out.push_back("density_windows " + std::to_string(density_windows) + " is outside [1, " + std::to_string(kMaxDensityWindows) + "]");
  }
  if (!std::isfinite(directional_min_deg) || !std::isfinite(directional_max_deg) || directional_min_deg > directional_max_deg) {
    out.push_back("directional range [" + format_number(directional_min_deg) + ", " + format_number(directional_max_deg) +
                  "] deg is not finite with min <= max");
  }
  return out;
}

void PatternStatsOptions::validate() const { throw_if_problems("pattern statistics options", problems()); }

RelaxationMode relaxation_mode_for(double mean_angle, const PatternStatsOptions& options) {
  return mean_angle >= options.directional_min_deg && mean_angle <= options.directional_max_deg
             ? RelaxationMode::Directional
             : RelaxationMode::Isotropic;
}

const char* to_string(RelaxationMode mode) {
  return mode == RelaxationMode::Directional ? "directional (Eq. 3)" : "isotropic (Eq. 4)";
}

const char* to_string(JunctionType type) {
  switch (type) {
    case JunctionType::T: return "T";
    case JunctionType::Y: return "Y";
    case JunctionType::X: return "X";
  }
  return "?";
}

PatternStats compute_pattern_stats(const PlanarCrackGraph& graph, const PatternStatsOptions& options) {
  options.validate();
  graph.validate();
  PatternStats s;
  s.source = graph.source;
  s.total_area = graph.total_area;
  const double root = std::sqrt(graph.total_area);
  s.crack_width = graph.crack_width / root;

  // S1: fragments.
  s.fragment_area_hist = Histogram::make(-6.0, 0.0, 24);
  for (const Fragment& f : graph.fragments) {
    s.fragments_touching_border += f.touches_border;
    if (options.exclude_border_fragments && f.touches_border) continue;
    s.fragment_areas.push_back(f.area / graph.total_area);
  }
  std::sort(s.fragment_areas.begin(), s.fragment_areas.end(), std::greater<>());
  s.fragment_count = static_cast<int>(s.fragment_areas.size());
  for (double a : s.fragment_areas) s.fragment_area_hist.add(std::log10(a));
  s.fragment_area_hist.normalize();

  // S2: cracks.
  s.crack_length_hist = Histogram::make(-4.0, 0.0, 16);
  for (const Crack& c : graph.cracks) {
    const double length = c.length() / root;
    s.crack_lengths.push_back(length);
    s.total_crack_length += length;
  }
  std::sort(s.crack_lengths.begin(), s.crack_lengths.end(), std::greater<>());
  s.crack_count = static_cast<int>(s.crack_lengths.size());
  for (double l : s.crack_lengths) s.crack_length_hist.add(std::log10(std::max(l, 1e-12)));
  s.crack_length_hist.normalize();

  // S3: junctions, with the direction of each incident crack probed a few widths out.
  std::vector<std::vector<Eigen::Vector2d>> directions(graph.nodes.size());
  const double near = std::max(options.probe_near_factor * graph.crack_width, options.probe_min / 4.0);
  const double far = std::max(options.probe_far_factor * graph.crack_width, options.probe_min);
  auto direction = [&](const std::vector<Eigen::Vector2d>& points, double length) -> Eigen::Vector2d {
    const double d_far = std::min(far, 0.5 * length);
    const double d_near = std::min(near, 0.25 * length);
    return point_along(points, d_far) - point_along(points, d_near);
  };
  for (const Crack& c : graph.cracks) {
    if (c.points.size() < 2) continue;
    const double length = c.length();
    if (c.start_node >= 0) directions[static_cast<std::size_t>(c.start_node)].push_back(direction(c.points, length));
    if (c.end_node >= 0) {
      const std::vector<Eigen::Vector2d> reversed(c.points.rbegin(), c.points.rend());
      directions[static_cast<std::size_t>(c.end_node)].push_back(direction(reversed, length));
    }
  }
  const Eigen::Vector2d frame_size = graph.frame_max - graph.frame_min;
  const double frame_area = frame_size.x() * frame_size.y();
  const int k = options.density_windows;
  std::vector<int> window_counts(static_cast<std::size_t>(k * k), 0);
  s.junction_angle_hist = Histogram::make(0.0, 360.0, 36);
  double angle_sum = 0.0, angle_sum_degree3 = 0.0;
  int degree3 = 0;
  for (std::size_t v = 0; v < graph.nodes.size(); ++v) {
    const CrackNode& node = graph.nodes[v];
    if (node.kind == CrackNode::Kind::End) ++s.end_count;
    if (node.kind == CrackNode::Kind::Border) ++s.border_end_count;
    if (node.kind != CrackNode::Kind::Junction) continue;
    JunctionStat j;
    j.node = static_cast<int>(v);
    j.degree = node.degree;
    j.position = frame_area > 0.0 ? Eigen::Vector2d((node.position - graph.frame_min).cwiseQuotient(frame_size))
                                  : Eigen::Vector2d::Zero();
    std::vector<double> angles;
    for (const Eigen::Vector2d& d : directions[v]) {
      if (d.squaredNorm() > 0.0) angles.push_back(std::atan2(d.y(), d.x()) * 180.0 / std::numbers::pi);
    }
    std::sort(angles.begin(), angles.end());
    for (std::size_t i = 0; i < angles.size(); ++i) {
      const double next = i + 1 < angles.size() ? angles[i + 1] : angles.front() + 360.0;
      j.gaps_deg.push_back(next - angles[i]);
    }
    if (j.gaps_deg.empty()) continue;
    j.angle_deg = *std::min_element(j.gaps_deg.begin(), j.gaps_deg.end());
    const double largest = *std::max_element(j.gaps_deg.begin(), j.gaps_deg.end());
    j.type = j.degree >= 4 ? JunctionType::X : (largest >= options.t_gap_deg ? JunctionType::T : JunctionType::Y);
    (j.type == JunctionType::T ? s.t_count : j.type == JunctionType::Y ? s.y_count : s.x_count)++;
    for (double gap : j.gaps_deg) s.junction_angle_hist.add(gap);
    angle_sum += j.angle_deg;
    if (j.degree == 3) {
      angle_sum_degree3 += j.angle_deg;
      ++degree3;
    }
    const int wx = std::clamp(static_cast<int>(j.position.x() * k), 0, k - 1);
    const int wy = std::clamp(static_cast<int>(j.position.y() * k), 0, k - 1);
    ++window_counts[static_cast<std::size_t>(wy * k + wx)];
    s.junctions.push_back(std::move(j));
  }
  s.junction_count = static_cast<int>(s.junctions.size());
  s.junction_density = s.junction_count;  // per unit normalised area
  s.mean_junction_angle_deg = degree3 > 0 ? angle_sum_degree3 / degree3
                              : (s.junction_count > 0 ? angle_sum / s.junction_count : 0.0);
  s.relaxation_mode = s.junction_count > 0 ? relaxation_mode_for(s.mean_junction_angle_deg, options)
                                           : RelaxationMode::Isotropic;
  s.junction_angle_hist.normalize();

  // Local densities: a window covers frame_area/k² of the frame, i.e. (frame_area/k²)/A of the
  // normalised area (exact without an ROI; the ROI case assumes windows as full as the frame).
  s.junction_density_hist = Histogram::make(0.0, 5.0, 20);
  const double window_area = frame_area > 0.0 ? frame_area / (k * k) / graph.total_area : 1.0 / (k * k);
  for (int count : window_counts) s.junction_density_hist.add(std::log10(1.0 + count / window_area));
  s.junction_density_hist.normalize();
  return s;
}

}  // namespace fissure
