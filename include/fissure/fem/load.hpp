#pragma once
/// Loads: total forces spread over a patch of boundary faces, and gravity. Nodal force vectors
/// have 3·#nodes entries (N), node-major.

#include "fissure/fem/selection.hpp"
#include "fissure/mesh/tet_mesh.hpp"

#include <Eigen/Core>

#include <string>
#include <string_view>

namespace fissure {

/// `SEL=fx,fy,fz`: a total force (N) on the boundary faces of selection SEL.
struct LoadSpec {
  std::string spec;
  Selection selection;
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
};

/// Parses `SEL=fx,fy,fz`. Throws InvalidInput naming the spec when malformed or non-finite.
LoadSpec parse_load(std::string_view spec);

/// Nodal forces of a patch load: the total force is split over the selection's boundary faces in
/// proportion to their area, and each face's share equally over its 3 nodes (the consistent load
/// of a uniform traction on linear triangles). The nodal forces sum to the total to round-off.
/// Throws InvalidInput naming the spec when the selection touches no boundary face.
Eigen::VectorXd assemble_load(const TetMesh& mesh, const LoadSpec& load);

/// Nodal forces of gravity g (m/s², e.g. (0, 0, −9.81)): ρ·g·V/4 per node of each tet, which is
/// both the lumped and the consistent load of a uniform body force on linear tets.
Eigen::VectorXd gravity_load(const TetMesh& mesh, double density, const Eigen::Vector3d& g);

}  // namespace fissure
