#include "fissure/mesh/surface_mesh.hpp"

#include <Eigen/Geometry>

namespace fissure {

double signed_volume(const SurfaceMesh& surface) {
  double six_volume = 0.0;
  for (Eigen::Index f = 0; f < surface.faces.rows(); ++f) {
    const Eigen::Vector3d a = surface.vertices.row(surface.faces(f, 0));
    const Eigen::Vector3d b = surface.vertices.row(surface.faces(f, 1));
    const Eigen::Vector3d c = surface.vertices.row(surface.faces(f, 2));
    six_volume += a.dot(b.cross(c));
  }
  return six_volume / 6.0;
}

double surface_area(const SurfaceMesh& surface) {
  double twice_area = 0.0;
  for (Eigen::Index f = 0; f < surface.faces.rows(); ++f) {
    const Eigen::Vector3d a = surface.vertices.row(surface.faces(f, 0));
    const Eigen::Vector3d b = surface.vertices.row(surface.faces(f, 1));
    const Eigen::Vector3d c = surface.vertices.row(surface.faces(f, 2));
    twice_area += (b - a).cross(c - a).norm();
  }
  return twice_area / 2.0;
}

void SurfaceAppearance::drop_unused_materials() {
  std::vector<int> renumbered(materials.size(), -1);
  for (const int m : material) renumbered[static_cast<std::size_t>(m)] = 0;
  std::vector<Material> kept;
  for (std::size_t m = 0; m < materials.size(); ++m) {
    if (renumbered[m] < 0) continue;
    renumbered[m] = static_cast<int>(kept.size());
    kept.push_back(std::move(materials[m]));
  }
  for (int& m : material) m = renumbered[static_cast<std::size_t>(m)];
  materials = std::move(kept);
}

}  // namespace fissure
