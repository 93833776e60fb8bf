#pragma once
// Small meshes and helpers shared by the FEM tests.

#include "fissure/base/rng.hpp"
#include "fissure/fem/elastic_body.hpp"
#include "fissure/mesh/structured_box.hpp"

#include <memory>

namespace fissure::test {

inline std::shared_ptr<const TetMesh> box_mesh(const Eigen::Vector3d& lo, const Eigen::Vector3d& size,
                                               int nx, int ny, int nz) {
  return std::make_shared<const TetMesh>(make_structured_box(lo, size, nx, ny, nz));
}

/// A structured box whose interior nodes are moved randomly by up to `fraction` of the cell size:
/// an unstructured-looking mesh with all tets still positive (fraction ≤ 0.2).
inline std::shared_ptr<const TetMesh> perturbed_box(int n, double fraction, std::uint64_t seed) {
  const TetMesh box = make_structured_box(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), n, n, n);
  Eigen::MatrixX3d nodes = box.nodes();
  Rng rng(seed);
  const double h = 1.0 / n;
  for (int v = 0; v < nodes.rows(); ++v) {
    const Eigen::Vector3d p = nodes.row(v);
    if ((p.array() > 1e-12).all() && (p.array() < 1.0 - 1e-12).all()) {
      for (int i = 0; i < 3; ++i) nodes(v, i) += fraction * h * rng.uniform(-1.0, 1.0);
    }
  }
  return std::make_shared<const TetMesh>(nodes, box.tets(), "perturbed box", box.named_sets());
}

inline ElasticMaterial concrete() { return ElasticMaterial{3.0e10, 0.2, 2400.0}; }

}  // namespace fissure::test
