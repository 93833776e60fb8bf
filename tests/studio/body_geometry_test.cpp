#include "body_geometry.hpp"

#include "test_support.hpp"

#include "fissure/io/scene_import.hpp"

#include <gtest/gtest.h>

namespace fissure::studio {
namespace {

// A whole body is drawn in world coordinates: the street's first slab, 12 triangles, keeps its
// size (0.6 × 0.05 × 0.6 m, from `fissure scene info`), and a ray straight down onto its middle
// hits its top face.
TEST(BodyGeometry, AWholeBodyIsItsMeshInTheWorld) {
  const ImportedScene scene = import_scene(test::source_dir() / "assets/scenes/street.glb");
  const std::vector<SceneBody> bodies = scene_bodies(scene);
  ASSERT_FALSE(bodies.empty());
  const BodyGeometry g = whole_body_geometry(scene, bodies.front());
  EXPECT_EQ(g.triangle_count(), 12);
  ASSERT_EQ(g.ranges.size(), 1u);
  EXPECT_EQ(g.ranges[0].count, 36);
  const Eigen::Vector3d size = g.bounds.sizes();
  EXPECT_NEAR(size.x(), 0.6, 1e-6);
  EXPECT_NEAR(size.y(), 0.05, 1e-6);
  EXPECT_NEAR(size.z(), 0.6, 1e-6);
  // Every normal is unit and, for this box, along an axis.
  for (std::size_t v = 0; v < g.surface.size(); v += BodyGeometry::kSurfaceFloats) {
    const Eigen::Vector3d n(g.surface[v + 3], g.surface[v + 4], g.surface[v + 5]);
    EXPECT_NEAR(n.norm(), 1.0, 1e-6);
    EXPECT_NEAR(n.cwiseAbs().maxCoeff(), 1.0, 1e-6);
  }
  const Eigen::Vector3d top(g.bounds.center().x(), g.bounds.max().y(), g.bounds.center().z());
  const Eigen::Vector3d origin = top + Eigen::Vector3d(0, 2, 0);
  EXPECT_NEAR(ray_hit(g, g.ranges[0], Eigen::Vector3d::Zero(), origin, -Eigen::Vector3d::UnitY()), 2.0, 1e-6);
  // Moved sideways by more than its width, it is missed.
  EXPECT_LT(ray_hit(g, g.ranges[0], Eigen::Vector3d(1, 0, 0), origin, -Eigen::Vector3d::UnitY()), 0.0);
}

}  // namespace
}  // namespace fissure::studio
