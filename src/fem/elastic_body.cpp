#include "fissure/fem/elastic_body.hpp"

namespace fissure {

ElasticBody::ElasticBody(std::shared_ptr<const TetMesh> mesh, const ElasticMaterial& material, int threads)
    : m_mesh(std::move(mesh)), m_material(material) {
  m_material.validate();
  m_gradients = compute_tet_gradients(*m_mesh);
  m_pattern = std::make_unique<StiffnessPattern>(*m_mesh);
  m_stiffness = assemble_stiffness(*m_mesh, m_gradients, m_material, *m_pattern, threads);
  m_lumped_mass = fissure::lumped_mass(*m_mesh, m_material.density);
}

const SparseMatrixD& ElasticBody::mass_matrix(MassKind kind) const {
  if (kind == MassKind::Consistent) {
    if (m_consistent_mass.nonZeros() == 0) {
      m_consistent_mass = consistent_mass(*m_mesh, m_material.density, *m_pattern);
    }
    return m_consistent_mass;
  }
  if (m_lumped_matrix.nonZeros() == 0) {
    m_lumped_matrix.resize(m_lumped_mass.size(), m_lumped_mass.size());
    m_lumped_matrix.reserve(Eigen::VectorXi::Ones(m_lumped_mass.size()));
    for (Eigen::Index i = 0; i < m_lumped_mass.size(); ++i) m_lumped_matrix.insert(i, i) = m_lumped_mass[i];
    m_lumped_matrix.makeCompressed();
  }
  return m_lumped_matrix;
}

Eigen::VectorXd ElasticBody::mass_times(MassKind kind, const Eigen::VectorXd& x) const {
  if (kind == MassKind::Lumped) return m_lumped_mass.cwiseProduct(x);
  return mass_matrix(MassKind::Consistent) * x;
}

}  // namespace fissure
