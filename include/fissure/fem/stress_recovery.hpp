#pragma once
/// Smoothed stress from the constant per-tet stress of linear tetrahedra. With 1–3 elements
/// through a plate, neighbouring tets' stresses scatter around the bending field (the element-
/// scale stress pattern of the 24K tile differs from a 200K-tet reference by ≈ 60 %, its 3 cm
/// average by 7 %: bench_mesh_convergence). Recovering nodal stresses removes most of that
/// scatter. Recovery is linear in the tet stresses, so it is built once per mesh as a sparse
/// operator and applied to every stress field of that mesh (every step of the stress map).

#include "fissure/fem/stress.hpp"
#include "fissure/mesh/tet_mesh.hpp"

#include <Eigen/SparseCore>

namespace fissure {

enum class RecoveryMethod {
  /// Each node takes the volume-weighted mean of its tets' stresses. Exact for a constant field,
  /// never overshoots, but pulls a bending stress towards the mid-plane at surface nodes.
  NodalAverage,
  /// Zienkiewicz–Zhu patch recovery with tet centroids as sampling points: a linear stress field
  /// fitted by volume-weighted least squares over the tets within two rings of the node (the
  /// tets around the nodes of its own tets), evaluated at the node. Exact for any linear field,
  /// surface nodes included. The first ring alone is too small: it fits the scatter (61 % RMS
  /// error against 19 % with two rings on the plate of stress_recovery_test.cpp). A patch whose
  /// centroids do not span 3-D (smallest eigenvalue of the scaled normal matrix < 1e-3 of the
  /// largest) falls back to the nodal average.
  PatchFit,
};

/// Immutable once built: every const method is safe to call from any number of threads.
class StressRecovery {
public:
  /// Builds the operator for `mesh`. O(#nodes · patch size); ≈ 150 tets per patch in the tile.
  explicit StressRecovery(const TetMesh& mesh, RecoveryMethod method = RecoveryMethod::PatchFit);

  /// Nodal stresses (#nodes × 6) from tet stresses (#tets × 6). Throws InvalidInput on a wrong
  /// row count. Deterministic: a fixed sparse product, the same bits at any thread count.
  StressField nodal(const StressField& tet_stress) const;
  /// Smoothed stress of every tet: the mean of its four recovered nodal stresses (the centroid
  /// value of the piecewise-linear field they define).
  StressField smoothed_tets(const StressField& tet_stress) const;

  /// The operator: row v holds node v's weights on the tets (rows sum to 1).
  const Eigen::SparseMatrix<double, Eigen::RowMajor>& weights() const { return m_weights; }
  /// Nodes whose patch could not be fitted and that took the nodal average (PatchFit only).
  int fallback_nodes() const { return m_fallback_nodes; }
  /// True when `mesh` has the node count and tets this operator was built from.
  bool built_for(const TetMesh& mesh) const;

private:
  Eigen::MatrixX4i m_tets;
  int m_tet_count = 0;
  Eigen::SparseMatrix<double, Eigen::RowMajor> m_weights;
  int m_fallback_nodes = 0;
};

/// The recovered stress state of every tet in one call: raw stress of `body` for `u`, smoothed by
/// `recovery` (smoothed_tets), then λ_max and its direction per tet by the vectorised closed forms
/// of stress.hpp (same guarantees). About a millisecond per 20K tets on one core (bench_fem, docs/BENCHMARKS.md). Throws
/// InvalidInput when `recovery` was built for another mesh, or as compute_stress. Thread-safe.
void compute_principal_stress(const ElasticBody& body, const Eigen::VectorXd& u, const StressRecovery& recovery,
                              PrincipalStressField& out);

}  // namespace fissure
