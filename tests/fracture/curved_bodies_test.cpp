// The default scenario (rim rollers on the lowest face, a patch load on the top face, up = +z)
// on the bodies issue 10 names: tiles from 0.3 m to 1 m and curved bodies, a bowl standing on
// its foot ring and a basin standing on its floor. Each must rest where it stands, take the load
// where a hand or a dropped weight would land (the bowl's and the basin's inside floor), have a
// visible face, and break into several fragments with the default material and no flags.

#include "fissure/fem/load.hpp"
#include "fissure/fracture/fracture_scenario.hpp"
#include "fissure/fracture/material_file.hpp"
#include "fissure/mesh/tetrahedralize.hpp"
#include "fissure/mesh/tile.hpp"

#include "../support/test_shapes.hpp"
#include "fracture_test_bodies.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <set>
#include <string>

namespace fissure {
namespace {

// ~8K tets: the CLI's default is 24K; a third of it keeps every body's preparation under a
// second on this machine class while leaving ≥ 1 tet through the thinnest wall (the bowl's 6 mm).
constexpr int kTets = 8000;

std::shared_ptr<const TetMesh> mesh_of(const SurfaceMesh& surface) {
  TetrahedralizeOptions options;
  options.target_tets = kTets;
  return std::make_shared<const TetMesh>(tetrahedralize(surface, options));
}

FractureParams default_params() { return load_material(find_material(kDefaultMaterialName)).params; }

struct Body {
  std::string name;
  SurfaceMesh surface;
};

// The smallest 3-D fragment count over seeds 1–3 with everything default. "Several" read as ≥ 3:
// measured over seeds 1–5 at ~8K tets (`fissure fracture … --tets 8000 --seed s`), the fewest
// were 28 (0.3 m tile), 88 (0.5 m), 242 (1 m), 20 (bowl), 77 (basin), so the bound fails only
// when a default stops breaking the body (no supports found, the load off the floor, cracks
// arresting at once), not on a seed's luck.
int fewest_fragments(const PreparedBody& body, const FractureParams& params) {
  int fewest = 1 << 30;
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const auto run = test::run_default_scenario(body, params, seed);
    test::expect_sane_result(body.mesh(), params, {}, run.result, "seed " + std::to_string(seed));
    fewest = std::min(fewest, run.result.fragments.count);
  }
  return fewest;
}

TEST(CurvedBodies, TilesFromThirtyCentimetresToOneMetreBreakWithTheDefaults) {
  const FractureParams params = default_params();
  for (const TileSpec tile : {TileSpec{0.3, 0.3, 0.02}, TileSpec{0.5, 0.5, 0.02}, TileSpec{1.0, 1.0, 0.03}}) {
    SCOPED_TRACE(tile.width);
    const PreparedBody body(mesh_of(make_tile_surface(tile)), params.elastic(), FractureScenario{});
    EXPECT_GE(fewest_fragments(body, params), 3);
    EXPECT_TRUE(test::expect_sane_pattern(body.mesh(), test::run_default_scenario(body, params, 1).result, "tile")
                    .fragment_count >= 3);
  }
}

// A scene body with an unfitted material and no loads is struck at a drawn point (drawn_load()):
// the points spread over the top's inner [inset, 1 − inset] footprint, each patch on a face that
// looks up, the same seed the same patch. On the basin the nearest up-facing face to a drawn
// point is its rim or its floor, never its underside.
TEST(CurvedBodies, DrawnLoadsSpreadOverTheTopAndStayOnIt) {
  const auto tile = mesh_of(make_tile_surface(TileSpec{0.5, 0.5, 0.02}));
  const auto basin = mesh_of(test::basin());
  for (const auto& mesh : {tile, basin}) {
    SCOPED_TRACE(mesh == tile ? "tile" : "basin");
    const Eigen::Matrix<double, 2, 3> box = mesh->bounding_box();
    Eigen::Vector2d lo = Eigen::Vector2d::Constant(1e9), hi = Eigen::Vector2d::Constant(-1e9);
    std::set<std::string> specs;
    for (std::uint64_t seed = 1; seed <= 40; ++seed) {
      const LoadSpec load = drawn_load(*mesh, Eigen::Vector3d::UnitZ(), 1.0, seed);
      EXPECT_EQ(load.spec, drawn_load(*mesh, Eigen::Vector3d::UnitZ(), 1.0, seed).spec);
      specs.insert(load.spec);
      const Eigen::Vector2d c = load.selection.center.head<2>();
      lo = lo.cwiseMin(c);
      hi = hi.cwiseMax(c);
      const Eigen::VectorXd f = assemble_load(*mesh, load);
      Eigen::Vector3d total = Eigen::Vector3d::Zero();
      for (int v = 0; v < mesh->node_count(); ++v) total += f.segment<3>(3 * v);
      EXPECT_NEAR(total.z(), -1.0, 1e-9) << load.spec;  // the patch holds faces and pushes down
      if (mesh == tile) {
        EXPECT_NEAR(load.selection.center.z(), 0.02, 1e-9) << load.spec;
      }
    }
    EXPECT_GE(specs.size(), 30u) << "40 seeds, few distinct patches";
    for (int a = 0; a < 2; ++a) {
      const double side = box(1, a) - box(0, a);
      // Inside the inset footprint, give or take the face the point snapped to (≤ 0.03 m here).
      EXPECT_GT(lo(a), box(0, a) + kDrawnLoadInset * side - 0.03);
      EXPECT_LT(hi(a), box(1, a) - kDrawnLoadInset * side + 0.03);
      // Spread: 40 uniform draws cover well over half the inner footprint.
      EXPECT_GT(hi(a) - lo(a), 0.5 * (1.0 - 2.0 * kDrawnLoadInset) * side);
    }
  }
}

// Where the default supports hold the body: every roller (an up dof) is on the sole it stands on.
void expect_rollers_on_the_sole(const PreparedBody& body, double sole_z, double tolerance) {
  int rollers = 0;
  for (int dof : body.fixed_dofs()) {
    if (dof % 3 != 2) continue;
    ++rollers;
    EXPECT_NEAR(body.mesh().nodes()(dof / 3, 2), sole_z, tolerance) << body.mesh().node_label(dof / 3);
  }
  EXPECT_GE(rollers, 3);
}

// Where the default load pushes: every loaded node lies on the inside floor (`off_floor(p)`, its
// distance from it, ≤ tolerance), none on the underside a few millimetres below it, and the force
// is the unit force pointing down.
template <class Distance>
void expect_load_on_the_floor(const PreparedBody& body, Distance off_floor, double tolerance) {
  ASSERT_EQ(body.loads().size(), 1u);
  ASSERT_TRUE(body.default_load());
  const Eigen::VectorXd f = assemble_load(body.mesh(), body.loads()[0]);
  Eigen::Vector3d total = Eigen::Vector3d::Zero();
  int loaded = 0;
  for (int v = 0; v < body.mesh().node_count(); ++v) {
    const Eigen::Vector3d fv = f.segment<3>(3 * v);
    if (fv.isZero(0.0)) continue;
    ++loaded;
    total += fv;
    EXPECT_LE(off_floor(Eigen::Vector3d(body.mesh().nodes().row(v).transpose())), tolerance)
        << body.mesh().node_label(v);
  }
  EXPECT_GE(loaded, 3);
  EXPECT_NEAR(total.z(), -1.0, 1e-9);
  EXPECT_NEAR(total.head<2>().norm(), 0.0, 1e-9);
}

TEST(CurvedBodies, ABowlStandsOnItsFootRingTakesTheLoadOnItsInsideFloorAndBreaks) {
  // test_shapes.hpp's bowl: a shell of outer radius 8 cm and wall 6 mm centred 8.5 cm above the
  // foot ring's sole, so the inside floor is the sphere of radius 7.4 cm about (0, 0, 8.5 cm),
  // its lowest point at z = 11 mm. The patch (2 element sizes, ≈ 13 mm at 8K tets) is curved.
  const FractureParams params = default_params();
  const PreparedBody body(mesh_of(test::bowl()), params.elastic(), FractureScenario{});
  expect_rollers_on_the_sole(body, 0.0, 1e-9);
  // 0.5 mm: the 64-gon facets and CGAL's surface approximation stay within a fraction of a
  // millimetre of the sphere; the underside is 6 mm (the outer sphere) to 12 mm (the ceiling
  // inside the foot ring) away.
  const auto off_inner_sphere = [](const Eigen::Vector3d& p) {
    return std::abs((p - Eigen::Vector3d(0.0, 0.0, 0.085)).norm() - 0.074);
  };
  expect_load_on_the_floor(body, off_inner_sphere, 5e-4);
  EXPECT_GE(fewest_fragments(body, params), 3);
  // The visible face (up, within 45°): the inside floor and the rim; its pattern breaks too.
  EXPECT_GE(test::expect_sane_pattern(body.mesh(), test::run_default_scenario(body, params, 1).result, "bowl")
                .fragment_count,
            3);
}

TEST(CurvedBodies, ABasinStandsOnItsBottomTakesTheLoadOnItsFloorAndBreaks) {
  // test_shapes.hpp's basin: 50 × 40 × 20 cm, 2 cm walls and floor: the floor's top at z = 2 cm.
  const FractureParams params = default_params();
  const PreparedBody body(mesh_of(test::basin()), params.elastic(), FractureScenario{});
  expect_rollers_on_the_sole(body, 0.0, 1e-9);
  // Flat: the nodes are on the plane z = 2 cm, to round-off.
  expect_load_on_the_floor(body, [](const Eigen::Vector3d& p) { return std::abs(p.z() - 0.02); }, 1e-12);
  EXPECT_GE(fewest_fragments(body, params), 3);
  EXPECT_GE(test::expect_sane_pattern(body.mesh(), test::run_default_scenario(body, params, 1).result, "basin")
                .fragment_count,
            3);
}

}  // namespace
}  // namespace fissure
