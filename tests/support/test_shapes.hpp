#pragma once
// Closed test surfaces shared by the mesh and io tests.

#include "fissure/mesh/surface_mesh.hpp"

#include <Eigen/Core>

#include <vector>

namespace fissure::test {

/// An L-shaped prism, outward-oriented: the L (0,0)-(2,0)-(2,1)-(1,1)-(1,2)-(0,2) extruded from
/// z = 0 to 0.5; volume 1.5 m³; non-convex.
inline SurfaceMesh l_prism() {
  SurfaceMesh s;
  s.source_name = "L prism";
  const double xy[6][2] = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  s.vertices.resize(12, 3);
  for (int i = 0; i < 6; ++i) {
    s.vertices.row(i) << xy[i][0], xy[i][1], 0.0;
    s.vertices.row(6 + i) << xy[i][0], xy[i][1], 0.5;
  }
  std::vector<Eigen::Vector3i> faces;
  const int cap[4][3] = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}};  // fan from corner 0
  for (const auto& t : cap) {
    faces.emplace_back(t[0], t[2], t[1]);              // bottom, facing −z
    faces.emplace_back(6 + t[0], 6 + t[1], 6 + t[2]);  // top, facing +z
  }
  for (int i = 0; i < 6; ++i) {
    const int j = (i + 1) % 6;
    faces.emplace_back(i, j, 6 + j);
    faces.emplace_back(i, 6 + j, 6 + i);
  }
  s.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f) s.faces.row(static_cast<Eigen::Index>(f)) = faces[f].transpose();
  return s;
}

}  // namespace fissure::test
