#include "fissure/fem/stress_recovery.hpp"

#include "fissure/base/error.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <string>
#include <vector>

namespace fissure {
namespace {

using Triplets = std::vector<Eigen::Triplet<double>>;

void add_average(const TetMesh& mesh, const std::vector<int>& ring, int v, Triplets& out) {
  double total = 0.0;
  for (int t : ring) total += mesh.volumes()[t];
  for (int t : ring) out.emplace_back(v, t, mesh.volumes()[t] / total);
}

// Weights of the volume-weighted least-squares linear fit σ(x) ≈ a + B(x − x_v) over `patch`,
// evaluated at the node: a = e₀ᵀ A⁻¹ Σ_t w_t p_t σ_t, so tet t weighs w_t (A⁻¹ p_t)₀. False when
// the centroids do not determine B well.
bool add_patch_fit(const TetMesh& mesh, const std::vector<int>& patch, int v, Triplets& out) {
  if (patch.size() < 4) return false;
  const Eigen::Vector3d node = mesh.nodes().row(v).transpose();
  std::vector<Eigen::Vector4d> p(patch.size());  // (1, centroid offset / patch radius)
  double radius = 0.0, total = 0.0;
  for (std::size_t i = 0; i < patch.size(); ++i) {
    p[i] << 1.0, mesh.centroid(patch[i]) - node;
    radius = std::max(radius, p[i].tail<3>().norm());
    total += mesh.volumes()[patch[i]];
  }
  if (!(radius > 0.0)) return false;
  // Offsets scaled by the patch radius so the normal matrix is O(1) whatever the units.
  Eigen::Matrix4d normal = Eigen::Matrix4d::Zero();
  for (std::size_t i = 0; i < patch.size(); ++i) {
    p[i].tail<3>() /= radius;
    normal.noalias() += (mesh.volumes()[patch[i]] / total) * p[i] * p[i].transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eigen(normal, Eigen::EigenvaluesOnly);
  if (!(eigen.eigenvalues()[0] >= 1e-3 * eigen.eigenvalues()[3])) return false;
  const Eigen::Vector4d row0 = normal.ldlt().solve(Eigen::Vector4d::UnitX());  // A symmetric: e₀ᵀA⁻¹ = (A⁻¹e₀)ᵀ
  for (std::size_t i = 0; i < patch.size(); ++i) {
    out.emplace_back(v, patch[i], (mesh.volumes()[patch[i]] / total) * row0.dot(p[i]));
  }
  return true;
}

}  // namespace

StressRecovery::StressRecovery(const TetMesh& mesh, RecoveryMethod method)
    : m_tets(mesh.tets()), m_tet_count(mesh.tet_count()) {
  const Incidence& around = mesh.node_tets();
  Triplets triplets;
  std::vector<int> ring, patch;
  std::vector<std::uint8_t> in_patch(static_cast<std::size_t>(mesh.tet_count()), 0);
  for (int v = 0; v < mesh.node_count(); ++v) {
    ring.clear();
    ring.assign(around.begin(v), around.end(v));
    if (method == RecoveryMethod::NodalAverage) {
      add_average(mesh, ring, v, triplets);
      continue;
    }
    // Second ring: every tet around a node of the first ring, in first-seen order.
    patch.clear();
    for (int t : ring)
      for (int k = 0; k < 4; ++k)
        for (const int* s = around.begin(mesh.tets()(t, k)); s != around.end(mesh.tets()(t, k)); ++s) {
          if (!in_patch[static_cast<std::size_t>(*s)]) {
            in_patch[static_cast<std::size_t>(*s)] = 1;
            patch.push_back(*s);
          }
        }
    for (int t : patch) in_patch[static_cast<std::size_t>(t)] = 0;
    if (!add_patch_fit(mesh, patch, v, triplets)) {
      add_average(mesh, ring, v, triplets);
      ++m_fallback_nodes;
    }
  }
  m_weights.resize(mesh.node_count(), mesh.tet_count());
  m_weights.setFromTriplets(triplets.begin(), triplets.end());
}

StressField StressRecovery::nodal(const StressField& tet_stress) const {
  if (tet_stress.rows() != m_tet_count) {
    throw InvalidInput("stress recovery: " + std::to_string(tet_stress.rows()) + " tet stresses for a mesh of " +
                       std::to_string(m_tet_count) + " tets");
  }
  // Row-major copies so each weight reads one tet's six components from one cache line; Eigen's
  // sparse × column-major product gathered from six arrays and ran 8× slower at 24K tets.
  const Eigen::Matrix<double, Eigen::Dynamic, 6, Eigen::RowMajor> tets = tet_stress;
  Eigen::Matrix<double, Eigen::Dynamic, 6, Eigen::RowMajor> nodes(m_weights.rows(), 6);
  const int* outer = m_weights.outerIndexPtr();
  const int* inner = m_weights.innerIndexPtr();
  const double* value = m_weights.valuePtr();
  for (Eigen::Index v = 0; v < m_weights.rows(); ++v) {
    Eigen::Matrix<double, 1, 6> sum = Eigen::Matrix<double, 1, 6>::Zero();
    for (int i = outer[v]; i < outer[v + 1]; ++i) sum.noalias() += value[i] * tets.row(inner[i]);
    nodes.row(v) = sum;
  }
  return nodes;
}

void compute_principal_stress(const ElasticBody& body, const Eigen::VectorXd& u, const StressRecovery& recovery,
                              PrincipalStressField& out) {
  if (!recovery.built_for(body.mesh())) {
    throw InvalidInput("stress recovery: the operator was built for another mesh than " +
                       (body.mesh().source_name().empty() ? std::string("the body's") : body.mesh().source_name()));
  }
  const StressField raw = compute_stress(body, u);
  out.stress = recovery.smoothed_tets(raw);
  max_principal_of(out.stress, out.max_principal, &out.max_direction);
}

bool StressRecovery::built_for(const TetMesh& mesh) const {
  return mesh.tet_count() == m_tet_count && mesh.node_count() == m_weights.rows() && mesh.tets() == m_tets;
}

StressField StressRecovery::smoothed_tets(const StressField& tet_stress) const {
  const Eigen::Matrix<double, Eigen::Dynamic, 6, Eigen::RowMajor> nodes = nodal(tet_stress);
  StressField out(m_tet_count, 6);
  for (int t = 0; t < m_tet_count; ++t) {
    out.row(t) = 0.25 * (nodes.row(m_tets(t, 0)) + nodes.row(m_tets(t, 1)) + nodes.row(m_tets(t, 2)) +
                         nodes.row(m_tets(t, 3)));
  }
  return out;
}

}  // namespace fissure
