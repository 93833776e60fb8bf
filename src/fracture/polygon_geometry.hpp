#pragma once
// Small geometry of the planar convex polygons cracks leave in tets.
#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

namespace fissure::detail {

// x, then y, then z: an order of points that is the body's, not its numbering's (tied tets by
// their centroids; the end a crossing is computed from, so both faces of a segment agree).
inline bool position_before(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  if (a.x() != b.x()) return a.x() < b.x();
  if (a.y() != b.y()) return a.y() < b.y();
  return a.z() < b.z();
}

// Σ (p_i − p_0) × (p_{i+1} − p_0): twice the area times the unit normal.
inline Eigen::Vector3d polygon_area_vector(std::span<const Eigen::Vector3d> p) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (std::size_t i = 1; i + 1 < p.size(); ++i) sum += (p[i] - p[0]).cross(p[i + 1] - p[0]);
  return sum;
}

inline double polygon_area(std::span<const Eigen::Vector3d> p) { return 0.5 * polygon_area_vector(p).norm(); }

// Distance from x to a planar convex polygon with unit normal n: to the plane when x projects
// inside it (on the same side of every edge, the winding either way round), else to its nearest
// edge. The edges are measured only when outside: relaxation calls this for every tet near a
// crack, and most of them project inside the polygon of the crack's nearest tet.
inline double polygon_distance(const Eigen::Vector3d& x, std::span<const Eigen::Vector3d> p,
                               const Eigen::Vector3d& n) {
  if (p.empty()) return std::numeric_limits<double>::infinity();
  if (p.size() == 1) return (x - p[0]).norm();
  const double h = n.dot(x - p[0]);
  const Eigen::Vector3d y = x - h * n;
  if (p.size() >= 3) {
    bool left = true, right = true;  // no edge with y strictly right of it / strictly left of it
    for (std::size_t i = 0; i < p.size() && (left || right); ++i) {
      const Eigen::Vector3d& a = p[i];
      const Eigen::Vector3d& b = p[(i + 1) % p.size()];
      const double side = n.dot((b - a).cross(y - a));
      if (side < 0.0) left = false;
      if (side > 0.0) right = false;
    }
    if (left || right) return std::abs(h);
  }
  // √ of the least squared distance equals the least distance exactly (√ rounds monotonically).
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Eigen::Vector3d& a = p[i];
    const Eigen::Vector3d ab = p[(i + 1) % p.size()] - a;
    const double len2 = ab.squaredNorm();
    const double t = len2 > 0.0 ? std::clamp((x - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, (x - (a + t * ab)).squaredNorm());
  }
  return std::sqrt(best);
}

}  // namespace fissure::detail
