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

}  // namespace fissure
