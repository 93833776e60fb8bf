#include "fissure/base/error.hpp"
#include "fissure/fem/selection.hpp"

#include "fem_test_meshes.hpp"

#include <gtest/gtest.h>

namespace fissure {
namespace {

TEST(Selection, ParsesAndRefusesWithTheSpecNamed) {
  const Selection box = parse_selection("box:0,1,-2,2,0,0.001");
  EXPECT_EQ(box.kind, Selection::Kind::Box);
  EXPECT_DOUBLE_EQ(box.box[5], 0.001);
  const Selection ball = parse_selection("ball:0,0,0.05,0.05");
  EXPECT_EQ(ball.kind, Selection::Kind::Ball);
  EXPECT_DOUBLE_EQ(ball.radius, 0.05);
  EXPECT_EQ(parse_selection("bottom").kind, Selection::Kind::NamedSet);
  for (const char* bad : {"box:0,1", "box:1,0,0,1,0,1", "ball:0,0,0,-1", "ball:0,0,x,1", "box:", "", "a b"}) {
    try {
      parse_selection(bad);
      FAIL() << bad;
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find("selection"), std::string::npos) << e.what();
    }
  }
}

TEST(Selection, ResolvesNodesAndBoundaryFaces) {
  auto mesh = test::box_mesh({0, 0, 0}, {1, 1, 1}, 4, 4, 4);
  // The top face z = 1: 25 nodes, 4·4·2 = 32 boundary triangles.
  const SelectedRegion top = resolve_selection(*mesh, parse_selection("box:0,1,0,1,1,1"));
  EXPECT_EQ(top.nodes.size(), 25u);
  EXPECT_EQ(top.faces.size(), 32u);
  EXPECT_NEAR(face_areas(*mesh, top).sum(), 1.0, 1e-14);
  // The named set gives the same faces.
  const SelectedRegion named = resolve_selection(*mesh, parse_selection("zmax"));
  EXPECT_EQ(named.faces.size(), 32u);
  // A ball around a corner: the corner node and its neighbours within 0.26.
  const SelectedRegion corner = resolve_selection(*mesh, parse_selection("ball:0,0,0,0.26"));
  EXPECT_EQ(corner.nodes.size(), 4u);  // corner + 3 edge neighbours at 0.25
  try {
    resolve_selection(*mesh, parse_selection("floor"));
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("zmin"), std::string::npos) << "lists existing groups: " << e.what();
  }
}

}  // namespace
}  // namespace fissure
