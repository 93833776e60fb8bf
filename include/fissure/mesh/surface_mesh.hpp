#pragma once
/// A triangle surface: the input to tetrahedralisation and the output of fragment extraction.

#include <Eigen/Core>

#include <string>
#include <vector>

namespace fissure {

/// What an input surface looks like, kept for the fragments' outer faces: its materials and
/// texture coordinates, as the file gives them. It is a triangle soup of the file's own faces
/// (before repair welds, drops or flips any), so repair never has to carry it along; the
/// fragments' outer faces take their material and UVs from the nearest of these triangles
/// (include/fissure/mesh/appearance_transfer.hpp). Empty when the file names no material and
/// has no texture coordinates.
struct SurfaceAppearance {
  struct Material {
    std::string name;
    Eigen::Vector3d colour = Eigen::Vector3d(0.62, 0.60, 0.56);  ///< linear RGB base colour
  };
  std::vector<Material> materials;
  /// One row per triangle: its corners (x₀ y₀ z₀ x₁ … z₂), m.
  Eigen::Matrix<double, Eigen::Dynamic, 9> corners;
  /// One row per triangle: its corners' texture coordinates (u₀ v₀ u₁ v₁ u₂ v₂); no rows when
  /// the file has none.
  Eigen::Matrix<double, Eigen::Dynamic, 6> uvs;
  /// Per triangle, an index into `materials` (0 when the file names none: `materials` then holds
  /// one unnamed entry).
  std::vector<int> material;

  bool empty() const { return corners.rows() == 0; }
  /// Removes the materials no triangle uses (an OBJ's default before its first `usemtl`),
  /// keeping the others' order.
  void drop_unused_materials();
  bool has_uvs() const { return uvs.rows() > 0; }
};

/// Vertices in metres; faces index vertices, counter-clockwise seen from outside for a closed,
/// outward-oriented surface.
struct SurfaceMesh {
  Eigen::MatrixX3d vertices;
  Eigen::MatrixX3i faces;
  /// Where the surface came from (file name or procedural spec), used in error messages.
  std::string source_name;
  /// The file's materials and UVs (empty for procedural bodies and files without them).
  SurfaceAppearance appearance;

  Eigen::Index vertex_count() const { return vertices.rows(); }
  Eigen::Index face_count() const { return faces.rows(); }
};

/// Signed volume enclosed by a closed surface (positive when outward-oriented). m³. O(#faces).
double signed_volume(const SurfaceMesh& surface);

/// Total area of the faces. m². O(#faces).
double surface_area(const SurfaceMesh& surface);

}  // namespace fissure
