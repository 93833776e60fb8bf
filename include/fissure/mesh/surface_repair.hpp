#pragma once
/// Checking and safe repair of imported surfaces before they are tetrahedralised. What is safe to
/// repair (duplicate vertices, degenerate or duplicate faces, inconsistent or inward orientation)
/// is repaired and listed; what is not (holes, non-manifold edges or vertices, self-intersections)
/// is refused with the reason.

#include "fissure/mesh/surface_mesh.hpp"

#include <string>
#include <vector>

namespace fissure {

struct SurfaceRepairReport {
  /// One line per repair made, e.g. "merged 24 duplicate vertices".
  std::vector<std::string> actions;
};

struct SurfaceRepairOptions {
  /// Vertices closer than this fraction of the bounding-box diagonal are merged. 1e-7 is above
  /// float32 round-off (6e-8 relative, the precision of STL and most glTF files), so vertices a
  /// float exporter wrote twice are joined, and far below any real feature.
  double merge_tolerance = 1e-7;
  /// Check for self-intersections (CGAL, O(F log F)).
  bool check_self_intersections = true;
};

/// Returns a closed, manifold, consistently outward-oriented copy of `surface` (inner shells of
/// cavities face inward, so every shell bounds the solid correctly), and lists what it changed.
/// Throws InvalidInput naming `surface.source_name` and the reason when the surface is empty,
/// open ("open: 12 border edges"), non-manifold, non-orientable or self-intersecting.
SurfaceMesh repair_surface(const SurfaceMesh& surface, SurfaceRepairReport& report,
                           const SurfaceRepairOptions& options = {});

/// Number of pairs of faces that intersect other than along shared edges or vertices (CGAL
/// Polygon_mesh_processing). Precondition: a manifold triangle surface.
long count_self_intersections(const SurfaceMesh& surface);

}  // namespace fissure
