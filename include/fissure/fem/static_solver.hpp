#pragma once
/// Static equilibrium K u = f (paper Eq. 1) by a direct sparse Cholesky factorisation, cached per
/// (body, supports). A supported body eliminates its fixed dofs; a free body (no supports) is
/// solved by inertia relief: the unbalanced part of the load is reacted by the rigid-body inertia
/// it causes, f' = f − M R (RᵀMR)⁻¹ Rᵀ f, and u is made M-orthogonal to the rigid motions
/// (NASTRAN's INREL; fem-pitfalls.md §2.1, performance.md §5.2).

#include "fissure/fem/elastic_body.hpp"
#include "fissure/fem/sparse_cholesky.hpp"
#include "fissure/fem/supports.hpp"

#include <Eigen/Core>

#include <memory>
#include <vector>

namespace fissure {

struct StaticSolverOptions {
  /// Mass used by inertia relief (free bodies only). Must match the modal basis when the two are
  /// compared.
  MassKind mass = MassKind::Lumped;
  /// Iterative-refinement steps allowed to bring the residual below `target_residual`.
  int max_refinement_steps = 3;
  /// Relative residual ‖Ku − f‖/‖f‖ aimed for. Round-off of a backward-stable Cholesky is
  /// ~1e-16·cond(K); refinement recovers 1e-10 up to cond ~1e10.
  double target_residual = 1e-10;
  /// Above this the solve is refused as numerically unreliable.
  double max_residual = 1e-8;
};

struct StaticSolution {
  Eigen::VectorXd displacement;   ///< u, 3·#nodes, m (zero on fixed dofs)
  Eigen::VectorXd balanced_load;  ///< the load actually equilibrated: f, or f' for a free body (N)
  /// ‖Ku − f‖/‖f‖ over the free dofs (all dofs for a free body, where it includes the reactions
  /// at the 3-2-1 dofs, which must vanish). 0 for a zero load.
  double relative_residual = 0.0;
  /// Total force the supports exert on the body (N): equilibrium makes it −Σf for a supported
  /// body (tested), also when the whole load sits on fixed nodes; 0 for a free body.
  Eigen::Vector3d support_reaction = Eigen::Vector3d::Zero();
  int refinement_steps = 0;
};

class StaticSolver {
public:
  /// Checks the supports for mechanisms (InvalidInput), restricts K to the free dofs and factorises
  /// it (NumericalFailure if not positive definite). `fixed_dofs` (dof 3·v + i) empty = free body.
  /// Cost: one CHOLMOD factorisation (~0.1 s at 24K tets: bench_fem in docs/BENCHMARKS.md).
  StaticSolver(std::shared_ptr<const ElasticBody> body, std::vector<int> fixed_dofs,
               const StaticSolverOptions& options = {});

  /// Displacements for the nodal forces `f` (3·#nodes, N). Throws InvalidInput for a wrong size
  /// or a non-finite f (naming the node), NumericalFailure when the residual stays above
  /// max_residual, or when the displacement overflows double precision (a load far too large for
  /// the stiffness: said so, not blamed on the mesh). Any finite load whose solution is
  /// representable is solved: f is scaled by a power of two first, so ‖f‖ never overflows.
  /// Cost: 2 triangular solves per refinement step (milliseconds at 24K tets). Thread-safe: any number
  /// of threads may solve on one solver at once (each solve has its own CHOLMOD workspace), with
  /// the same bits as a serial solve.
  StaticSolution solve(const Eigen::VectorXd& f) const;

  bool free_body() const { return m_fixed_dofs.empty(); }
  const std::vector<int>& fixed_dofs() const { return m_fixed_dofs; }
  const ElasticBody& body() const { return *m_body; }
  /// Dofs kept in the factorisation (supports eliminated; for a free body, the 3-2-1 dofs).
  const DofMap& dofs() const { return m_dofs; }
  /// K restricted to dofs().
  const Eigen::SparseMatrix<double>& reduced_stiffness() const { return m_reduced_stiffness; }
  const SparseCholesky& factorization() const { return m_factor; }
  /// Free body: the rigid motions, M-orthonormal (RᵀMR = I), 6 columns per component.
  /// Supported body: empty.
  const Eigen::MatrixXd& rigid_modes() const { return m_rigid_modes; }

private:
  std::shared_ptr<const ElasticBody> m_body;
  std::vector<int> m_fixed_dofs;
  StaticSolverOptions m_options;
  DofMap m_dofs;
  Eigen::SparseMatrix<double> m_reduced_stiffness;
  SparseCholesky m_factor;
  Eigen::MatrixXd m_rigid_modes;
};

}  // namespace fissure
