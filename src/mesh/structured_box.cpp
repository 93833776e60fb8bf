#include "fissure/mesh/structured_box.hpp"

#include "fissure/base/error.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <string>

namespace fissure {

TetMesh make_structured_box(const Eigen::Vector3d& min_corner, const Eigen::Vector3d& size, int nx,
                            int ny, int nz) {
  if (nx < 1 || ny < 1 || nz < 1) {
    throw InvalidInput("structured box: cell counts must be >= 1 (got " + std::to_string(nx) + ", " +
                       std::to_string(ny) + ", " + std::to_string(nz) + ")");
  }
  if (!min_corner.allFinite() || !size.allFinite() || (size.array() <= 0.0).any()) {
    throw InvalidInput("structured box: sizes must be positive and finite");
  }
  const int px = nx + 1, py = ny + 1, pz = nz + 1;
  auto node = [&](int i, int j, int k) { return i + px * (j + py * k); };

  Eigen::MatrixX3d nodes(static_cast<Eigen::Index>(px) * py * pz, 3);
  for (int k = 0; k < pz; ++k)
    for (int j = 0; j < py; ++j)
      for (int i = 0; i < px; ++i) {
        nodes.row(node(i, j, k)) << min_corner.x() + size.x() * i / nx,
            min_corner.y() + size.y() * j / ny, min_corner.z() + size.z() * k / nz;
      }

  // Kuhn split: the 6 monotone paths from cube corner 0 to corner 7 (bit 0 = x, 1 = y, 2 = z).
  // Every cube uses the same main diagonal, so shared faces are split identically.
  const int paths[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7},
                           {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};
  Eigen::MatrixX4i tets(static_cast<Eigen::Index>(nx) * ny * nz * 6, 4);
  Eigen::Index t = 0;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        int corner[8];
        for (int c = 0; c < 8; ++c) corner[c] = node(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1));
        for (const auto& path : paths) {
          Eigen::Vector4i tet(corner[path[0]], corner[path[1]], corner[path[2]], corner[path[3]]);
          const Eigen::Vector3d a = nodes.row(tet[0]), b = nodes.row(tet[1]), c = nodes.row(tet[2]),
                                d = nodes.row(tet[3]);
          if ((b - a).dot((c - a).cross(d - a)) < 0.0) std::swap(tet[2], tet[3]);
          tets.row(t++) = tet.transpose();
        }
      }

  // Named boundary faces: collect boundary triangles by the box side they lie on.
  TetMesh plain(nodes, tets, "structured box");
  const char* names[6] = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
  std::vector<NamedSet> sets(6);
  for (int s = 0; s < 6; ++s) {
    sets[s].name = names[s];
    sets[s].dimension = 2;
  }
  // The max planes use the same expression as the node coordinates, so comparisons are exact.
  const int counts[3] = {nx, ny, nz};
  for (const BoundaryFace& face : plain.boundary_faces()) {
    for (int axis = 0; axis < 3; ++axis) {
      for (int side = 0; side < 2; ++side) {
        const double plane =
            side == 0 ? min_corner[axis]
                      : min_corner[axis] + size[axis] * counts[axis] / counts[axis];
        bool on = true;
        for (int v : face.nodes) on = on && nodes(v, axis) == plane;
        if (on) sets[2 * axis + side].faces.push_back(face.nodes);
      }
    }
  }
  for (NamedSet& set : sets) {
    for (const auto& face : set.faces) set.nodes.insert(set.nodes.end(), face.begin(), face.end());
    std::sort(set.nodes.begin(), set.nodes.end());
    set.nodes.erase(std::unique(set.nodes.begin(), set.nodes.end()), set.nodes.end());
  }
  return TetMesh(std::move(nodes), std::move(tets), "box", std::move(sets));
}

}  // namespace fissure
