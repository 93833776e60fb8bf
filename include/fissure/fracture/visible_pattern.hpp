#pragma once
/// The crack pattern a viewer sees on a fractured body's visible face, as the planar crack graph
/// the exemplar module measures (paper §4, §6.1): so a simulation and a traced photograph are
/// measured by the same definitions (compute_pattern_stats), and the fit compares them (Eq. 5).
///
/// The visible face is the set of boundary triangles whose outward normal lies within
/// `max_angle_deg` of the view direction `up`, projected onto the plane normal to `up`. On it:
/// - crack polylines are where the crack polygons meet the visible triangles. Inside a tet a crack
///   is the zero set of the P1 interpolant of S_k (crack_surface.hpp), so on a boundary triangle
///   it is the segment where the linear interpolant of the triangle's three node values vanishes,
///   clipped for a T-junction to the arrival side of the earlier crack (as crack_polygon clips the
///   polygon, whose edge on that triangle it is). Segments of one crack in neighbouring triangles
///   share their end point on the common mesh edge, computed once per (edge, crack);
/// - junctions: a clipped segment ends on the crack that clipped it (a T, degree 3), and two
///   segments that cross inside a triangle make an X (degree 4);
/// - a crack ends freely (End) where it stops inside the face: its last tet's trace reaches a mesh
///   edge beyond which the next visible triangle's tet is not cut; it ends on the border (Border)
///   at an edge of the visible region (an edge with one visible triangle);
/// - fragments are exact polygonal areas: each visible triangle is split by its segments into
///   convex pieces (a clipped segment only splits pieces on its arrival side), and pieces of
///   neighbouring triangles whose footprints on the shared edge overlap are one fragment. A crack
///   that ends inside the face therefore separates nothing.
#include "fissure/exemplar/pattern_stats.hpp"
#include "fissure/exemplar/planar_crack_graph.hpp"
#include "fissure/fracture/crack_surface.hpp"
#include "fissure/mesh/tet_mesh.hpp"

#include <Eigen/Core>

#include <array>
#include <string>
#include <vector>

namespace fissure {

struct VisiblePatternOptions {
  /// Boundary triangles whose outward normal is within this angle of `up` are visible, degrees,
  /// in [0, 90). 45° takes a tile's top face and leaves its sides (at 90°) out.
  double max_angle_deg = 45.0;
  /// The image the pattern is compared with at the fit's resolution: its long side and the width of
  /// its crack lines, pixels (render_pattern_image draws at these by default). They set the
  /// graph's crack width and the junction probe of stats_options in metres, so the geometric
  /// statistics probe junction directions as far out as the analysis of the drawing does.
  int reference_long_side_px = 1024;  ///< ≥ kMinImageSide
  double line_width_px = 3.0;

  /// Readable problems naming the field; empty when valid.
  std::vector<std::string> problems() const;
  void validate() const;
};

/// A point of the pattern plane, metres: p ↦ (p·axis_u, p·axis_v).
struct PatternProjection {
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();      ///< unit view direction
  Eigen::Vector3d axis_u = Eigen::Vector3d::UnitX();  ///< unit, ⟂ up
  Eigen::Vector3d axis_v = Eigen::Vector3d::UnitY();  ///< up × axis_u, so (u, v, up) is right-handed
  Eigen::Vector2d project(const Eigen::Vector3d& p) const { return {p.dot(axis_u), p.dot(axis_v)}; }
};

/// The deterministic in-plane basis for `up` (unit): axis_u is the world axis least aligned with
/// up (the first of x, y, z on ties) with its up component removed, normalised; axis_v = up ×
/// axis_u. For up = +z: (x, y); for +y: (x, −z)... i.e. the view from above with x to the right.
PatternProjection pattern_projection(const Eigen::Vector3d& up);

struct VisiblePattern {
  /// False when no boundary triangle faces `up` closely enough: the graph is then empty (and
  /// invalid for compute_pattern_stats), and `empty_reason` says why. The 3-D fracture still
  /// counts: the caller reports it without a pattern.
  bool has_visible_face = false;
  std::string empty_reason;
  /// Metres in the projection plane; frame = the visible region's bounding box; total_area = the
  /// projected area of the visible triangles, which the fragment areas sum to (round-off).
  PlanarCrackGraph graph;
  /// graph.cracks[i] is part of crack source_crack[i] (index into the cracks passed in).
  std::vector<int> source_crack;
  PatternProjection projection;
  int visible_triangles = 0;
  /// The visible triangles in the projection plane, metres, counter-clockwise (for drawing the
  /// region and its mask).
  std::vector<std::array<Eigen::Vector2d, 3>> visible_triangle_corners;
  /// For compute_pattern_stats(graph, stats_options): the defaults with the junction probe floor
  /// (8 px of the reference image) in metres.
  PatternStatsOptions stats_options;
};

/// The visible pattern of cracks[0 .. crack_count) on `mesh`, seen along `up` (any finite non-zero
/// vector; normalised). Throws InvalidInput for invalid options, a zero or non-finite `up`, a
/// crack_count outside [0, cracks.size()], a cut naming a tet outside the mesh or with
/// non-finite values, or a clipped cut whose clipping crack does not cut that tet (each naming
/// the crack and the tet). O(visible triangles + Σ cuts): milliseconds for tens of cracks at 24K
/// tets (bench_visible_pattern, docs/BENCHMARKS.md).
VisiblePattern extract_visible_pattern(const TetMesh& mesh, const std::vector<CrackSurface>& cracks, int crack_count,
                                       const Eigen::Vector3d& up, const VisiblePatternOptions& options = {});

}  // namespace fissure
