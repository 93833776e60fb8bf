#pragma once
/// A tet mesh with an elastic material: its element gradients, stiffness K and mass M. Built once
/// per (mesh, material) and shared by the static solver and the modal analysis.

#include "fissure/fem/assembly.hpp"
#include "fissure/fem/elastic_material.hpp"
#include "fissure/fem/tet_gradients.hpp"
#include "fissure/mesh/tet_mesh.hpp"

#include <Eigen/Core>

#include <memory>
#include <mutex>

namespace fissure {

/// Which mass matrix a computation uses (fem-pitfalls.md §2.3: lumped is diagonal, positive and
/// cheap, and slightly lower in frequency; consistent has the exact second moment).
enum class MassKind { Lumped, Consistent };

/// Immutable after construction except for two lazily built mass matrices, which are made once
/// under std::call_once: every const method is safe to call from any number of threads at once
/// (the fit runs trials on one shared body).
class ElasticBody {
public:
  /// Validates the material (InvalidInput), computes gradients and assembles K on `threads`
  /// threads (bit-identical at any count) and the lumped mass. O(#tets).
  ElasticBody(std::shared_ptr<const TetMesh> mesh, const ElasticMaterial& material, int threads = 1);

  const TetMesh& mesh() const { return *m_mesh; }
  std::shared_ptr<const TetMesh> mesh_ptr() const { return m_mesh; }
  const ElasticMaterial& material() const { return m_material; }
  const TetGradients& gradients() const { return m_gradients; }
  const StiffnessPattern& pattern() const { return *m_pattern; }
  /// K, 3n × 3n, both triangles stored, N/m.
  const SparseMatrixD& stiffness() const { return m_stiffness; }
  /// Lumped mass per dof, kg.
  const Eigen::VectorXd& lumped_mass() const { return m_lumped_mass; }
  /// M of the requested kind as a sparse matrix (diagonal for Lumped). Both are built on first use
  /// (thread-safe); the reference stays valid for the body's lifetime.
  const SparseMatrixD& mass_matrix(MassKind kind) const;
  /// M·x for the requested kind.
  Eigen::VectorXd mass_times(MassKind kind, const Eigen::VectorXd& x) const;

private:
  std::shared_ptr<const TetMesh> m_mesh;
  ElasticMaterial m_material;
  TetGradients m_gradients;
  std::unique_ptr<StiffnessPattern> m_pattern;
  SparseMatrixD m_stiffness;
  Eigen::VectorXd m_lumped_mass;
  // Lazily built matrices, in their own block so the body stays movable (once_flag is not).
  struct MassCache {
    std::once_flag lumped_made, consistent_made;
    SparseMatrixD lumped, consistent;
  };
  std::unique_ptr<MassCache> m_mass_cache = std::make_unique<MassCache>();
};

}  // namespace fissure
