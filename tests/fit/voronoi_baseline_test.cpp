// The Voronoi baseline (voronoi_baseline.hpp): one visible fragment per point, Y junctions near
// 120° (what a Voronoi diagram is made of), the same drawing for the same seed, bad input named.

#include "fissure/base/error.hpp"
#include "fissure/exemplar/exemplar_analysis.hpp"
#include "fissure/fit/voronoi_baseline.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace fissure {
namespace {

PatternStats analyse(const GreyImage& drawing) {
  return analyze_crack_mask(crack_mask_from_grey(drawing, {}, "voronoi")).stats;
}

TEST(VoronoiBaseline, EveryPointIsAFragmentAndJunctionsAreYs) {
  PatternImageOptions options;
  options.long_side_px = 512;
  int junctions = 0, ts = 0;
  double angle_sum = 0.0;
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    const GreyImage drawing = draw_voronoi_baseline(1.0, 0.6, 25, seed, options);
    ASSERT_EQ(drawing.width, 512);
    ASSERT_EQ(drawing.height, 307);
    const PatternStats s = analyse(drawing);
    // A uniform draw can put two points so close that their cell is under a line width across
    // and the analysis loses it: allow one such cell in 25.
    EXPECT_GE(s.fragment_count, 24) << "seed " << seed;
    EXPECT_LE(s.fragment_count, 25) << "seed " << seed;
    // Voronoi vertices have degree 3; two of them closer than a line width read as one X.
    EXPECT_LE(s.x_count, 1) << "seed " << seed;
    junctions += s.junction_count;
    ts += s.t_count;
    angle_sum += s.mean_junction_angle_deg;
  }
  // Uniform points make some vertices T-like (a gap of 160° or more: 0.2-0.33 per drawing at
  // seeds 1-3), far fewer than a brick or craquelure pattern (over 0.6), and the smallest gap
  // averages near 87° (a T's is 90°, a symmetric Y's 120°).
  EXPECT_LT(static_cast<double>(ts), 0.4 * junctions);
  EXPECT_GT(angle_sum / 3, 80.0);
}

TEST(VoronoiBaseline, SameSeedSameDrawing) {
  PatternImageOptions options;
  options.long_side_px = 128;
  EXPECT_EQ(draw_voronoi_baseline(1.0, 1.0, 10, 7, options).pixels, draw_voronoi_baseline(1.0, 1.0, 10, 7, options).pixels);
  EXPECT_NE(draw_voronoi_baseline(1.0, 1.0, 10, 7, options).pixels, draw_voronoi_baseline(1.0, 1.0, 10, 8, options).pixels);
  // One cell: no boundary at all.
  const GreyImage one = draw_voronoi_baseline(1.0, 1.0, 1, 7, options);
  EXPECT_EQ(std::count(one.pixels.begin(), one.pixels.end(), 0), 0);
}

TEST(VoronoiBaseline, BadInputIsNamed) {
  const auto message = [](auto&& call) -> std::string {
    try {
      call();
    } catch (const InvalidInput& e) {
      return e.what();
    }
    return "accepted";
  };
  EXPECT_NE(message([] { draw_voronoi_baseline(0.0, 1.0, 5, 1); }).find("not positive"), std::string::npos);
  EXPECT_NE(message([] { draw_voronoi_baseline(1.0, std::nan(""), 5, 1); }).find("not positive"), std::string::npos);
  EXPECT_NE(message([] { draw_voronoi_baseline(1.0, 1.0, 0, 1); }).find("0 cells"), std::string::npos);
  PatternImageOptions bad;
  bad.line_width_px = 0.0;
  EXPECT_NE(message([&] { draw_voronoi_baseline(1.0, 1.0, 5, 1, bad); }).find("width"), std::string::npos);
}

}  // namespace
}  // namespace fissure
