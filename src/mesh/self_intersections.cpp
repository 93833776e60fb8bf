// CGAL Polygon_mesh_processing lives in this translation unit only.
#include "fissure/mesh/surface_repair.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <iterator>
#include <utility>
#include <vector>

namespace fissure {

long count_self_intersections(const SurfaceMesh& surface) {
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
  Mesh mesh;
  std::vector<Mesh::Vertex_index> v;
  v.reserve(static_cast<std::size_t>(surface.vertex_count()));
  for (Eigen::Index i = 0; i < surface.vertex_count(); ++i) {
    v.push_back(mesh.add_vertex(Kernel::Point_3(surface.vertices(i, 0), surface.vertices(i, 1), surface.vertices(i, 2))));
  }
  for (Eigen::Index f = 0; f < surface.face_count(); ++f) {
    mesh.add_face(v[surface.faces(f, 0)], v[surface.faces(f, 1)], v[surface.faces(f, 2)]);
  }
  std::vector<std::pair<Mesh::Face_index, Mesh::Face_index>> pairs;
  CGAL::Polygon_mesh_processing::self_intersections(mesh, std::back_inserter(pairs));
  return static_cast<long>(pairs.size());
}

}  // namespace fissure
