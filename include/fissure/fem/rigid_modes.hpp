#pragma once
/// Rigid-body motions of a tet mesh: the null space of its stiffness, one 6-column block per
/// connected component.

#include "fissure/mesh/tet_mesh.hpp"

#include <Eigen/Core>

#include <vector>

namespace fissure {

/// Rigid motions of component `component` (3·#nodes × 6; zero on other components): columns 0–2
/// translate along x, y, z; columns 3–5 rotate about x, y, z through the component's centroid,
/// divided by its size L (bounding-box diagonal), so every column has entries of order 1 whatever
/// the body's scale. Not orthonormal.
Eigen::MatrixXd rigid_body_modes(const TetMesh& mesh, int component);

/// The same 6 columns evaluated only at `nodes` (3·#nodes × 6), with the given centroid and size.
Eigen::MatrixXd rigid_body_modes_at(const Eigen::MatrixX3d& positions, const std::vector<int>& nodes,
                                    const Eigen::Vector3d& centroid, double size);

/// Nodes of each component, sorted, indexed by component.
std::vector<std::vector<int>> nodes_by_component(const TetMesh& mesh);

}  // namespace fissure
