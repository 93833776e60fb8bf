#pragma once
// Whether a triangle mesh is a closed, consistently wound, 2-manifold surface: every directed
// edge used once and its reverse once, no triangle without area. Header-only, so any test binary
// can use it on its own mesh type.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <map>
#include <utility>

namespace fissure::test {

// With `pinched`, an edge may be used k times each way (k sheets of the surface touching along
// it), and the number of such edges is added to *pinched.
inline ::testing::AssertionResult closed_surface(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& triangles,
                                                 int* pinched = nullptr) {
  std::map<std::pair<int, int>, int> edges;
  for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
    const Eigen::Vector3d a = vertices.row(triangles(t, 0)), b = vertices.row(triangles(t, 1)),
                          c = vertices.row(triangles(t, 2));
    if (!((b - a).cross(c - a).norm() > 0.0)) return ::testing::AssertionFailure() << "triangle " << t << " has no area";
    for (int i = 0; i < 3; ++i) ++edges[{triangles(t, i), triangles(t, (i + 1) % 3)}];
  }
  for (const auto& [e, count] : edges) {
    const auto it = edges.find({e.second, e.first});
    const int reverse = it == edges.end() ? 0 : it->second;
    if (pinched && count == reverse && count > 1) {
      ++*pinched;
      continue;
    }
    if (count != 1 || reverse != 1)
      return ::testing::AssertionFailure() << "edge " << e.first << "→" << e.second << " used " << count
                                           << " times, its reverse " << reverse;
  }
  return ::testing::AssertionSuccess();
}

}  // namespace fissure::test
