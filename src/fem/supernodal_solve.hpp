#pragma once
// Private to fem: triangular solves with a CHOLMOD supernodal factor for blocks of right-hand
// sides, without CHOLMOD's per-supernode BLAS calls.

#include <Eigen/Core>

#include <cholmod.h>

namespace fissure {

/// x = A⁻¹ b for the supernodal LLᵀ factor of A (`factor.is_super`, `is_ll`, int indices),
/// b and x n × c (c ≥ 1; may alias). Sequential and deterministic; only reads the factor, so
/// concurrent calls on one factor are safe.
///
/// Why: CHOLMOD's supernodal solve calls dtrsm and dgemm once per supernode and per triangle, and
/// the 3-D meshes' supernodes are small (a few to a few tens of columns), so for 2–16 right-hand
/// sides the calls' fixed cost, not the arithmetic, set the time: 8 columns took as long as 4,
/// and 2 twice as long as 1. Here the right-hand sides are interleaved row by row (the 8 values
/// of one row are one AVX-512 register) and every supernode is two register-blocked loops; the
/// factor is read twice per 8 columns. Timings in docs/BENCHMARKS.md (BM_BlockSolve).
void supernodal_block_solve(const cholmod_factor& factor, const Eigen::Ref<const Eigen::MatrixXd>& b,
                            Eigen::Ref<Eigen::MatrixXd> x);

}  // namespace fissure
