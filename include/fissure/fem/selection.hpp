#pragma once
/// Selections name the parts of a mesh that supports and loads act on:
///   box:x0,x1,y0,y1,z0,z1   nodes inside the axis-aligned box (bounds inclusive)
///   ball:x,y,z,r            nodes within distance r of (x, y, z)
///   NAME                    a named set of the mesh (a gmsh physical group)
/// The faces of a selection are the boundary triangles whose three nodes are selected (for a
/// dimension-2 named set, its own triangles).

#include "fissure/mesh/tet_mesh.hpp"

#include <Eigen/Core>

#include <string>
#include <string_view>
#include <vector>

namespace fissure {

struct Selection {
  enum class Kind { Box, Ball, NamedSet };
  Kind kind = Kind::NamedSet;
  std::string spec;                ///< the text it was parsed from, for messages
  Eigen::Matrix<double, 6, 1> box;  ///< x0, x1, y0, y1, z0, z1 (Kind::Box)
  Eigen::Vector3d center;           ///< Kind::Ball
  double radius = 0.0;              ///< Kind::Ball, m
  std::string name;                 ///< Kind::NamedSet
};

/// Parses a selection spec. Throws InvalidInput naming the spec when it is malformed (wrong count
/// of numbers, non-finite values, x0 > x1, r ≤ 0, an empty name).
Selection parse_selection(std::string_view spec);

/// What a selection picks on one mesh.
struct SelectedRegion {
  std::vector<int> nodes;                  ///< sorted node indices
  std::vector<std::array<int, 3>> faces;   ///< outward-wound boundary triangles (node indices)
};

/// Resolves a selection. Coordinates are compared with a tolerance of 1e-9 × the mesh's bounding
/// box diagonal, so a box face placed exactly on a mesh face still selects nodes that round-off
/// moved by a few ulps. Throws InvalidInput when a named set does not exist (listing the names
/// that do). An empty result is returned as is; callers decide whether that is an error.
SelectedRegion resolve_selection(const TetMesh& mesh, const Selection& selection);

/// Area of each face of a region (m²), in order.
Eigen::VectorXd face_areas(const TetMesh& mesh, const SelectedRegion& region);

}  // namespace fissure
