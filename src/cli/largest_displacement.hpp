#pragma once
// The largest nodal displacement magnitude max_v |u_v| of a solve, for the CLI's summary line.

#include <Eigen/Core>

namespace fissure::cli {

/// max over nodes of the Euclidean norm of (u_3v, u_3v+1, u_3v+2), `u` of length 3·#nodes.
/// Computed without overflow or underflow: each component is divided by the largest absolute
/// component first, so |u| = 1e300 m (E = 1e-300 Pa) and 1e-310 m (a tiny load) come out right
/// where squaring gives inf and 0. NaN when `u` holds a NaN. O(#nodes).
double largest_displacement(const Eigen::VectorXd& u);

}  // namespace fissure::cli
