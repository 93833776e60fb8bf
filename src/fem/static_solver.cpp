#include "fissure/fem/static_solver.hpp"

#include "fissure/base/error.hpp"
#include "fissure/fem/rigid_modes.hpp"

#include <Eigen/Cholesky>
#include <Eigen/QR>

#include <algorithm>
#include <string>

namespace fissure {

Eigen::MatrixXd mass_orthonormal_rigid_modes(const ElasticBody& body, MassKind mass) {
  const TetMesh& mesh = body.mesh();
  const int components = mesh.component_count();
  Eigen::MatrixXd r(3 * static_cast<Eigen::Index>(mesh.node_count()), 6 * components);
  for (int c = 0; c < components; ++c) r.middleCols(6 * c, 6) = rigid_body_modes(mesh, c);
  // RᵀMR is block diagonal and SPD (6 independent motions per component): R ← R L⁻ᵀ with
  // L Lᵀ = RᵀMR gives RᵀMR = I.
  Eigen::MatrixXd mr(r.rows(), r.cols());
  for (Eigen::Index j = 0; j < r.cols(); ++j) mr.col(j) = body.mass_times(mass, r.col(j));
  const Eigen::MatrixXd gram = r.transpose() * mr;
  const Eigen::LLT<Eigen::MatrixXd> llt(gram);
  if (llt.info() != Eigen::Success) {
    throw NumericalFailure("rigid-body modes: the mass matrix is not positive on the rigid motions");
  }
  return llt.matrixU().solve<Eigen::OnTheRight>(r);  // R U⁻¹ = R L⁻ᵀ
}

namespace {

// Six dofs per component that stop its rigid motions in a statically determinate way (3-2-1):
// column-pivoted QR of Rᵀ picks the 6 best-conditioned columns, i.e. dofs far apart and in
// independent directions.
std::vector<int> statically_determinate_dofs(const TetMesh& mesh) {
  std::vector<int> dofs;
  const auto groups = nodes_by_component(mesh);
  for (int c = 0; c < mesh.component_count(); ++c) {
    const Eigen::MatrixXd r = rigid_body_modes(mesh, c);
    const auto& nodes = groups[static_cast<std::size_t>(c)];
    Eigen::MatrixXd rt(6, 3 * static_cast<Eigen::Index>(nodes.size()));
    for (std::size_t k = 0; k < nodes.size(); ++k) {
      rt.middleCols(3 * static_cast<Eigen::Index>(k), 3) =
          r.middleRows(3 * static_cast<Eigen::Index>(nodes[k]), 3).transpose();
    }
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(rt);
    for (int i = 0; i < 6; ++i) {
      const int column = qr.colsPermutation().indices()[i];
      dofs.push_back(3 * nodes[static_cast<std::size_t>(column / 3)] + column % 3);
    }
  }
  std::sort(dofs.begin(), dofs.end());
  return dofs;
}

}  // namespace

StaticSolver::StaticSolver(std::shared_ptr<const ElasticBody> body, std::vector<int> fixed_dofs,
                           const StaticSolverOptions& options)
    : m_body(std::move(body)), m_fixed_dofs(std::move(fixed_dofs)), m_options(options) {
  const TetMesh& mesh = m_body->mesh();
  std::sort(m_fixed_dofs.begin(), m_fixed_dofs.end());
  m_fixed_dofs.erase(std::unique(m_fixed_dofs.begin(), m_fixed_dofs.end()), m_fixed_dofs.end());
  for (int d : m_fixed_dofs) {
    if (d < 0 || d >= 3 * mesh.node_count()) {
      throw InvalidInput("support dof " + std::to_string(d) + " does not exist");
    }
  }
  check_supports_for_mechanisms(mesh, m_fixed_dofs);

  if (free_body()) {
    m_rigid_modes = mass_orthonormal_rigid_modes(*m_body, m_options.mass);
    m_dofs = DofMap(3 * mesh.node_count(), statically_determinate_dofs(mesh));
  } else {
    m_dofs = DofMap(3 * mesh.node_count(), m_fixed_dofs);
  }
  m_reduced_stiffness = m_dofs.restrict_matrix(m_body->stiffness());
  try {
    m_factor.factorize(m_reduced_stiffness);
  } catch (const NumericalFailure& e) {
    const int column = m_factor.failed_column();
    if (column < 0) throw;
    const int dof = m_dofs.free_dofs()[static_cast<std::size_t>(column)];
    throw NumericalFailure(std::string(e.what()) + "; it is dof " + "xyz"[dof % 3] + " of node " + std::to_string(dof / 3) +
                           (mesh.source_name().empty() ? std::string() : " of " + mesh.source_name()));
  }
}

StaticSolution StaticSolver::solve(const Eigen::VectorXd& f) const {
  const Eigen::Index n = m_body->stiffness().rows();
  if (f.size() != n) {
    throw InvalidInput("static solve: load vector has " + std::to_string(f.size()) +
                       " entries, the mesh has " + std::to_string(n) + " dofs");
  }
  if (!f.allFinite()) throw InvalidInput("static solve: the load vector is not finite");

  StaticSolution out;
  out.balanced_load = f;
  if (free_body()) {
    // f' = f − M R Rᵀ f with RᵀMR = I.
    const Eigen::VectorXd modal = m_rigid_modes.transpose() * f;
    out.balanced_load -= m_body->mass_times(m_options.mass, m_rigid_modes * modal);
  }
  const Eigen::VectorXd& load = out.balanced_load;
  const double load_norm = free_body() ? f.norm() : m_dofs.restrict_vector(f).norm();
  if (load_norm == 0.0) {
    out.displacement = Eigen::VectorXd::Zero(n);
    return out;
  }

  // Solve on the kept dofs, then refine: u += K⁻¹(f − Ku) while the residual is above target.
  const Eigen::VectorXd load_free = m_dofs.restrict_vector(load);
  Eigen::VectorXd u_free = m_factor.solve(load_free);
  auto residual_of = [&](const Eigen::VectorXd& u_full) -> Eigen::VectorXd {
    // Free body: every dof counts, including the 3-2-1 dofs, whose reactions must vanish.
    // Supported body: the free dofs only, through the smaller reduced K.
    if (free_body()) return m_body->stiffness() * u_full - load;
    return m_reduced_stiffness * u_free - load_free;
  };
  Eigen::VectorXd u = m_dofs.expand_vector(u_free);
  Eigen::VectorXd residual = residual_of(u);
  out.relative_residual = residual.norm() / load_norm;
  while (out.relative_residual > m_options.target_residual &&
         out.refinement_steps < m_options.max_refinement_steps) {
    const Eigen::VectorXd r_free = free_body() ? m_dofs.restrict_vector(residual) : residual;
    u_free -= m_factor.solve(r_free);
    u = m_dofs.expand_vector(u_free);
    residual = residual_of(u);
    out.relative_residual = residual.norm() / load_norm;
    ++out.refinement_steps;
  }
  if (!(out.relative_residual <= m_options.max_residual)) {
    throw NumericalFailure("static solve: relative residual " + std::to_string(out.relative_residual) +
                           " after " + std::to_string(out.refinement_steps) +
                           " refinement steps (limit " + std::to_string(m_options.max_residual) +
                           "): the stiffness matrix is too ill-conditioned (slivers, nu near 0.5?)");
  }

  if (free_body()) {
    // Remove the rigid part: u ← u − R Rᵀ M u.
    u -= m_rigid_modes * (m_rigid_modes.transpose() * m_body->mass_times(m_options.mass, u));
  } else {
    // Reactions at the fixed dofs only: row d of K is column d (K is symmetric), so each costs
    // one sparse column instead of a full K·u.
    const SparseMatrixD& k = m_body->stiffness();
    for (int d : m_fixed_dofs) {
      double ku = 0.0;
      for (SparseMatrixD::InnerIterator it(k, d); it; ++it) ku += it.value() * u[it.row()];
      out.support_reaction[d % 3] += ku - f[d];
    }
  }
  out.displacement = std::move(u);
  return out;
}

}  // namespace fissure
