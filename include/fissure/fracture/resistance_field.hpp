#pragma once
/// The resistance to fracture of every element: material flaws make it differ from tet to tet
/// (paper §5.1). R_c,e ~ N(R_cm, R_cvar²), R_cvar read as a standard deviation, truncated below
/// at 0.05·R_cm (paper-gaps §2). One field is drawn per trial.
#include "fissure/fracture/fracture_params.hpp"

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

/// R_c,e (Pa) at `points` (one row per element, its centroid; metres) as a spatially correlated
/// random field, so the same body meshed at any resolution, or with its elements numbered in any
/// order, gets the same resistance at the same place: the fracture is then a property of the
/// body, not of its mesh (docs/fracture.md, "Resistance field"). With i.i.d. draws per element
/// a finer mesh has more weak elements: the 1 m demo tile gave 202, 253 and 331 visible
/// fragments at 7K, 24K and 54K tets.
///
/// The field: independent standard normals g at the nodes of a cubic lattice of spacing
/// `correlation_length` (node (i, j, k) draws from Rng::derive(seed, "resistance_field", hash of
/// i, j, k)), blended at a point by the smoothstep trilinear weights w of its cell and divided by
/// √Σw², so it is exactly N(0, 1) at every point; values at points more than one spacing apart
/// in any axis are independent. Each value z is then mapped by quantiles onto the normal
/// N(mean, stddev²) truncated below at kResistanceFloorFraction·mean, R = mean + stddev·Q⁻¹(Q(α)·Q(z)),
/// α = (floor − mean)/stddev, Q the standard normal tail (computed from the lower tail for
/// z < 0): the same marginal distribution as draw_resistance, and z's correlations, monotonically.
///
/// correlation_length = 0 is draw_resistance(points.rows(), mean, stddev, seed, threads): one
/// independent draw per element, by index (the paper's). Throws InvalidInput for what
/// draw_resistance refuses, a negative or non-finite correlation length, non-finite points, or
/// a body whose coordinates exceed 2^52 spacings. Same bytes at any `threads` count. O(#points)
/// plus O(lattice nodes over the points' bounding box) when that is at most a few times the
/// points (else per point): about a normal draw per point (docs/BENCHMARKS.md).
Eigen::VectorXd draw_resistance_field(const Eigen::MatrixX3d& points, double mean, double stddev,
                                      double correlation_length, std::uint64_t seed, int threads = 1);

/// The resistance field a simulation of `params` uses on elements with these centroids:
/// draw_resistance_field(centroids, R_cm, R_cvar, params.resistance_correlation, seed, threads).
Eigen::VectorXd draw_resistance(const Eigen::MatrixX3d& centroids, const FractureParams& params, std::uint64_t seed,
                                int threads = 1);

}  // namespace fissure
