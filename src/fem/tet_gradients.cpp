#include "fissure/fem/tet_gradients.hpp"

#include <Eigen/LU>

namespace fissure {

TetGradients compute_tet_gradients(const TetMesh& mesh) {
  const int n = mesh.tet_count();
  TetGradients out;
  out.g.resize(n, 9);
  out.volumes = mesh.volumes();
  const auto& x = mesh.nodes();
  const auto& tets = mesh.tets();
  for (int t = 0; t < n; ++t) {
    Eigen::Matrix3d j;
    const Eigen::Vector3d x0 = x.row(tets(t, 0));
    for (int a = 1; a < 4; ++a) j.col(a - 1) = x.row(tets(t, a)).transpose() - x0;
    // TetMesh guarantees a positive volume well above round-off, so J is invertible.
    const Eigen::Matrix3d inv = j.inverse();
    for (int a = 0; a < 3; ++a)
      for (int i = 0; i < 3; ++i) out.g(t, 3 * a + i) = inv(a, i);
  }
  return out;
}

}  // namespace fissure
