#include "fissure/base/error.hpp"
#include "fissure/mesh/tetrahedralize.hpp"
#include "fissure/mesh/tile.hpp"

#include "test_shapes.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <map>

namespace fissure {
namespace {

TEST(Tile, ParsesAndRefuses) {
  const TileSpec t = parse_tile_spec("tile:1,0.5,0.05");
  EXPECT_DOUBLE_EQ(t.width, 1.0);
  EXPECT_DOUBLE_EQ(t.height, 0.5);
  EXPECT_DOUBLE_EQ(t.thickness, 0.05);
  EXPECT_TRUE(is_tile_spec("tile:1,1,1"));
  EXPECT_FALSE(is_tile_spec("tile.obj"));
  for (const char* bad : {"tile:1,1", "tile:1,1,0", "tile:1,-1,1", "tile:a,1,1", "tile:1,1,1,1", "tile:1,1,inf"}) {
    try {
      parse_tile_spec(bad);
      FAIL() << bad;
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
    }
  }
}

TEST(Tile, SurfaceIsClosedOutwardAndExact) {
  const SurfaceMesh s = make_tile_surface({0.8, 0.6, 0.05});
  EXPECT_NEAR(signed_volume(s), 0.8 * 0.6 * 0.05, 1e-16);
  EXPECT_NEAR(surface_area(s), 2 * (0.8 * 0.6 + 0.8 * 0.05 + 0.6 * 0.05), 1e-15);
  // Every directed edge appears once and its reverse once: closed and consistently oriented.
  std::map<std::pair<int, int>, int> directed;
  for (int f = 0; f < s.face_count(); ++f)
    for (int k = 0; k < 3; ++k) ++directed[{s.faces(f, k), s.faces(f, (k + 1) % 3)}];
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1);
    EXPECT_EQ(directed.count({edge.second, edge.first}), 1u);
  }
  // The conventions of tile.hpp.
  EXPECT_DOUBLE_EQ(s.vertices.col(2).minCoeff(), 0.0);
  EXPECT_DOUBLE_EQ(s.vertices.col(2).maxCoeff(), 0.05);
  EXPECT_DOUBLE_EQ(s.vertices.col(0).minCoeff(), -0.4);
}

// Every boundary face of the tet mesh lies on one of the box's six planes.
void expect_boundary_on_box(const TetMesh& m, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  // CGAL places surface vertices by intersecting with the input planes in double: 1e-12 of the
  // box size covers that round-off.
  const double tol = 1e-12 * (hi - lo).norm();
  for (const BoundaryFace& f : m.boundary_faces()) {
    bool on_a_plane = false;
    for (int axis = 0; axis < 3 && !on_a_plane; ++axis) {
      for (double plane : {lo[axis], hi[axis]}) {
        bool all = true;
        for (int v : f.nodes) all = all && std::abs(m.nodes()(v, axis) - plane) <= tol;
        on_a_plane = on_a_plane || all;
      }
    }
    ASSERT_TRUE(on_a_plane) << "boundary face of tet " << f.tet << " is not on the box";
  }
}

TEST(Tetrahedralize, TileIsFilledExactly) {
  TetrahedralizeOptions options;
  options.target_tets = 4000;
  TetrahedralizeReport report;
  const TetMesh m = tetrahedralize(make_tile_surface({1.0, 1.0, 0.2}), options, &report);
  // Sharp features are protected, so the box is reproduced exactly: the volume differs only by
  // the round-off of summing ~4000 tet volumes (~1e-15 relative).
  EXPECT_NEAR(m.total_volume(), 0.2, 1e-13);
  EXPECT_NEAR(m.tet_count(), 4000, 0.25 * 4000);
  EXPECT_GE(report.quality.min_dihedral_deg, 10.0) << "perturb + exude target 12 deg";
  EXPECT_EQ(m.component_count(), 1);
  expect_boundary_on_box(m, {-0.5, -0.5, 0.0}, {0.5, 0.5, 0.2});
  EXPECT_TRUE(report.warnings.empty());
}

TEST(Tetrahedralize, ThinTileKeepsItsCornersAndVolume) {
  TetrahedralizeOptions options;
  options.target_tets = 8000;
  TetrahedralizeReport report;
  const TetMesh m = tetrahedralize(make_tile_surface({0.5, 0.5, 0.05}), options, &report);
  EXPECT_NEAR(m.total_volume(), 0.5 * 0.5 * 0.05, 1e-14);
  expect_boundary_on_box(m, {-0.25, -0.25, 0.0}, {0.25, 0.25, 0.05});
  // The 8 corners are mesh nodes (features protected).
  for (int i = 0; i < 8; ++i) {
    const Eigen::RowVector3d corner((i & 1) ? 0.25 : -0.25, (i & 2) ? 0.25 : -0.25, (i & 4) ? 0.05 : 0.0);
    EXPECT_LT((m.nodes().rowwise() - corner).rowwise().norm().minCoeff(), 1e-12);
  }
}

TEST(Tetrahedralize, SameInputSameMesh) {
  TetrahedralizeOptions options;
  options.target_tets = 3000;
  const SurfaceMesh s = make_tile_surface({1.0, 0.5, 0.25});
  const TetMesh a = tetrahedralize(s, options);
  const TetMesh b = tetrahedralize(s, options);
  ASSERT_EQ(a.node_count(), b.node_count());
  EXPECT_TRUE(a.nodes() == b.nodes());  // bitwise
  EXPECT_TRUE(a.tets() == b.tets());
}

TEST(Tetrahedralize, NonConvexSurface) {
  const SurfaceMesh s = test::l_prism();
  ASSERT_NEAR(signed_volume(s), 1.5, 1e-15);
  TetrahedralizeOptions options;
  options.target_tets = 3000;
  const TetMesh m = tetrahedralize(s, options);
  EXPECT_NEAR(m.total_volume(), 1.5, 1e-12);
  // No tet centroid falls in the notch (x > 1 and y > 1).
  for (int t = 0; t < m.tet_count(); ++t) {
    const Eigen::Vector3d c = m.centroid(t);
    ASSERT_FALSE(c.x() > 1.0 && c.y() > 1.0) << "tet " << t << " fills the notch";
  }
}

TEST(Tetrahedralize, RefusesBadInputAndHonoursCancel) {
  TetrahedralizeOptions options;
  options.target_tets = 2000;
  SurfaceMesh open = make_tile_surface({1, 1, 1});
  open.faces.conservativeResize(11, 3);
  EXPECT_THROW(tetrahedralize(open, options), InvalidInput);
  SurfaceMesh inside_out = make_tile_surface({1, 1, 1});
  inside_out.faces.col(1).swap(inside_out.faces.col(2));
  EXPECT_THROW(tetrahedralize(inside_out, options), InvalidInput);
  TetrahedralizeOptions bad = options;
  bad.facet_angle_deg = 40;
  EXPECT_THROW(tetrahedralize(make_tile_surface({1, 1, 1}), bad), InvalidInput);
  CancelToken cancel;
  cancel.cancel();
  EXPECT_THROW(tetrahedralize(make_tile_surface({1, 1, 1}), options, nullptr, nullptr, &cancel), Cancelled);
}

}  // namespace
}  // namespace fissure
