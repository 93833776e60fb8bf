#include "fissure/scene/body_facing.hpp"

#include <algorithm>
#include <array>
#include <limits>

namespace fissure {
namespace {

// A plate: its thinnest side at most this fraction of the next. Tiles (0.6–2 cm on 10–60 cm),
// mirrors and panes are far below it; a kerb (15 × 30 cm) and a basin are above it.
constexpr double kPlateRatio = 0.25;

}  // namespace

Eigen::Vector3d scene_centre(const ImportedScene& scene, const std::vector<SceneBody>& bodies) {
  Eigen::Vector3d low = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d high = -low;
  for (const SceneBody& body : bodies) {
    for (int m : body.meshes) {
      const Eigen::MatrixX3d& v = scene.meshes[static_cast<std::size_t>(m)].vertices;
      for (Eigen::Index i = 0; i < v.rows(); ++i) {
        const Eigen::Vector3d p = body.world.topLeftCorner<3, 3>() * v.row(i).transpose() + body.world.topRightCorner<3, 1>();
        low = low.cwiseMin(p);
        high = high.cwiseMax(p);
      }
    }
  }
  if (!(low.array() <= high.array()).all()) return Eigen::Vector3d::Zero();
  return 0.5 * (low + high);
}

Eigen::Vector3d body_facing(const Eigen::MatrixX3d& world, const Eigen::Vector3d& up, const Eigen::Vector3d& centre) {
  if (world.rows() == 0) return up;
  const Eigen::Vector3d low = world.colwise().minCoeff(), high = world.colwise().maxCoeff();
  const Eigen::Vector3d extent = high - low;
  std::array<int, 3> order = {0, 1, 2};
  std::sort(order.begin(), order.end(), [&](int a, int b) { return extent[a] < extent[b]; });
  const int thin = order[0];
  int up_axis = 0;
  up.cwiseAbs().maxCoeff(&up_axis);
  if (thin == up_axis || !(extent[thin] <= kPlateRatio * extent[order[1]])) return up;
  // Towards the scene's centre; a body at the centre itself (a scene of one plate) looks along
  // the axis's positive direction.
  const double mid = 0.5 * (low[thin] + high[thin]);
  return (centre[thin] < mid ? -1.0 : 1.0) * Eigen::Vector3d::Unit(thin);
}

}  // namespace fissure
