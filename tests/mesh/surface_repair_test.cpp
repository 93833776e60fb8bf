#include "fissure/base/error.hpp"
#include "fissure/mesh/surface_repair.hpp"
#include "fissure/mesh/tile.hpp"

#include <gtest/gtest.h>

namespace fissure {
namespace {

// The tile surface with every face given its own three vertices (as STL stores it).
SurfaceMesh unwelded(const SurfaceMesh& s) {
  SurfaceMesh out;
  out.source_name = "unwelded";
  out.vertices.resize(3 * s.face_count(), 3);
  out.faces.resize(s.face_count(), 3);
  for (Eigen::Index f = 0; f < s.face_count(); ++f)
    for (int k = 0; k < 3; ++k) {
      out.vertices.row(3 * f + k) = s.vertices.row(s.faces(f, k));
      out.faces(f, k) = static_cast<int>(3 * f + k);
    }
  return out;
}

SurfaceMesh two_boxes(double offset_x, double offset_y = 0.0) {
  const SurfaceMesh a = make_tile_surface({1, 1, 1});
  SurfaceMesh s;
  s.source_name = "two boxes";
  s.vertices.resize(16, 3);
  s.vertices << a.vertices, (a.vertices.rowwise() + Eigen::RowVector3d(offset_x, offset_y, 0.0));
  s.faces.resize(24, 3);
  s.faces << a.faces, (a.faces.array() + 8).matrix();
  return s;
}

std::string refusal(const SurfaceMesh& s) {
  SurfaceRepairReport report;
  try {
    repair_surface(s, report);
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "";
}

TEST(SurfaceRepair, CleanSurfaceIsUnchanged) {
  const SurfaceMesh tile = make_tile_surface({1, 2, 0.5});
  SurfaceRepairReport report;
  const SurfaceMesh out = repair_surface(tile, report);
  EXPECT_TRUE(report.actions.empty());
  EXPECT_EQ(out.faces, tile.faces);
  EXPECT_NEAR(signed_volume(out), 1.0, 1e-15);
}

TEST(SurfaceRepair, WeldsFlipsAndReports) {
  SurfaceMesh s = unwelded(make_tile_surface({1, 1, 1}));
  // Flip three faces and turn the whole thing inside out on top.
  for (int f : {1, 4, 7}) std::swap(s.faces(f, 1), s.faces(f, 2));
  s.faces.col(1).swap(s.faces.col(2));
  // A duplicate face and a degenerate one.
  s.faces.conservativeResize(14, 3);
  s.faces.row(12) = s.faces.row(0);
  s.faces.row(13) << 0, 0, 1;
  SurfaceRepairReport report;
  const SurfaceMesh out = repair_surface(s, report);
  EXPECT_EQ(out.vertex_count(), 8);
  EXPECT_EQ(out.face_count(), 12);
  EXPECT_NEAR(signed_volume(out), 1.0, 1e-15);
  std::string all;
  for (const auto& a : report.actions) all += a + "\n";
  EXPECT_NE(all.find("merged 28 duplicate vertices"), std::string::npos) << all;
  EXPECT_NE(all.find("removed 1 degenerate"), std::string::npos) << all;
  EXPECT_NE(all.find("removed 1 duplicate"), std::string::npos) << all;
  EXPECT_NE(all.find("flipped"), std::string::npos) << all;
  EXPECT_NE(all.find("reversed 1 shell"), std::string::npos) << all;
}

TEST(SurfaceRepair, CavityShellFacesInward) {
  // A 1 m box with a 0.4 m box inside it: the inner shell bounds a cavity.
  SurfaceMesh s = two_boxes(0.0);
  s.vertices.bottomRows(8) = (s.vertices.bottomRows(8) * 0.4).rowwise() + Eigen::RowVector3d(0, 0, 0.3);
  SurfaceRepairReport report;
  const SurfaceMesh out = repair_surface(s, report);
  EXPECT_NEAR(signed_volume(out), 1.0 - 0.064, 1e-14);
}

TEST(SurfaceRepair, RefusesWhatIsUnsafe) {
  SurfaceMesh open = make_tile_surface({1, 1, 1});
  open.faces.conservativeResize(10, 3);  // the right side is missing
  EXPECT_NE(refusal(open).find("open: 4 border edges"), std::string::npos) << refusal(open);
  // Two boxes sharing an edge: that edge has four faces.
  const std::string edge = refusal(two_boxes(1.0, 1.0));
  EXPECT_NE(edge.find("non-manifold"), std::string::npos) << edge;
  // Overlapping boxes: faces cross.
  const std::string crossing = refusal(two_boxes(0.5, 0.25));
  EXPECT_NE(crossing.find("self-intersecting"), std::string::npos) << crossing;
  SurfaceMesh empty;
  empty.source_name = "empty.obj";
  EXPECT_NE(refusal(empty).find("empty.obj: the surface has no triangles"), std::string::npos);
}


// Refusals name vertices and faces by the user's 1-based input numbers. Main named them by
// their 0-based index after merging and compaction ("between vertices 1 and 3"), which is not
// what the file or any viewer shows.
TEST(SurfaceRepair, RefusalsNameInputVerticesAndFaces) {
  // An unused vertex first shifts every input number by one; compaction removes it again.
  const SurfaceMesh tile = make_tile_surface({1, 1, 1});
  SurfaceMesh open;
  open.source_name = "open.obj";
  open.vertices.resize(9, 3);
  open.vertices << Eigen::RowVector3d(9, 9, 9), tile.vertices;
  open.faces = (tile.faces.topRows(10).array() + 1).matrix();  // the right side is missing
  EXPECT_NE(refusal(open).find("open.obj: open: 4 border edges (e.g. the edge between vertex 3 and vertex 5, "
                               "which only face 2 has)"),
            std::string::npos)
      << refusal(open);

  // Two boxes sharing the vertical edge x = y = 0.5: input vertices 9 and 13 (1-based) of the
  // second box are welded onto 4 and 8 of the first.
  const std::string edge = refusal(two_boxes(1.0, 1.0));
  EXPECT_NE(edge.find("non-manifold: 1 edges shared by more than two faces (e.g. the edge between vertex 4 "
                      "(merged with 9) and vertex 8 (merged with 13), shared by faces 8, 12, 17 and 21)"),
            std::string::npos)
      << edge;

  // Two boxes touching at one corner (0.5, 0.5, 1): vertex 8 of the first, 9 of the second.
  SurfaceMesh corner = two_boxes(1.0, 1.0);
  corner.vertices.bottomRows(8).col(2).array() += 1.0;
  const std::string vertex = refusal(corner);
  EXPECT_NE(vertex.find("non-manifold vertex 8 (merged with 9): two surface sheets touch only there (face 4 on "
                        "one, face 13 on the other)"),
            std::string::npos)
      << vertex;
}

}  // namespace
}  // namespace fissure
