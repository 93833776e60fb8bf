#pragma once
/// Rigid-body motions of a tet mesh: the null space of its stiffness, one 6-column block per
/// connected component.

#include "fissure/fem/elastic_body.hpp"
#include "fissure/mesh/tet_mesh.hpp"

#include <Eigen/Core>

#include <vector>

namespace fissure {

/// Where a set of nodes sits and how big it is: the mean of the node positions and the diagonal
/// of their axis-aligned bounding box (m). The one place that measures a component, for the
/// rigid modes, the mechanism check and the free-body shift.
struct NodeFrame {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  double size = 0.0;
};
NodeFrame node_frame(const TetMesh& mesh, const std::vector<int>& nodes);

/// Rigid motions of component `component` (3·#nodes × 6; zero on other components): columns 0–2
/// translate along x, y, z; columns 3–5 rotate about x, y, z through the component's centroid,
/// divided by its size L (bounding-box diagonal), so every column has entries of order 1 whatever
/// the body's scale. Not orthonormal.
Eigen::MatrixXd rigid_body_modes(const TetMesh& mesh, int component);

/// The same 6 columns evaluated only at `nodes` (3·#nodes × 6), in the given frame.
Eigen::MatrixXd rigid_body_modes_at(const Eigen::MatrixX3d& positions, const std::vector<int>& nodes,
                                    const NodeFrame& frame);

/// Nodes of each component, sorted, indexed by component.
std::vector<std::vector<int>> nodes_by_component(const TetMesh& mesh);

/// The rigid motions of every component of `body`'s mesh, M-orthonormal for the given mass
/// (RᵀMR = I): 3·#nodes × 6·#components. Throws NumericalFailure when M is not positive on them.
Eigen::MatrixXd mass_orthonormal_rigid_modes(const ElasticBody& body, MassKind mass);

}  // namespace fissure
