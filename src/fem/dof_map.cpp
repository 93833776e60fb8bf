#include "fissure/fem/dof_map.hpp"

#include "fissure/base/error.hpp"

#include <algorithm>
#include <string>

namespace fissure {

void check_fixed_dofs(const TetMesh& mesh, const std::vector<int>& fixed_dofs) {
  const long long dofs = 3LL * mesh.node_count();
  for (int d : fixed_dofs) {
    if (d < 0 || d >= dofs) {
      throw InvalidInput("fixed dof " + std::to_string(d) + " is outside the " + std::to_string(dofs) + " dofs of " +
                         (mesh.source_name().empty() ? std::string("the mesh") : mesh.source_name()) + " (" +
                         std::to_string(mesh.node_count()) + " nodes)");
    }
  }
}

DofMap::DofMap(int dof_count, const std::vector<int>& fixed_dofs) {
  m_free_index.assign(static_cast<std::size_t>(dof_count), 0);
  for (int d : fixed_dofs) {
    if (d < 0 || d >= dof_count) {
      throw InvalidInput("fixed dof " + std::to_string(d) + " is outside the " + std::to_string(dof_count) + " dofs");
    }
    m_free_index[static_cast<std::size_t>(d)] = -1;
  }
  for (int d = 0; d < dof_count; ++d) {
    if (m_free_index[static_cast<std::size_t>(d)] < 0) continue;
    m_free_index[static_cast<std::size_t>(d)] = static_cast<int>(m_free_dofs.size());
    m_free_dofs.push_back(d);
  }
}

Eigen::VectorXd DofMap::restrict_vector(const Eigen::VectorXd& full) const {
  Eigen::VectorXd out(free_count());
  for (int k = 0; k < free_count(); ++k) out[k] = full[m_free_dofs[static_cast<std::size_t>(k)]];
  return out;
}

Eigen::VectorXd DofMap::expand_vector(const Eigen::VectorXd& free) const {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(dof_count());
  for (int k = 0; k < free_count(); ++k) out[m_free_dofs[static_cast<std::size_t>(k)]] = free[k];
  return out;
}

Eigen::SparseMatrix<double> DofMap::restrict_matrix(const Eigen::SparseMatrix<double>& full) const {
  // Columns and rows keep their order, so the CSC structure is built directly without sorting.
  Eigen::SparseMatrix<double> out(free_count(), free_count());
  std::vector<int> outer(static_cast<std::size_t>(free_count()) + 1, 0);
  for (int k = 0; k < free_count(); ++k) {
    int count = 0;
    for (Eigen::SparseMatrix<double>::InnerIterator it(full, m_free_dofs[static_cast<std::size_t>(k)]); it; ++it) {
      count += m_free_index[static_cast<std::size_t>(it.row())] >= 0;
    }
    outer[k + 1] = outer[k] + count;
  }
  out.resizeNonZeros(outer.back());
  std::copy(outer.begin(), outer.end(), out.outerIndexPtr());
  int pos = 0;
  for (int k = 0; k < free_count(); ++k) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(full, m_free_dofs[static_cast<std::size_t>(k)]); it; ++it) {
      const int row = m_free_index[static_cast<std::size_t>(it.row())];
      if (row < 0) continue;
      out.innerIndexPtr()[pos] = row;
      out.valuePtr()[pos] = it.value();
      ++pos;
    }
  }
  return out;
}

}  // namespace fissure
