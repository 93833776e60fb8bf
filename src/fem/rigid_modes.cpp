#include "fissure/fem/rigid_modes.hpp"

namespace fissure {

std::vector<std::vector<int>> nodes_by_component(const TetMesh& mesh) {
  std::vector<std::vector<int>> out(static_cast<std::size_t>(mesh.component_count()));
  const auto component = mesh.component_of_node();
  for (int v = 0; v < mesh.node_count(); ++v) out[static_cast<std::size_t>(component[v])].push_back(v);
  return out;
}

Eigen::MatrixXd rigid_body_modes_at(const Eigen::MatrixX3d& positions, const std::vector<int>& nodes,
                                    const Eigen::Vector3d& centroid, double size) {
  Eigen::MatrixXd r = Eigen::MatrixXd::Zero(3 * static_cast<Eigen::Index>(nodes.size()), 6);
  const double scale = size > 0.0 ? 1.0 / size : 1.0;
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    const Eigen::Vector3d p = (positions.row(nodes[k]).transpose() - centroid) * scale;
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
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (int v : nodes) {
    const Eigen::Vector3d p = mesh.nodes().row(v);
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
    centroid += p;
  }
  centroid /= static_cast<double>(nodes.size());
  const Eigen::MatrixXd local = rigid_body_modes_at(mesh.nodes(), nodes, centroid, (hi - lo).norm());
  Eigen::MatrixXd r = Eigen::MatrixXd::Zero(3 * static_cast<Eigen::Index>(mesh.node_count()), 6);
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    r.middleRows(3 * static_cast<Eigen::Index>(nodes[k]), 3) = local.middleRows(3 * static_cast<Eigen::Index>(k), 3);
  }
  return r;
}

}  // namespace fissure
