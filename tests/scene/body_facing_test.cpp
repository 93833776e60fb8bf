// Which way a scene body's visible face looks (scene/body_facing.hpp): a plate standing on its
// edge faces the scene's centre and is struck there; anything else looks along the scene's up;
// a body's own "up" overrides the rule.
#include "fissure/io/scene_export.hpp"
#include "fissure/io/scene_import.hpp"
#include "fissure/scene/body_facing.hpp"
#include "fissure/scene/demo_scenes.hpp"
#include "fissure/scene/scene_fracture.hpp"

#include "test_support.hpp"

#include <gtest/gtest.h>

namespace fissure {
namespace {

namespace fs = std::filesystem;

// The 8 corners of the box [low, high].
Eigen::MatrixX3d box(const Eigen::Vector3d& low, const Eigen::Vector3d& high) {
  Eigen::MatrixX3d v(8, 3);
  for (int c = 0; c < 8; ++c)
    for (int a = 0; a < 3; ++a) v(c, a) = (c >> a) & 1 ? high[a] : low[a];
  return v;
}

TEST(BodyFacing, AStandingPlateFacesTheSceneAndEverythingElseLooksUp) {
  const Eigen::Vector3d y = Eigen::Vector3d::UnitY(), z = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d room(0.6, 0.5, 0.6);
  // A floor tile, thin along up.
  EXPECT_EQ(body_facing(box({0, 0, 0}, {0.3, 0.01, 0.3}), y, room), y);
  // A wall tile at z ∈ [−0.01, 0] with the room in front (+z), and one on the opposite wall.
  EXPECT_EQ(body_facing(box({0, 0.2, -0.01}, {0.3, 0.5, 0}), y, room), z);
  EXPECT_EQ(body_facing(box({0, 0.2, 1.2}, {0.3, 0.5, 1.21}), y, room), -z);
  // A tile on a side wall faces ±x.
  EXPECT_EQ(body_facing(box({1.2, 0.2, 0}, {1.21, 0.5, 0.3}), y, room), -Eigen::Vector3d::UnitX());
  // A kerb (25 × 15 cm across, long along x) and a cube are no plates.
  EXPECT_EQ(body_facing(box({0, 0, 0}, {7, 0.25, 0.15}), y, room), y);
  EXPECT_EQ(body_facing(box({0, 0, 0}, {1, 1, 1}), y, room), y);
  // Just past the plate ratio (a quarter) is no plate; just inside is.
  EXPECT_EQ(body_facing(box({0, 0, 0}, {0.4, 0.4, 0.101}), y, room), y);
  EXPECT_EQ(body_facing(box({0, 0, 0}, {0.4, 0.4, 0.099}), y, room), z);
  // A plate at the scene's centre itself (a scene of one pane) faces the axis's + side.
  EXPECT_EQ(body_facing(box({-0.3, -0.3, -0.003}, {0.3, 0.3, 0.003}), y, Eigen::Vector3d::Zero()), z);
  // Under another scene up the same wall tile still faces the room.
  EXPECT_EQ(body_facing(box({0, -0.01, 0.2}, {0.3, 0, 0.5}), z, {0.6, 0.6, 0.5}), y);
}

// A small bathroom written and read back as a user's GLB: one floor tile, two wall tiles.
ImportedScene small_bathroom(const fs::path& dir) {
  DemoBathroomOptions o;
  o.floor_tiles = 1;
  o.wall_tiles_wide = 2;
  o.wall_tiles_high = 1;
  o.basin_segments = 12;
  write_scene(dir / "bathroom.glb", demo_bathroom(o));
  return import_scene(dir / "bathroom.glb");
}

// The world bounding box of a body, from its fragments (they fill it).
Eigen::Matrix<double, 2, 3> fragment_box(const BodyFracture& f) {
  Eigen::Matrix<double, 2, 3> b;
  b.row(0).setConstant(1e300);
  b.row(1).setConstant(-1e300);
  for (const FragmentMesh& m : f.fragments) {
    b.row(0) = b.row(0).cwiseMin(m.vertices.colwise().minCoeff());
    b.row(1) = b.row(1).cwiseMax(m.vertices.colwise().maxCoeff());
  }
  return b;
}

TEST(BodyFacing, AWallTileIsStruckOnItsFaceAndItsOwnUpOverridesThat) {
  const fs::path dir = test::fresh_temp_dir("body_facing");
  const ImportedScene scene = small_bathroom(dir);
  std::string wall, floor;
  for (const SceneBody& b : scene_bodies(scene)) {
    if (b.path.find("/wall_tile") != std::string::npos && wall.empty()) wall = b.path;
    if (b.path.find("/floor_tile") != std::string::npos) floor = b.path;
  }
  ASSERT_FALSE(wall.empty());
  ASSERT_FALSE(floor.empty());
  SceneFractureOptions options;
  options.assignments.by_path[wall] = "ceramic-tile";
  options.assignments.by_path[floor] = "ceramic-tile";
  options.target_tets = 1500;
  const SceneFracture run = fracture_scene(scene, options);
  for (std::size_t b = 0; b < run.bodies.size(); ++b) {
    const SceneBodyReport& r = run.reports[b];
    if (r.path != wall && r.path != floor) continue;
    ASSERT_EQ(r.status, SceneBodyReport::Status::Fractured) << r.path << ": " << r.reason;
    const BodyFracture& f = run.results[b]->fracture;
    const Eigen::Vector3d expected = r.path == wall ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitY();
    EXPECT_EQ(r.up, expected) << r.path;
    ASSERT_EQ(f.loads.size(), 1u);
    EXPECT_EQ(f.loads[0].normal, expected) << r.path;
    EXPECT_LT(f.loads[0].force.dot(expected), 0.0) << r.path;  // pushing into the face
    // The patch sits on the face the room sees (the wall tile's front at its box's high z, the
    // floor tile's top), at a drawn point away from its rim (drawn_load(): [inset, 1 − inset] of
    // each side, then the nearest face centre, within 0.02 m, an element at 1500 tets).
    const Eigen::Matrix<double, 2, 3> bounds = fragment_box(f);
    const int axis = r.path == wall ? 2 : 1;
    EXPECT_NEAR(f.loads[0].selection.center[axis], bounds(1, axis), 1e-9) << r.path;
    for (int a = 0; a < 3; ++a) {
      if (a == axis) continue;
      const double side = bounds(1, a) - bounds(0, a);
      EXPECT_GT(f.loads[0].selection.center[a], bounds(0, a) + kDrawnLoadInset * side - 0.02) << r.path << " axis " << a;
      EXPECT_LT(f.loads[0].selection.center[a], bounds(1, a) - kDrawnLoadInset * side + 0.02) << r.path << " axis " << a;
    }
    EXPECT_GT(f.fragments.size(), 3u) << r.path;
  }

  // The tile's own up: struck on its top edge, as the scene's up alone would have it.
  options.body_setups[wall].up = Eigen::Vector3d::UnitY();
  const SceneFracture edge = fracture_scene(scene, options);
  EXPECT_NE(edge.run, run.run);
  for (std::size_t b = 0; b < edge.bodies.size(); ++b) {
    if (edge.reports[b].path != wall) continue;
    ASSERT_TRUE(edge.results[b]) << edge.reports[b].reason;
    EXPECT_EQ(edge.reports[b].up, Eigen::Vector3d::UnitY());
    const BodyFracture& f = edge.results[b]->fracture;
    ASSERT_EQ(f.loads.size(), 1u);
    EXPECT_EQ(f.loads[0].normal, Eigen::Vector3d::UnitY());
    EXPECT_NEAR(f.loads[0].selection.center.y(), fragment_box(f)(1, 1), 1e-9);
  }
}

}  // namespace
}  // namespace fissure
