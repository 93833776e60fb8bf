#include "polygon_triangulation.hpp"

#include <array>
#include <cmath>

namespace fissure::io_detail {
namespace {

using Point2 = std::array<double, 2>;

double cross(const Point2& o, const Point2& a, const Point2& b) {
  return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

bool same(const Point2& a, const Point2& b) { return a[0] == b[0] && a[1] == b[1]; }

// p inside or on the boundary of the counter-clockwise triangle abc, and not one of its corners
// (a vertex repeated in the outline sits on a corner without blocking the ear).
bool blocks_ear(const Point2& p, const Point2& a, const Point2& b, const Point2& c) {
  if (same(p, a) || same(p, b) || same(p, c)) return false;
  return cross(a, b, p) >= 0.0 && cross(b, c, p) >= 0.0 && cross(c, a, p) >= 0.0;
}

}  // namespace

bool triangulate_polygon(const std::vector<double>& xyz, std::span<const int> polygon, std::vector<int>& triangles) {
  const std::size_t n = polygon.size();
  auto fan = [&] {
    for (std::size_t k = 1; k + 1 < n; ++k) triangles.insert(triangles.end(), {polygon[0], polygon[k], polygon[k + 1]});
  };
  auto point = [&](std::size_t k, int axis) { return xyz[3 * static_cast<std::size_t>(polygon[k]) + static_cast<std::size_t>(axis)]; };
  if (n == 3) {
    fan();
    return true;
  }

  // Newell normal about the first vertex (differences keep far-from-origin faces accurate).
  double normal[3] = {0, 0, 0};
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t l = (k + 1) % n;
    double a[3], b[3];
    for (int axis = 0; axis < 3; ++axis) {
      a[axis] = point(k, axis) - point(0, axis);
      b[axis] = point(l, axis) - point(0, axis);
    }
    normal[0] += a[1] * b[2] - a[2] * b[1];
    normal[1] += a[2] * b[0] - a[0] * b[2];
    normal[2] += a[0] * b[1] - a[1] * b[0];
  }
  int drop = 0;
  for (int axis = 1; axis < 3; ++axis) {
    if (std::abs(normal[axis]) > std::abs(normal[drop])) drop = axis;
  }
  if (!(std::abs(normal[drop]) > 0.0) || !std::isfinite(normal[drop])) {
    fan();  // no plane: degenerate, dropped by repair_surface
    return true;
  }
  // Project onto the plane of the two other axes, in the cyclic order that makes the outline
  // counter-clockwise (positive area) seen along the normal.
  int u = (drop + 1) % 3, v = (drop + 2) % 3;
  if (normal[drop] < 0.0) std::swap(u, v);
  std::vector<Point2> p(n);
  for (std::size_t k = 0; k < n; ++k) p[k] = {point(k, u), point(k, v)};

  bool convex = true;
  for (std::size_t k = 0; k < n && convex; ++k) convex = cross(p[(k + n - 1) % n], p[k], p[(k + 1) % n]) >= 0.0;
  if (convex) {
    fan();
    return true;
  }
  if (n > kMaxConcaveFaceVertices) return false;

  // Ear clipping over a doubly linked ring. An ear is a convex corner whose triangle holds no
  // other remaining vertex. When none is found in a whole lap (a self-overlapping or collinear
  // outline), the current corner is clipped anyway, so the loop always ends after n − 3 clips.
  std::vector<std::size_t> prev(n), next(n);
  for (std::size_t k = 0; k < n; ++k) {
    prev[k] = (k + n - 1) % n;
    next[k] = (k + 1) % n;
  }
  std::size_t left = n, at = 0, tried = 0;
  auto is_ear = [&](std::size_t k) {
    const std::size_t a = prev[k], c = next[k];
    if (cross(p[a], p[k], p[c]) <= 0.0) return false;
    for (std::size_t q = next[c]; q != a; q = next[q]) {
      if (blocks_ear(p[q], p[a], p[k], p[c])) return false;
    }
    return true;
  };
  while (left > 3) {
    if (is_ear(at) || tried >= left) {
      triangles.insert(triangles.end(), {polygon[prev[at]], polygon[at], polygon[next[at]]});
      next[prev[at]] = next[at];
      prev[next[at]] = prev[at];
      at = next[at];
      --left;
      tried = 0;
    } else {
      at = next[at];
      ++tried;
    }
  }
  triangles.insert(triangles.end(), {polygon[prev[at]], polygon[at], polygon[next[at]]});
  return true;
}

}  // namespace fissure::io_detail
