#pragma once
/// What the fracture simulation needs of a body beyond its FEM, computed once per mesh and shared
/// by every simulation on it (the fit runs thousands): the nearest surface normal of every tet,
/// which sets the direction of the stress increase dσ_e and of the relaxation (paper §5.1–5.2),
/// and the mesh's length scale.
#include "fissure/mesh/tet_mesh.hpp"

#include <Eigen/Core>

#include <memory>

namespace fissure {

/// Immutable after construction: safe to share between threads.
class FractureBody {
public:
  /// O(#tets log #tets): a nearest-boundary-face propagation through the mesh.
  explicit FractureBody(std::shared_ptr<const TetMesh> mesh);

  const TetMesh& mesh() const { return *m_mesh; }
  std::shared_ptr<const TetMesh> mesh_ptr() const { return m_mesh; }
  /// Outward unit normal of the boundary face nearest to each tet's centroid (row t), measured
  /// through the body.
  const Eigen::MatrixX3d& surface_normals() const { return m_surface_normals; }
  /// Distance from each tet's centroid to that face's centroid, m.
  const Eigen::VectorXd& surface_distances() const { return m_surface_distances; }
  /// The tangent-plane projector I − n nᵀ of each tet in Voigt order (xx, yy, zz, yz, xz, xy):
  /// dσ_e adds stress_rate · this row per age unit (docs/architecture.md, "Fracture simulation").
  const Eigen::Matrix<double, Eigen::Dynamic, 6, Eigen::RowMajor>& tangent_projectors() const { return m_tangent; }
  /// Mean edge length h of the mesh, m.
  double mean_edge_length() const { return m_mean_edge; }
  /// Mass of the body for `density` (kg/m³).
  double mass(double density) const { return density * m_mesh->total_volume(); }

private:
  std::shared_ptr<const TetMesh> m_mesh;
  Eigen::MatrixX3d m_surface_normals;
  Eigen::VectorXd m_surface_distances;
  Eigen::Matrix<double, Eigen::Dynamic, 6, Eigen::RowMajor> m_tangent;
  double m_mean_edge = 0.0;
};

}  // namespace fissure
