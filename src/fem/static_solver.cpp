#include "fissure/fem/static_solver.hpp"

#include "fissure/base/error.hpp"
#include "fissure/base/number_text.hpp"
#include "fissure/fem/rigid_modes.hpp"

#include <Eigen/Cholesky>
#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <string>

namespace fissure {

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
  check_supports_for_mechanisms(mesh, m_fixed_dofs);  // also refuses dofs outside the mesh

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
    throw NumericalFailure(std::string(e.what()) + "; it is dof " + "xyz"[dof % 3] + " of " + mesh.node_label(dof / 3) +
                           (mesh.source_name().empty() ? std::string() : " of " + mesh.source_name()));
  }
}

namespace {

// The first non-finite entry of a nodal vector as "node 12 (y)", for messages.
std::string first_non_finite(const TetMesh& mesh, const Eigen::VectorXd& v) {
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i])) return mesh.node_label(static_cast<int>(i / 3)) + " (" + "xyz"[i % 3] + ")";
  }
  return {};
}

}  // namespace

StaticSolution StaticSolver::solve(const Eigen::VectorXd& f) const {
  const TetMesh& mesh = m_body->mesh();
  const Eigen::Index n = m_body->stiffness().rows();
  if (f.size() != n) {
    throw InvalidInput("static solve: load vector has " + std::to_string(f.size()) +
                       " entries, the mesh has " + std::to_string(n) + " dofs");
  }
  if (!f.allFinite()) throw InvalidInput("static solve: the load on " + first_non_finite(mesh, f) + " is not finite");

  // The system is linear, so it is solved for f scaled by a power of two that brings its largest
  // entry to [0.5, 1): the scaling is exact (the bits of u are those of the unscaled solve), and
  // norms and residuals can neither overflow (a 1e300 N load) nor underflow. u is scaled back at
  // the end, and only then can it overflow, which is reported as such.
  const double peak = f.cwiseAbs().maxCoeff();
  int exponent = 0;
  if (peak > 0.0) std::frexp(peak, &exponent);
  const Eigen::VectorXd scaled = peak > 0.0 ? Eigen::VectorXd(f * std::ldexp(1.0, -exponent)) : f;
  auto refuse_overflow = [&](const Eigen::VectorXd& u) {
    if (u.allFinite()) return;
    throw NumericalFailure("static solve: the displacement overflows double precision on " + first_non_finite(mesh, u) +
                           " (largest load " + format_number(peak) + " N, E = " +
                           format_number(m_body->material().youngs_modulus) + " Pa): the load is too large for the stiffness");
  };

  StaticSolution out;
  Eigen::VectorXd load = scaled;  // the balanced load, scaled
  if (free_body()) {
    // f' = f − M R Rᵀ f with RᵀMR = I.
    const Eigen::VectorXd modal = m_rigid_modes.transpose() * scaled;
    load -= m_body->mass_times(m_options.mass, m_rigid_modes * modal);
  }
  const double load_norm = free_body() ? scaled.norm() : m_dofs.restrict_vector(scaled).norm();

  Eigen::VectorXd u = Eigen::VectorXd::Zero(n);
  if (load_norm > 0.0) {
    // Solve on the kept dofs, then refine: u += K⁻¹(f − Ku) while the residual is above target.
    const Eigen::VectorXd load_free = m_dofs.restrict_vector(load);
    Eigen::VectorXd u_free = m_factor.solve(load_free);
    auto residual_of = [&](const Eigen::VectorXd& u_full) -> Eigen::VectorXd {
      // Free body: every dof counts, including the 3-2-1 dofs, whose reactions must vanish.
      // Supported body: the free dofs only, through the smaller reduced K.
      if (free_body()) return m_body->stiffness() * u_full - load;
      return m_reduced_stiffness * u_free - load_free;
    };
    u = m_dofs.expand_vector(u_free);
    refuse_overflow(u);
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
      throw NumericalFailure("static solve: relative residual " + format_number(out.relative_residual, 3) + " after " +
                             std::to_string(out.refinement_steps) + " refinement steps (limit " +
                             format_number(m_options.max_residual, 3) +
                             "): the stiffness matrix is too ill-conditioned (slivers, nu near 0.5?)");
    }
    if (free_body()) {
      // Remove the rigid part: u ← u − R Rᵀ M u.
      u -= m_rigid_modes * (m_rigid_modes.transpose() * m_body->mass_times(m_options.mass, u));
    }
  }

  if (!free_body()) {
    // Reactions at the fixed dofs only: row d of K is column d (K is symmetric), so each costs
    // one sparse column instead of a full K·u. Computed also when no load reaches a free dof
    // (u = 0): the supports then carry the whole load.
    const SparseMatrixD& k = m_body->stiffness();
    for (int d : m_fixed_dofs) {
      double ku = 0.0;
      for (SparseMatrixD::InnerIterator it(k, d); it; ++it) ku += it.value() * u[it.row()];
      out.support_reaction[d % 3] += ku - scaled[d];
    }
  }
  // Back to the caller's units; the scaling is by a power of two, hence exact.
  const double unscale = std::ldexp(1.0, exponent);
  out.support_reaction *= unscale;
  out.balanced_load = load * unscale;
  u *= unscale;
  refuse_overflow(u);
  out.displacement = std::move(u);
  return out;
}

}  // namespace fissure
