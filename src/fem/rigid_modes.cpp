#include "fissure/fem/rigid_modes.hpp"

#include "fissure/base/error.hpp"

#include <Eigen/Cholesky>

#include <cmath>

namespace fissure {

NodeFrame node_frame(const TetMesh& mesh, const std::vector<int>& nodes) {
  NodeFrame frame;
  if (nodes.empty()) return frame;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
  for (int v : nodes) {
    const Eigen::Vector3d p = mesh.nodes().row(v);
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
    frame.centroid += p;
  }
  frame.centroid /= static_cast<double>(nodes.size());
  frame.size = (hi - lo).norm();
  return frame;
}

std::vector<std::vector<int>> nodes_by_component(const TetMesh& mesh) {
  std::vector<std::vector<int>> out(static_cast<std::size_t>(mesh.component_count()));
  const auto component = mesh.component_of_node();
  for (int v = 0; v < mesh.node_count(); ++v) out[static_cast<std::size_t>(component[v])].push_back(v);
  return out;
}

Eigen::MatrixXd rigid_body_modes_at(const Eigen::MatrixX3d& positions, const std::vector<int>& nodes,
                                    const NodeFrame& frame) {
  Eigen::MatrixXd r = Eigen::MatrixXd::Zero(3 * static_cast<Eigen::Index>(nodes.size()), 6);
  const double scale = frame.size > 0.0 ? 1.0 / frame.size : 1.0;
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    const Eigen::Vector3d p = (positions.row(nodes[k]).transpose() - frame.centroid) * scale;
    const Eigen::Index row = 3 * static_cast<Eigen::Index>(k);
    for (int i = 0; i < 3; ++i) r(row + i, i) = 1.0;
    // ω × p for ω = e_x, e_y, e_z.
    r(row + 1, 3) = -p.z();
    r(row + 2, 3) = p.y();
    r(row + 0, 4) = p.z();
    r(row + 2, 4) = -p.x();
    r(row + 0, 5) = -p.y();
    r(row + 1, 5) = p.x();
  }
  return r;
}

Eigen::MatrixXd rigid_body_modes(const TetMesh& mesh, int component) {
  const auto groups = nodes_by_component(mesh);
  const auto& nodes = groups.at(static_cast<std::size_t>(component));
  const Eigen::MatrixXd local = rigid_body_modes_at(mesh.nodes(), nodes, node_frame(mesh, nodes));
  Eigen::MatrixXd r = Eigen::MatrixXd::Zero(3 * static_cast<Eigen::Index>(mesh.node_count()), 6);
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    r.middleRows(3 * static_cast<Eigen::Index>(nodes[k]), 3) = local.middleRows(3 * static_cast<Eigen::Index>(k), 3);
  }
  return r;
}

Eigen::MatrixXd mass_orthonormal_rigid_modes(const ElasticBody& body, MassKind mass) {
  const TetMesh& mesh = body.mesh();
  const int components = mesh.component_count();
  Eigen::MatrixXd r(3 * static_cast<Eigen::Index>(mesh.node_count()), 6 * components);
  for (int c = 0; c < components; ++c) r.middleCols(6 * c, 6) = rigid_body_modes(mesh, c);
  // RᵀMR is block diagonal and SPD (6 independent motions per component): R ← R L⁻ᵀ with
  // L Lᵀ = RᵀMR gives RᵀMR = I.
  Eigen::MatrixXd mr(r.rows(), r.cols());
  for (Eigen::Index j = 0; j < r.cols(); ++j) mr.col(j) = body.mass_times(mass, r.col(j));
  const Eigen::MatrixXd gram = r.transpose() * mr;
  const Eigen::LLT<Eigen::MatrixXd> llt(gram);
  if (llt.info() != Eigen::Success) {
    throw NumericalFailure("rigid-body modes: the mass matrix is not positive on the rigid motions");
  }
  return llt.matrixU().solve<Eigen::OnTheRight>(r);  // R U⁻¹ = R L⁻ᵀ
}

}  // namespace fissure
