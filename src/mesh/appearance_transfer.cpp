#include "fissure/mesh/appearance_transfer.hpp"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <Eigen/Geometry>

#include <vector>

namespace fissure {

namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Triangle = Kernel::Triangle_3;
using Iterator = std::vector<Triangle>::const_iterator;
using AabbTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, CGAL::AABB_triangle_primitive<Kernel, Iterator>>>;

Eigen::Vector3d corner(const SurfaceAppearance& a, int t, int k) {
  return a.corners.row(t).segment<3>(3 * k).transpose();
}

}  // namespace

struct AppearanceTransfer::Tree {
  std::vector<Triangle> triangles;
  std::vector<int> index;  // of each tree triangle in the appearance
  AabbTree tree;
};

AppearanceTransfer::AppearanceTransfer(const SurfaceAppearance& appearance)
    : m_appearance(appearance), m_tree(std::make_unique<Tree>()) {
  const auto point = [&](int t, int k) {
    const Eigen::Vector3d x = corner(appearance, t, k);
    return Kernel::Point_3(x.x(), x.y(), x.z());
  };
  for (int pass = 0; pass < 2 && m_tree->triangles.empty(); ++pass) {
    for (int t = 0; t < static_cast<int>(appearance.corners.rows()); ++t) {
      const Triangle triangle(point(t, 0), point(t, 1), point(t, 2));
      // Degenerate triangles have no plane to project on; kept only if all are (second pass).
      if (pass == 0 && triangle.is_degenerate()) continue;
      m_tree->triangles.push_back(triangle);
      m_tree->index.push_back(t);
    }
  }
  m_tree->tree.insert(m_tree->triangles.cbegin(), m_tree->triangles.cend());
  m_tree->tree.build();
  m_tree->tree.accelerate_distance_queries();
}

AppearanceTransfer::~AppearanceTransfer() = default;

int AppearanceTransfer::nearest_triangle(const Eigen::Vector3d& point) const {
  const auto hit = m_tree->tree.closest_point_and_primitive(Kernel::Point_3(point.x(), point.y(), point.z()));
  return m_tree->index[static_cast<std::size_t>(hit.second - m_tree->triangles.cbegin())];
}

Eigen::Vector2d AppearanceTransfer::uv_at(int t, const Eigen::Vector3d& point) const {
  if (!m_appearance.has_uvs()) return Eigen::Vector2d::Zero();
  const Eigen::Vector3d a = corner(m_appearance, t, 0), b = corner(m_appearance, t, 1), c = corner(m_appearance, t, 2);
  // Barycentric coordinates of the projection onto the plane: areas against its normal n.
  const Eigen::Vector3d n = (b - a).cross(c - a);
  const double area2 = n.squaredNorm();
  const auto uv = [&](int k) { return Eigen::Vector2d(m_appearance.uvs.row(t).segment<2>(2 * k).transpose()); };
  if (!(area2 > 0.0)) return uv(0);
  // w_b is the area of (a, p, c) over that of (a, b, c), signed along n; so for w_c.
  const double wb = (point - a).cross(c - a).dot(n) / area2;
  const double wc = (b - a).cross(point - a).dot(n) / area2;
  return (1.0 - wb - wc) * uv(0) + wb * uv(1) + wc * uv(2);
}

int AppearanceTransfer::material_of(int t) const {
  return m_appearance.material.empty() ? 0 : m_appearance.material[static_cast<std::size_t>(t)];
}

}  // namespace fissure
