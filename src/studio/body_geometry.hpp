#pragma once
// What the viewport draws for one body, built once when the body changes (never per frame):
// flat-shaded triangles (position, normal, colour, crack flag per vertex), the crack lines where
// crack faces meet the body's surface, and a draw range per fragment so moving, hiding or
// exploding a fragment is a uniform, not a rebuild. Qt-free: tested without a window.
#include "fissure/fracture/fragment_mesh.hpp"
#include "fissure/io/scene_import.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <vector>

namespace fissure::studio {

struct BodyGeometry {
  static constexpr int kSurfaceFloats = 10;  ///< position 3, normal 3, colour 3, crack 1
  static constexpr int kLineFloats = 6;      ///< position 3, colour 3
  std::vector<float> surface;                ///< triangles, 3 vertices each
  std::vector<float> lines;                  ///< segments, 2 vertices each
  struct Range {
    int fragment = -1;                       ///< -1: the whole body
    int first = 0, count = 0;                ///< surface vertices
    int first_line = 0, line_count = 0;      ///< line vertices
  };
  std::vector<Range> ranges;
  Eigen::AlignedBox3d bounds;                ///< world, without offsets
  int triangle_count() const { return static_cast<int>(surface.size() / (3 * kSurfaceFloats)); }
};

/// A body not fractured: its meshes in world coordinates, each in its scene material's colour.
BodyGeometry whole_body_geometry(const ImportedScene& scene, const SceneBody& body);

/// A fractured body's fragments (world coordinates, m, drawn × `scale`: 1 / the scene's metres
/// per unit, so they sit on the scene's own bodies): outer faces in `colour`, crack faces flagged
/// (the shader gives them the crack colour), crack lines in `line_colour`.
BodyGeometry fragment_geometry(const std::vector<FragmentMesh>& fragments, const Eigen::Vector3d& colour,
                               const Eigen::Vector3d& line_colour, double scale = 1.0);

/// The base colour a body is drawn in: its first mesh's scene material's (0.8 grey without one).
Eigen::Vector3d body_colour(const ImportedScene& scene, const SceneBody& body);

/// The nearest hit of the ray (origin, unit direction) on the triangles of `g`'s range `r`
/// moved by `offset`: its distance along the ray, or a negative number for none.
double ray_hit(const BodyGeometry& g, const BodyGeometry::Range& r, const Eigen::Vector3d& offset,
               const Eigen::Vector3d& origin, const Eigen::Vector3d& direction);

}  // namespace fissure::studio
