#pragma once
// Small geometry of the planar convex polygons cracks leave in tets.
#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <vector>

namespace fissure::detail {

// Σ (p_i − p_0) × (p_{i+1} − p_0): twice the area times the unit normal.
inline Eigen::Vector3d polygon_area_vector(const std::vector<Eigen::Vector3d>& p) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (std::size_t i = 1; i + 1 < p.size(); ++i) sum += (p[i] - p[0]).cross(p[i + 1] - p[0]);
  return sum;
}

inline double polygon_area(const std::vector<Eigen::Vector3d>& p) { return 0.5 * polygon_area_vector(p).norm(); }

inline Eigen::Vector3d polygon_centroid(const std::vector<Eigen::Vector3d>& p) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& q : p) c += q;
  return p.empty() ? c : Eigen::Vector3d(c / static_cast<double>(p.size()));
}

inline double segment_distance(const Eigen::Vector3d& x, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((x - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (x - (a + t * ab)).norm();
}

// Distance from x to a planar convex polygon with unit normal n: to the plane when x projects
// inside it, else to its nearest edge.
inline double polygon_distance(const Eigen::Vector3d& x, const std::vector<Eigen::Vector3d>& p,
                               const Eigen::Vector3d& n) {
  if (p.empty()) return std::numeric_limits<double>::infinity();
  if (p.size() == 1) return (x - p[0]).norm();
  const double h = n.dot(x - p[0]);
  const Eigen::Vector3d y = x - h * n;
  bool inside = p.size() >= 3;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Eigen::Vector3d& a = p[i];
    const Eigen::Vector3d& b = p[(i + 1) % p.size()];
    if (inside && n.dot((b - a).cross(y - a)) < 0.0) inside = false;
    best = std::min(best, segment_distance(x, a, b));
  }
  if (inside) {
    // The winding may be either way round: inside means on the same side of every edge.
    return std::abs(h);
  }
  // Try the opposite winding before falling back to the edges.
  bool inside_reversed = p.size() >= 3;
  for (std::size_t i = 0; i < p.size() && inside_reversed; ++i) {
    const Eigen::Vector3d& a = p[i];
    const Eigen::Vector3d& b = p[(i + 1) % p.size()];
    if (n.dot((b - a).cross(y - a)) > 0.0) inside_reversed = false;
  }
  return inside_reversed ? std::abs(h) : best;
}

}  // namespace fissure::detail
