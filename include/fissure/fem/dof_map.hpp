#pragma once
/// Numbering of the free degrees of freedom once supports are eliminated. Dofs are node-major:
/// dof 3·v + i is component i of node v.

#include "fissure/mesh/tet_mesh.hpp"

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <vector>

namespace fissure {

/// Throws InvalidInput when a fixed dof is outside [0, 3·#nodes), e.g. "fixed dof 3000 is outside
/// the 2997 dofs of tile.msh (999 nodes)". Every entry point taking fixed dofs calls it first
/// (the mechanism check, the static solver, the modal basis, DofMap's callers), so an index from a
/// caller's bug is refused instead of read out of bounds.
void check_fixed_dofs(const TetMesh& mesh, const std::vector<int>& fixed_dofs);

class DofMap {
public:
  DofMap() = default;
  /// All `dof_count` dofs minus `fixed_dofs` (any order, duplicates allowed). Throws InvalidInput
  /// for a fixed dof outside [0, dof_count).
  DofMap(int dof_count, const std::vector<int>& fixed_dofs);

  int dof_count() const { return static_cast<int>(m_free_index.size()); }
  int free_count() const { return static_cast<int>(m_free_dofs.size()); }
  /// Index among free dofs, or −1 for a fixed dof.
  int free_index(int dof) const { return m_free_index[static_cast<std::size_t>(dof)]; }
  const std::vector<int>& free_dofs() const { return m_free_dofs; }

  Eigen::VectorXd restrict_vector(const Eigen::VectorXd& full) const;
  /// Free entries placed back, fixed dofs zero.
  Eigen::VectorXd expand_vector(const Eigen::VectorXd& free) const;
  /// Rows and columns of the free dofs. O(nnz).
  Eigen::SparseMatrix<double> restrict_matrix(const Eigen::SparseMatrix<double>& full) const;

private:
  std::vector<int> m_free_index;
  std::vector<int> m_free_dofs;
};

}  // namespace fissure
