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
  MassCache& cache = *m_mass_cache;
  if (kind == MassKind::Consistent) {
    std::call_once(cache.consistent_made,
                   [&] { cache.consistent = consistent_mass(*m_mesh, m_material.density, *m_pattern); });
    return cache.consistent;
  }
  std::call_once(cache.lumped_made, [&] {
    const Eigen::Index n = m_lumped_mass.size();
    cache.lumped.resize(n, n);
    cache.lumped.reserve(Eigen::VectorXi::Ones(n));
    for (Eigen::Index i = 0; i < n; ++i) cache.lumped.insert(i, i) = m_lumped_mass[i];
    cache.lumped.makeCompressed();
  });
  return cache.lumped;
}

Eigen::VectorXd ElasticBody::mass_times(MassKind kind, const Eigen::VectorXd& x) const {
  if (kind == MassKind::Lumped) return m_lumped_mass.cwiseProduct(x);
  return mass_matrix(MassKind::Consistent) * x;
}

}  // namespace fissure
