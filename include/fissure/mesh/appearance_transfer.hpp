#pragma once
/// Carries an input surface's materials and UVs onto the fragments' outer faces.
///
/// The tet mesh's boundary is the mesher's approximation of the input (within its facet
/// distance), so an outer face of a fragment lies on the input surface but shares none of its
/// vertices. Each outer triangle takes the material of the input triangle nearest its centroid,
/// and each of its corners the UV that triangle's linear UV map gives at the corner's projection
/// onto its plane. One triangle per fragment triangle keeps the UVs of a fragment triangle
/// continuous where the input's UV map has a seam (a fragment triangle straddling the seam is
/// textured from its centroid's side). Cost: O(n log n) to build over n input triangles, then
/// O(log n) per query (CGAL's AABB tree). Queries are const and safe from several threads.

#include "fissure/mesh/surface_mesh.hpp"

#include <Eigen/Core>

#include <memory>

namespace fissure {

class AppearanceTransfer {
public:
  /// Precondition: !appearance.empty(). `appearance` must outlive this object.
  explicit AppearanceTransfer(const SurfaceAppearance& appearance);
  ~AppearanceTransfer();
  AppearanceTransfer(const AppearanceTransfer&) = delete;
  AppearanceTransfer& operator=(const AppearanceTransfer&) = delete;

  /// The input triangle nearest to `point` (an index into the appearance's rows). Triangles of
  /// zero area are never returned unless every one is.
  int nearest_triangle(const Eigen::Vector3d& point) const;

  /// The UV at `point` of input triangle `t`: its linear UV map at the point's projection onto
  /// the triangle's plane (extrapolated beyond its edges). Zero when the input has no UVs.
  Eigen::Vector2d uv_at(int t, const Eigen::Vector3d& point) const;

  /// The material (index into the appearance's materials) of input triangle `t`.
  int material_of(int t) const;

private:
  struct Tree;
  const SurfaceAppearance& m_appearance;
  std::unique_ptr<Tree> m_tree;
};

}  // namespace fissure
