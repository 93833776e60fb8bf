#pragma once
/// Quantities of node-major vector fields (3·#nodes entries: displacements, forces).

#include <Eigen/Core>

namespace fissure {

/// The largest nodal vector length max_v |(x, y, z)_v| and its node (0-based index; −1 for an
/// empty field). Each length is computed as m·√((x/m)² + (y/m)² + (z/m)²) with m the node's
/// largest |component|, so it neither overflows for 1e200 m nor underflows to 0 for 1e-300 m
/// (the plain √(x² + y² + z²) printed "inf m" for a body with E = 1e-300). Non-finite entries
/// give a non-finite result. O(#nodes).
struct NodalMaximum {
  double magnitude = 0.0;
  int node = -1;
};
NodalMaximum max_nodal_magnitude(const Eigen::VectorXd& field);

}  // namespace fissure
