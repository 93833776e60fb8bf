#pragma once
/// The resistance to fracture of every element: material flaws make it differ from tet to tet
/// (paper §5.1). R_c,e ~ N(R_cm, R_cvar²), R_cvar read as a standard deviation, truncated below
/// at 0.05·R_cm (paper-gaps §2). One field is drawn per trial.
#include <Eigen/Core>

#include <cstdint>

namespace fissure {

/// The truncation point of the draws, as a fraction of R_cm: no element is weaker than this.
constexpr double kResistanceFloorFraction = 0.05;

/// Tets per random stream: element e draws from Rng::derive(seed, "resistance", e / kResistanceBlock),
/// in order within its block. A block amortises the stream's derivation (a few SplitMix64
/// rounds) over many draws while keeping blocks independent, so they can be drawn in parallel.
constexpr std::size_t kResistanceBlock = 1024;

/// R_c,e (Pa) for tets 0 … tet_count−1, indexed by tet (TetMesh order): the field depends on
/// (tet index, seed, mean, stddev) only, and is the same bytes at any `threads` count. A mesh
/// whose tets are renumbered therefore gets a different (equally distributed) field.
///
/// Truncation by resampling, not clamping: a draw below kResistanceFloorFraction·mean is thrown
/// away and drawn again from the same stream. Clamping would put the whole lower tail on one value
/// (at R_cvar = R_cm, 17 % of the elements at exactly 0.05·R_cm), a spike of identical weak
/// elements that all open at the same stress, which is neither flaws nor deterministic-order
/// friendly. The floor lies below the mean, so more than half the draws are kept for any stddev
/// (at Table 3's largest R_cvar = R_cm, 83 %): < 2 draws per element on average. The price: the
/// field's mean exceeds R_cm by stddev·φ(α)/(1 − Φ(α)), α = −0.95·mean/stddev (+0.31·stddev at
/// R_cvar = R_cm, +3e-4·stddev at R_cvar = 0.25·R_cm), and its spread is below stddev.
///
/// stddev = 0 gives exactly `mean` everywhere (no draws). Throws InvalidInput when mean is not
/// positive and finite or stddev is negative or not finite. O(#tets): about the cost of one
/// normal draw per tet (docs/BENCHMARKS.md).
Eigen::VectorXd draw_resistance(std::size_t tet_count, double mean, double stddev, std::uint64_t seed,
                                int threads = 1);

}  // namespace fissure
