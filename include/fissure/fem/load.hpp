#pragma once
/// Loads: total forces spread over a patch of boundary faces, and gravity. Nodal force vectors
/// have 3·#nodes entries (N), node-major.
///
/// Which faces a patch loads. A box or ball often reaches through a thin body (a 15 cm ball on a
/// 10 cm plate holds faces of the top and of the bottom), and the user means one surface:
///  - by default, the face of the selection nearest to its centre (box or ball centre, by face
///    centroid) sets the reference normal n̄, and the patch is the selected faces whose outward
///    normal n has n·n̄ > 0.01 (within ≈ 89° of it): the surface the centre sits on, with its
///    curvature, but not the opposite side nor sides at right angles;
///  - `SEL^nx,ny,nz=fx,fy,fz` gives n̄ explicitly (any non-zero length), e.g.
///    `ball:0,0,0.1,0.15^0,0,1=0,0,-1e4` loads only the upward-facing faces;
///  - a named surface (a dimension-2 physical group) is loaded whole unless a normal is given.

#include "fissure/fem/selection.hpp"
#include "fissure/mesh/tet_mesh.hpp"

#include <Eigen/Core>

#include <optional>
#include <string>
#include <string_view>

namespace fissure {

/// `SEL[^nx,ny,nz]=fx,fy,fz`: a total force (N) on the boundary faces of selection SEL (those
/// facing along the optional normal).
struct LoadSpec {
  std::string spec;
  Selection selection;
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  /// The reference normal, unit length, when the spec gave one.
  std::optional<Eigen::Vector3d> normal;
};

/// Parses `SEL[^nx,ny,nz]=fx,fy,fz`. Throws InvalidInput naming the spec when malformed,
/// non-finite, or the normal is zero.
LoadSpec parse_load(std::string_view spec);

/// The boundary faces a load acts on (the rule above), outward-wound node triples, and their
/// areas (m²). Throws InvalidInput naming the spec when no face qualifies.
SelectedRegion loaded_faces(const TetMesh& mesh, const LoadSpec& load);

/// Nodal forces of a patch load: the total force is split over loaded_faces() in proportion to
/// their area, and each face's share equally over its 3 nodes (the consistent load of a uniform
/// traction on linear triangles). The nodal forces sum to the total to round-off. Throws
/// InvalidInput naming the spec when the selection touches no boundary face (facing the right way).
Eigen::VectorXd assemble_load(const TetMesh& mesh, const LoadSpec& load);

/// Nodal forces of gravity g (m/s², e.g. (0, 0, −9.81)): ρ·g·V/4 per node of each tet, which is
/// both the lumped and the consistent load of a uniform body force on linear tets.
Eigen::VectorXd gravity_load(const TetMesh& mesh, double density, const Eigen::Vector3d& g);

}  // namespace fissure
