#pragma once
/// A triangle surface: the input to tetrahedralisation and the output of fragment extraction.

#include <Eigen/Core>

#include <string>

namespace fissure {

/// Vertices in metres; faces index vertices, counter-clockwise seen from outside for a closed,
/// outward-oriented surface.
struct SurfaceMesh {
  Eigen::MatrixX3d vertices;
  Eigen::MatrixX3i faces;
  /// Where the surface came from (file name or procedural spec), used in error messages.
  std::string source_name;

  Eigen::Index vertex_count() const { return vertices.rows(); }
  Eigen::Index face_count() const { return faces.rows(); }
};

/// Signed volume enclosed by a closed surface (positive when outward-oriented). m³. O(#faces).
double signed_volume(const SurfaceMesh& surface);

/// Total area of the faces. m². O(#faces).
double surface_area(const SurfaceMesh& surface);

}  // namespace fissure
