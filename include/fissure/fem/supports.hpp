#pragma once
/// Supports fix components of the selected nodes: `SEL` fixes x, y and z; `SEL@x`, `SEL@yz`, …
/// fix only the listed components (rollers). Fixed degrees of freedom are eliminated
/// (never penalised), through a DofMap. A support set that leaves a rigid motion free (a
/// mechanism) is refused, because every solver tried solves such a system silently and wrongly
/// (fem-pitfalls.md §2.1).

#include "fissure/fem/selection.hpp"
#include "fissure/mesh/tet_mesh.hpp"

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <array>
#include <string>
#include <string_view>
#include <vector>

namespace fissure {

/// Numbering of the free degrees of freedom (dof 3·v + i of node v).
class DofMap {
public:
  DofMap() = default;
  /// All `dof_count` dofs minus `fixed_dofs` (any order, duplicates allowed).
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

/// One support: a selection and the components it fixes.
struct SupportSpec {
  std::string spec;
  Selection selection;
  std::array<bool, 3> components{true, true, true};
};

/// Parses `SEL` or `SEL@xyz` (any non-empty subset of x, y, z). Throws InvalidInput naming the
/// spec when malformed.
SupportSpec parse_support(std::string_view spec);

/// The dofs fixed by a list of supports (sorted, unique; dof 3·v + i). Throws InvalidInput naming
/// a support that selects no node.
std::vector<int> resolve_supports(const TetMesh& mesh, const std::vector<SupportSpec>& supports);

/// All three dofs of each node.
std::vector<int> dofs_of_nodes(const std::vector<int>& nodes);

/// Throws InvalidInput when the fixed dofs leave a rigid motion free in some connected component,
/// naming the component and the number of free rigid motions, e.g.
/// "supports leave 1 rigid motion free in component 0 (the fixed nodes are collinear)". With no
/// fixed dof at all the body is free (inertia relief) and nothing is thrown.
void check_supports_for_mechanisms(const TetMesh& mesh, const std::vector<int>& fixed_dofs);

}  // namespace fissure
