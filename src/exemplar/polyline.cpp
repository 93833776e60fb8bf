// The polyline clean-up of extract_crack_graph (crack_graph_steps.hpp).

#include "crack_graph_steps.hpp"

#include <algorithm>
#include <cmath>

namespace fissure::detail {

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

}  // namespace fissure::detail
