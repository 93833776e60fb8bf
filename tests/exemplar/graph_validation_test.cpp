// PlanarCrackGraph::validate and PlanarCrackGraphBuilder: a graph from a caller (a simulation)
// is checked before any statistic is computed from it.

#include "fissure/base/error.hpp"
#include "fissure/exemplar/exemplar_analysis.hpp"
#include "fissure/exemplar/pattern_stats.hpp"

#include "drawings.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace fissure {
namespace {

// Two cracks meeting at a T in the unit square: a junction of degree 3 and three border ends.
PlanarCrackGraph t_graph() {
  PlanarCrackGraphBuilder b({0, 0}, {1, 1}, 1.0, "t.sim");
  const int left = b.add_node({0, 0.5}, true), right = b.add_node({1, 0.5}, true), top = b.add_node({0.5, 1}, true);
  const int middle = b.add_node({0.5, 0.5});
  b.add_crack({{0, 0.5}, {0.5, 0.5}}, left, middle);
  b.add_crack({{0.5, 0.5}, {1, 0.5}}, middle, right);
  b.add_crack({{0.5, 0.5}, {0.5, 1}}, middle, top);
  b.add_fragment(Fragment{0.5, true, {0.5, 0.25}, {}});
  b.add_fragment(Fragment{0.25, true, {0.25, 0.75}, {}});
  b.add_fragment(Fragment{0.25, true, {0.75, 0.75}, {}});
  return std::move(b).build();
}

std::string invalid_input_of(const PlanarCrackGraph& g) {
  try {
    compute_pattern_stats(g);
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "accepted";
}

TEST(CrackGraphBuilder, DerivesDegreesAndKinds) {
  const PlanarCrackGraph g = t_graph();
  ASSERT_EQ(g.nodes.size(), 4u);
  EXPECT_EQ(g.nodes[3].kind, CrackNode::Kind::Junction);
  EXPECT_EQ(g.nodes[3].degree, 3);
  for (int v = 0; v < 3; ++v) {
    EXPECT_EQ(g.nodes[static_cast<std::size_t>(v)].kind, CrackNode::Kind::Border);
    EXPECT_EQ(g.nodes[static_cast<std::size_t>(v)].degree, 1);
  }
  EXPECT_TRUE(g.problems().empty());
  const PatternStats s = compute_pattern_stats(g, PatternStatsOptions{.probe_min = 0.02});
  EXPECT_EQ(s.t_count, 1);
  EXPECT_EQ(s.border_end_count, 3);
}

TEST(CrackGraphBuilder, DropsUnusedNodesAndSnapsEnds) {
  PlanarCrackGraphBuilder b({0, 0}, {2, 1}, 2.0, "snap");
  b.add_node({5, 5});  // never used: dropped, the others renumbered
  const int a = b.add_node({0, 0.5}, true), c = b.add_node({2, 0.5}, true);
  b.add_crack({{0.001, 0.5}, {1, 0.6}, {1.999, 0.5}}, a, c);
  const PlanarCrackGraph g = std::move(b).build();
  ASSERT_EQ(g.nodes.size(), 2u);
  EXPECT_EQ(g.cracks[0].start_node, 0);
  EXPECT_EQ(g.cracks[0].points.front(), Eigen::Vector2d(0, 0.5));
  EXPECT_EQ(g.cracks[0].points.back(), Eigen::Vector2d(2, 0.5));
  EXPECT_EQ(g.nodes[0].kind, CrackNode::Kind::Border);
}

TEST(CrackGraphBuilder, RefusesAnUnknownNode) {
  PlanarCrackGraphBuilder b({0, 0}, {1, 1}, 1.0, "bad.sim");
  const int a = b.add_node({0, 0});
  b.add_crack({{0, 0}, {1, 1}}, a, 7);
  try {
    std::move(b).build();
    FAIL() << "accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("bad.sim: invalid crack graph: cracks[0] names node 7"), std::string::npos) << e.what();
  }
}

// Used to write out of bounds: compute_pattern_stats indexed its per-node direction lists with
// the crack's node index unchecked.
TEST(CrackGraphValidation, NodeIndexOutOfRangeIsRefused) {
  PlanarCrackGraph g = t_graph();
  g.cracks[1].end_node = 1000;
  EXPECT_NE(invalid_input_of(g).find("t.sim: invalid crack graph: cracks[1] names node 1000, outside [0, 4)"), std::string::npos)
      << invalid_input_of(g);
  g.cracks[1].end_node = -5;
  EXPECT_NE(invalid_input_of(g).find("cracks[1] names node -5"), std::string::npos) << invalid_input_of(g);
}

TEST(CrackGraphValidation, EachInconsistencyIsNamed) {
  struct Case {
    const char* expected;
    void (*spoil)(PlanarCrackGraph&);
  };
  const Case cases[] = {
      {"nodes[3] has degree 4 but 3 crack ends", [](PlanarCrackGraph& g) { g.nodes[3].degree = 4; }},
      {"nodes[3] joins 3 crack ends but is not a junction", [](PlanarCrackGraph& g) { g.nodes[3].kind = CrackNode::Kind::End; }},
      {"nodes[0] is a junction with only 1 crack ends", [](PlanarCrackGraph& g) { g.nodes[0].kind = CrackNode::Kind::Junction; }},
      {"nodes[4] touches no crack", [](PlanarCrackGraph& g) { g.nodes.push_back(CrackNode{}); }},
      {"nodes[3] position (nan, 0.5) is not finite", [](PlanarCrackGraph& g) { g.nodes[3].position.x() = std::numeric_limits<double>::quiet_NaN(); }},
      {"cracks[2] point 1 (0.5, inf) is not finite",
       [](PlanarCrackGraph& g) { g.cracks[2].points[1].y() = std::numeric_limits<double>::infinity(); }},
      {"cracks[0] has 1 points, fewer than 2", [](PlanarCrackGraph& g) { g.cracks[0].points.resize(1); }},
      {"cracks[0] runs from (0, 0.5) to (0.4, 0.5)", [](PlanarCrackGraph& g) { g.cracks[0].points[1].x() = 0.4; }},
      {"fragments[1] area 0 is not positive", [](PlanarCrackGraph& g) { g.fragments[1].area = 0.0; }},
      {"fragments[0] centroid (nan, 0.25)", [](PlanarCrackGraph& g) { g.fragments[0].centroid.x() = std::numeric_limits<double>::quiet_NaN(); }},
      {"fragment areas sum to 1.5", [](PlanarCrackGraph& g) { g.fragments[0].area = 1.0; }},
      {"total area nan is not positive", [](PlanarCrackGraph& g) { g.total_area = std::numeric_limits<double>::quiet_NaN(); }},
      {"total area -1 is not positive", [](PlanarCrackGraph& g) { g.total_area = -1.0; }},
      {"frame (0, 0) to (0, 1) is not a finite rectangle", [](PlanarCrackGraph& g) { g.frame_max.x() = 0.0; }},
      {"crack width -0.1 is negative", [](PlanarCrackGraph& g) { g.crack_width = -0.1; }},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.expected);
    PlanarCrackGraph g = t_graph();
    c.spoil(g);
    const std::string message = invalid_input_of(g);
    EXPECT_EQ(message.rfind("t.sim: invalid crack graph: ", 0), 0u) << message;
    EXPECT_NE(message.find(c.expected), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

// Every graph the image path extracts is consistent (it is built by the builder, and validated).
TEST(CrackGraphValidation, ExtractedGraphsAreValid) {
  for (const cv::Mat& drawing : {test::grid_drawing(300, 60, 3), test::honeycomb_drawing(300, 30.0, 2),
                                 test::brick_drawing(300, 40, 3), test::oblique_grid_drawing(300, 24, 3)}) {
    const ExemplarAnalysis a = analyze_crack_mask(crack_mask_from_grey(test::to_grey_image(drawing), {}, "drawing"));
    EXPECT_TRUE(a.graph.problems().empty()) << a.graph.problems().front();
  }
}

}  // namespace
}  // namespace fissure
