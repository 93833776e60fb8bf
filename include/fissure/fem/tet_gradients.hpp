#pragma once
/// Constant shape-function gradients of linear tetrahedra, stored structure-of-arrays so the
/// stress kernel streams them with unit stride.

#include "fissure/mesh/tet_mesh.hpp"

#include <Eigen/Core>

namespace fissure {

/// For tet t, gradients of the shape functions of local nodes 1, 2, 3 (1/m) are
/// g(t, 3·(a−1) + i), a ∈ {1,2,3}, i ∈ {x,y,z}; node 0's gradient is minus their sum (partition of
/// unity). Column-major with one row per tet: each column is a contiguous array over tets.
struct TetGradients {
  Eigen::Matrix<double, Eigen::Dynamic, 9> g;
  Eigen::VectorXd volumes;  ///< m³

  /// Gradient of local node a ∈ [0, 4) of tet t.
  Eigen::Vector3d gradient(int t, int a) const {
    if (a == 0) {
      return -Eigen::Vector3d(g(t, 0) + g(t, 3) + g(t, 6), g(t, 1) + g(t, 4) + g(t, 7),
                              g(t, 2) + g(t, 5) + g(t, 8));
    }
    return Eigen::Vector3d(g(t, 3 * (a - 1)), g(t, 3 * (a - 1) + 1), g(t, 3 * (a - 1) + 2));
  }
};

/// Gradients from J⁻¹, J = [x1−x0, x2−x0, x3−x0]; the rows of J⁻¹ are ∇N1, ∇N2, ∇N3. O(#tets).
TetGradients compute_tet_gradients(const TetMesh& mesh);

}  // namespace fissure
