#pragma once
/// Global stiffness and mass matrices of linear tetrahedra. Degrees of freedom are node-major:
/// dof 3·v + i is component i of node v.

#include "fissure/fem/elastic_material.hpp"
#include "fissure/fem/tet_gradients.hpp"
#include "fissure/mesh/tet_mesh.hpp"

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <memory>
#include <vector>

namespace fissure {

using SparseMatrixD = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

/// The sparsity pattern of K (and of the consistent M): 3×3 blocks for every pair of nodes that
/// share a tet, both triangles stored. Built once per mesh, then K and M are assembled into it by
/// plain additions (no sorting), which is ~10× faster than triplets.
class StiffnessPattern {
public:
  explicit StiffnessPattern(const TetMesh& mesh);

  /// An all-zero matrix with the full pattern.
  SparseMatrixD empty_matrix() const;
  /// Position in the value array of entry (3a+i, 3b+j), for local nodes a, b of tet t:
  /// slot(t, a, b) + (column offset of j) + i. Internal to assembly.
  int block_slot(int tet, int a, int b, int j) const {
    return m_column_start[3 * m_tet_nodes(tet, b) + j] + 3 * m_rank(tet, 4 * b + a);
  }
  int dof_count() const { return static_cast<int>(m_column_start.size()) - 1; }

private:
  Eigen::Matrix<int, Eigen::Dynamic, 4> m_tet_nodes;
  std::vector<int> m_column_start;       // CSC column pointers, size dofs + 1
  std::vector<int> m_row_index;          // CSC row indices
  Eigen::Matrix<int, Eigen::Dynamic, 16> m_rank;  // rank of node a among node b's neighbours
};

/// Stiffness K = Σ_e V_e B_eᵀ D B_e (N/m), symmetric positive semi-definite with the 6 rigid
/// motions (per component) in its null space. Element blocks are computed on `threads` threads and
/// added in tet order, so K is bit-identical at any thread count. O(#tets).
SparseMatrixD assemble_stiffness(const TetMesh& mesh, const TetGradients& gradients,
                                 const ElasticMaterial& material, const StiffnessPattern& pattern,
                                 int threads = 1);

/// Lumped mass per dof (kg): ρV/4 of each tet to each of its nodes, repeated for x, y, z.
Eigen::VectorXd lumped_mass(const TetMesh& mesh, double density);

/// Consistent mass M_ab = ρV/20·(1 + δ_ab)·I₃ (kg), in the stiffness pattern.
SparseMatrixD consistent_mass(const TetMesh& mesh, double density, const StiffnessPattern& pattern);

}  // namespace fissure
