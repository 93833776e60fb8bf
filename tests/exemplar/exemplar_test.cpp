#include "fissure/base/error.hpp"
#include "fissure/base/rng.hpp"
#include "fissure/exemplar/exemplar_analysis.hpp"
#include "fissure/exemplar/similarity.hpp"
#include "fissure/exemplar/stats_json.hpp"

#include "drawings.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

namespace fissure {
namespace {

ExemplarAnalysis analyze(const cv::Mat& drawing, const std::string& name = "drawing") {
  return analyze_crack_mask(crack_mask_from_grey(test::to_grey_image(drawing), {}, name));
}

// Grid of 4 + 4 lines across a 400 px canvas: 25 regions, 16 four-way junctions, 40 cracks,
// 16 ends on the border, right angles everywhere.
TEST(ExemplarSynthetic, GridOfSquares) {
  for (int width : {1, 2, 3, 5, 7}) {
    SCOPED_TRACE("line width " + std::to_string(width));
    const ExemplarAnalysis a = analyze(test::grid_drawing(400, 100, width));
    ASSERT_EQ(a.mask.width, 400);
    const PatternStats& s = a.stats;
    EXPECT_EQ(s.fragment_count, 25);
    EXPECT_EQ(s.junction_count, 16);
    EXPECT_EQ(s.x_count, 16);
    EXPECT_EQ(s.crack_count, 40);
    EXPECT_EQ(s.border_end_count, 16);
    EXPECT_EQ(s.end_count, 0);
    // The 9 inner cells are equal squares of 100 × 100 px: each takes half of the strokes around
    // it (crack pixels go to the nearest fragment), whatever the pen width. Ties on the stroke's
    // centre line go one way, so a cell may gain or lose that line: ±1 px of 100 per side.
    const cv::Mat drawing = test::grid_drawing(400, 100, width);
    const double inner = 100.0 * 100.0 / (400.0 * 400.0);
    int equal = 0;
    for (double area : s.fragment_areas) equal += std::abs(area - inner) <= 0.02 * inner;
    EXPECT_GE(equal, 9);
    double total = 0.0;
    for (double area : s.fragment_areas) total += area;
    EXPECT_NEAR(total, 1.0, 1e-12);  // every pixel belongs to a fragment
    // Skeleton angles of straight crossings: within 2° of 90 (pixel-quantised directions).
    EXPECT_NEAR(s.mean_junction_angle_deg, 90.0, 2.0);
    for (const JunctionStat& j : s.junctions)
      for (double gap : j.gaps_deg) EXPECT_NEAR(gap, 90.0, 3.0);
    EXPECT_EQ(s.relaxation_mode, RelaxationMode::Directional);
    // The measured crack width follows the drawn stroke (counted across a line away from the
    // crossings), ±1 px: area over skeleton length counts the crossings once.
    const double stroke = cv::countNonZero(drawing.col(10).rowRange(0, 100));
    EXPECT_NEAR(a.diagnostics.crack_width_px, stroke, 1.0);
  }
}

// A dense network of oblique crossings (2048², 24 px pitch, 3 px strokes). An oblique crossing
// of strokes thins to two junctions a stroke width apart, which pruning contracts into one 4-way
// junction when they are closer than the merge length: thousands of contractions, which the
// analysis once did in quadratic time (10 s here, 207 s at 4096²; now 0.4 s / 2.3 s).
TEST(ExemplarSynthetic, DenseObliqueCrossingsAreContracted) {
  const ExemplarAnalysis a = analyze(test::oblique_grid_drawing(2048, 24, 3));
  // Crossings whose centre lies inside the image: 7,267; those at least a stroke from the border
  // (the others may merge into the border): 7,183. Each crossing is either one contracted 4-way
  // junction or, when its two junctions lie a merge length or more apart, two 3-way ones.
  const int crossings = (a.stats.junction_count + a.stats.x_count) / 2;
  EXPECT_GE(crossings, 7183);
  EXPECT_LE(crossings, 7267);
  EXPECT_EQ(a.stats.x_count, a.diagnostics.junctions_contracted);  // no crossing thins to one junction here
  EXPECT_GT(a.diagnostics.junctions_contracted, 1000);              // measured 3,328
}

TEST(ExemplarSynthetic, BrickWallHasRightAngledTs) {
  const ExemplarAnalysis a = analyze(test::brick_drawing(480, 60, 3));
  const PatternStats& s = a.stats;
  ASSERT_GT(s.junction_count, 20);
  EXPECT_EQ(s.x_count, 0);
  EXPECT_EQ(s.y_count, 0);
  EXPECT_EQ(s.t_count, s.junction_count);
  EXPECT_NEAR(s.mean_junction_angle_deg, 90.0, 2.0);
  EXPECT_EQ(s.relaxation_mode, RelaxationMode::Directional);
}

TEST(ExemplarSynthetic, HoneycombHasY120) {
  const ExemplarAnalysis a = analyze(test::honeycomb_drawing(500, 40.0, 3));
  const PatternStats& s = a.stats;
  ASSERT_GT(s.junction_count, 50);
  EXPECT_EQ(s.t_count, 0);
  EXPECT_EQ(s.x_count, 0);
  // Rasterised hexagon edges (integer vertices) deviate from 120° by a few degrees.
  EXPECT_NEAR(s.mean_junction_angle_deg, 120.0, 4.0);
  EXPECT_EQ(s.relaxation_mode, RelaxationMode::Isotropic);
  // All interior cells have the hexagon's area, 3√3/2·r² minus the stroke.
  const double hexagon = 1.5 * std::sqrt(3.0) * 40.0 * 40.0 / (500.0 * 500.0);
  int interior = 0, close = 0;
  for (double area : s.fragment_areas) {
    if (area > 0.7 * hexagon && area < 1.1 * hexagon) ++close;
    ++interior;
  }
  EXPECT_GT(close, 40);
}

TEST(ExemplarSynthetic, OneLineAcross) {
  cv::Mat c = test::blank_canvas(300, 200);
  cv::line(c, {0, 80}, {299, 120}, cv::Scalar(255), 3);
  const PatternStats s = analyze(c).stats;
  EXPECT_EQ(s.fragment_count, 2);
  EXPECT_EQ(s.crack_count, 1);
  EXPECT_EQ(s.junction_count, 0);
  EXPECT_EQ(s.border_end_count, 2);
  // The two sides share the stroke between them: together they are the whole image.
  EXPECT_NEAR(s.fragment_areas[0] + s.fragment_areas[1], 1.0, 1e-12);
  // Length: the segment's, normalised by √(area), within 2 % (the skeleton stops a few pixels
  // short of the frame; the 1-px simplification removes the staircase's +4.6 %).
  EXPECT_NEAR(s.crack_lengths[0], std::hypot(299.0, 40.0) / std::sqrt(300.0 * 200.0), 0.02 * s.crack_lengths[0]);
  EXPECT_EQ(s.relaxation_mode, RelaxationMode::Isotropic);  // no junction: no preferred direction
}

TEST(ExemplarSynthetic, EmptyImageIsRefused) {
  try {
    analyze(test::blank_canvas(100, 100), "empty.png");
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("empty.png: image is blank"), std::string::npos) << e.what();
  }
}

// Statistics must not depend on how the tracing was drawn or stored.
void expect_same_pattern(const PatternStats& a, const PatternStats& b, double area_tolerance, const char* what) {
  SCOPED_TRACE(what);
  EXPECT_EQ(a.fragment_count, b.fragment_count);
  EXPECT_EQ(a.junction_count, b.junction_count);
  EXPECT_EQ(a.crack_count, b.crack_count);
  const std::size_t n = std::min(a.fragment_areas.size(), b.fragment_areas.size());
  for (std::size_t i = 0; i < n; ++i) EXPECT_NEAR(a.fragment_areas[i], b.fragment_areas[i], area_tolerance * a.fragment_areas[i]);
  EXPECT_LT(pattern_similarity(a, b).total, 0.05);
}

TEST(ExemplarInvariance, PolarityJpegAndNoise) {
  const cv::Mat drawing = test::closed_grid_drawing(400, 5, 60, 3);
  const PatternStats reference = analyze(drawing).stats;
  ASSERT_EQ(reference.fragment_count, 26);  // 25 cells + the outside
  ASSERT_EQ(reference.junction_count, 4 * 4 + 4 * 4);  // 16 X inside, 16 T on the frame

  cv::Mat inverted = 255 - drawing;
  expect_same_pattern(reference, analyze(inverted).stats, 1e-12, "polarity");

  std::vector<std::uint8_t> jpeg;
  cv::imencode(".jpg", drawing, jpeg, {cv::IMWRITE_JPEG_QUALITY, 40});
  expect_same_pattern(reference, analyze(cv::imdecode(jpeg, cv::IMREAD_GRAYSCALE)).stats, 0.02, "JPEG quality 40");

  cv::Mat noisy = drawing.clone();
  Rng rng(7);  // seeded fissure::Rng (was OpenCV's cv::RNG)
  for (int k = 0; k < 400 * 400 / 200; ++k) {  // 0.5 % salt and pepper
    const int y = static_cast<int>(rng.uniform_index(400)), x = static_cast<int>(rng.uniform_index(400));
    noisy.at<std::uint8_t>(y, x) = k % 2 ? 255 : 0;
  }
  expect_same_pattern(reference, analyze(noisy).stats, 0.02, "salt and pepper");
}

// Resamples a drawing by `factor` (area averaging down, linear up) and re-binarises at 50 %.
cv::Mat rescaled(const cv::Mat& drawing, double factor) {
  cv::Mat out;
  cv::resize(drawing, out, cv::Size(), factor, factor, factor < 1.0 ? cv::INTER_AREA : cv::INTER_LINEAR);
  cv::threshold(out, out, 127, 255, cv::THRESH_BINARY);
  return out;
}

TEST(ExemplarInvariance, ScaleAndRotation) {
  const cv::Mat drawing = test::closed_grid_drawing(400, 5, 60, 3);
  const PatternStats reference = analyze(drawing).stats;
  // The same drawing resampled to half and double size. Re-rasterising moves each stroke edge by
  // up to half a pixel: at half size a 27.5-px cell side can lose 0.5 px on each axis, i.e. up to
  // 2 × 0.5 / 27.5 = 3.7 % of its area; doubled, 2 × 0.5 / 110 = 0.9 %.
  expect_same_pattern(reference, analyze(rescaled(drawing, 0.5)).stats, 0.037, "0.5x");
  expect_same_pattern(reference, analyze(rescaled(drawing, 2.0)).stats, 0.01, "2x");
  // 90°: an exact pixel permutation.
  cv::Mat rotated;
  cv::rotate(drawing, rotated, cv::ROTATE_90_CLOCKWISE);
  expect_same_pattern(reference, analyze(rotated).stats, 1e-12, "90 deg");
  // 30°: resampled with interpolation; areas within 3 % (the stroke edges are re-rasterised),
  // angles within 3° of the straight grid's.
  cv::Mat big = test::blank_canvas(600, 600);
  drawing.copyTo(big(cv::Rect(100, 100, 400, 400)));
  cv::Mat turned;
  cv::warpAffine(big, turned, cv::getRotationMatrix2D({300, 300}, 30.0, 1.0), big.size(), cv::INTER_LINEAR);
  cv::threshold(turned, turned, 127, 255, cv::THRESH_BINARY);
  const PatternStats s = analyze(turned).stats;
  EXPECT_EQ(s.fragment_count, reference.fragment_count);
  EXPECT_EQ(s.junction_count, reference.junction_count);
  EXPECT_NEAR(s.mean_junction_angle_deg, reference.mean_junction_angle_deg, 3.0);
  // Cells are not cut by the frame in either, so their areas compare (the outside does not).
  std::vector<double> a(reference.fragment_areas.begin() + 1, reference.fragment_areas.end());
  std::vector<double> b(s.fragment_areas.begin() + 1, s.fragment_areas.end());
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(b[i] * 600 * 600, a[i] * 400 * 400, 0.03 * a[i] * 400 * 400);
}

// The same pattern built as a planar graph (what a simulation produces) and drawn as an image
// gives the same statistics: one set of definitions for both.
TEST(ExemplarPlanarGraph, PolygonsAndImageAgree) {
  // A 1 m square split into 4 × 4 cells by 3 + 3 cracks across (metres).
  PlanarCrackGraph g;
  g.total_area = 1.0;
  g.frame_min = {0, 0};
  g.frame_max = {1, 1};
  g.crack_width = 0.0;
  std::map<std::pair<int, int>, int> node_at;
  auto node = [&](int i, int j) {
    const auto key = std::pair{i, j};
    if (!node_at.count(key)) {
      CrackNode n;
      n.position = {i / 4.0, j / 4.0};
      const bool border = i == 0 || j == 0 || i == 4 || j == 4;
      n.kind = border ? CrackNode::Kind::Border : CrackNode::Kind::Junction;
      n.degree = border ? 1 : 4;
      node_at[key] = static_cast<int>(g.nodes.size());
      g.nodes.push_back(n);
    }
    return node_at[key];
  };
  for (int line = 1; line <= 3; ++line) {
    for (int k = 0; k < 4; ++k) {
      g.cracks.push_back(Crack{{{line / 4.0, k / 4.0}, {line / 4.0, (k + 1) / 4.0}}, node(line, k), node(line, k + 1)});
      g.cracks.push_back(Crack{{{k / 4.0, line / 4.0}, {(k + 1) / 4.0, line / 4.0}}, node(k, line), node(k + 1, line)});
    }
  }
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      Fragment f;
      f.outline = {{i / 4.0, j / 4.0}, {(i + 1) / 4.0, j / 4.0}, {(i + 1) / 4.0, (j + 1) / 4.0}, {i / 4.0, (j + 1) / 4.0}};
      f.area = polygon_area(f.outline);
      f.touches_border = i == 0 || j == 0 || i == 3 || j == 3;
      g.fragments.push_back(f);
    }
  PatternStatsOptions options;
  options.probe_min = 0.02;  // graph units are metres here
  const PatternStats from_graph = compute_pattern_stats(g, options);
  EXPECT_EQ(from_graph.fragment_count, 16);
  EXPECT_EQ(from_graph.junction_count, 9);
  EXPECT_EQ(from_graph.x_count, 9);
  EXPECT_EQ(from_graph.crack_count, 24);
  EXPECT_NEAR(from_graph.mean_junction_angle_deg, 90.0, 1e-9);
  // The same pattern drawn at 400 px with 3-px cracks (lines at 100, 200, 300).
  cv::Mat c = test::blank_canvas(400, 400);
  for (int p : {100, 200, 300}) {
    cv::line(c, {p, 0}, {p, 399}, cv::Scalar(255), 3);
    cv::line(c, {0, p}, {399, p}, cv::Scalar(255), 3);
  }
  const PatternStats from_image = analyze(c).stats;
  EXPECT_EQ(from_image.fragment_count, from_graph.fragment_count);
  EXPECT_EQ(from_image.junction_count, from_graph.junction_count);
  EXPECT_EQ(from_image.crack_count, from_graph.crack_count);
  // Drawn cracks take area: ≈ 3·400·6 px of 400², so image fragments are ~4.5 % smaller.
  const Similarity d = pattern_similarity(from_graph, from_image);
  EXPECT_LT(d.total, 0.05) << d.fragment << " " << d.crack << " " << d.junction;
}

TEST(ExemplarJson, RoundTripKeepsEverythingCompared) {
  const PatternStats s = analyze(test::brick_drawing(300, 50, 2)).stats;
  const PatternStats back = pattern_stats_from_json(pattern_stats_to_json(s), "mem");
  EXPECT_EQ(back.fragment_count, s.fragment_count);
  EXPECT_EQ(back.junction_count, s.junction_count);
  EXPECT_EQ(back.fragment_areas, s.fragment_areas);
  EXPECT_EQ(pattern_similarity(s, back).total, 0.0);
  EXPECT_THROW(pattern_stats_from_json("{\"format\": 99}", "x.json"), IoError);
  EXPECT_THROW(pattern_stats_from_json("not json", "x.json"), IoError);
  EXPECT_THROW(pattern_stats_from_json("{\"format\": 1}", "x.json"), IoError);
}

}  // namespace
}  // namespace fissure
