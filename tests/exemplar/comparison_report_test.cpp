// write_comparison_report: the two drawings land in their panels, each histogram's bars sit over
// the bins that hold its mass, and bad input or an unwritable file is refused by name.

#include "fissure/base/error.hpp"
#include "fissure/exemplar/comparison_report.hpp"
#include "fissure/exemplar/exemplar_analysis.hpp"

#include "drawings.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include <cstdlib>
#include <string>

namespace fissure {
namespace {

namespace fs = std::filesystem;

PatternStats bricks() {
  return analyze_crack_mask(crack_mask_from_grey(test::to_grey_image(test::brick_drawing(240, 40, 2)), {}, "bricks")).stats;
}

GreyImage flat(int width, int height, std::uint8_t value) {
  return {width, height, std::vector<std::uint8_t>(static_cast<std::size_t>(width) * height, value)};
}

// Pixels within `tolerance` of `colour` (BGR) in every channel, in the rectangle (anti-aliased
// lines blend their edges; filled bars are exact).
int count_colour(const cv::Mat& image, const cv::Rect& r, const cv::Vec3b& colour, int tolerance = 0) {
  int n = 0;
  for (int y = r.y; y < r.y + r.height; ++y)
    for (int x = r.x; x < r.x + r.width; ++x) {
      const cv::Vec3b p = image.at<cv::Vec3b>(y, x);
      bool close = true;
      for (int c = 0; c < 3; ++c) close = close && std::abs(p[c] - colour[c]) <= tolerance;
      n += close;
    }
  return n;
}

TEST(ComparisonReport, DrawingsAndBarsLandWhereTheirDataSays) {
  const fs::path dir = test::fresh_temp_dir("comparison-report");
  ComparisonReport r;
  r.title = "test";
  r.left_label = "black";
  r.right_label = "white";
  r.left_image = flat(200, 100, 0);
  r.right_image = flat(200, 100, 255);
  r.left = bricks();
  r.right = r.left;
  // The left pattern's fragment mass all in the first bin, the right's all in the last.
  std::fill(r.left.fragment_area_hist.p.begin(), r.left.fragment_area_hist.p.end(), 0.0);
  r.left.fragment_area_hist.p.front() = 1.0;
  std::fill(r.right.fragment_area_hist.p.begin(), r.right.fragment_area_hist.p.end(), 0.0);
  r.right.fragment_area_hist.p.back() = 1.0;
  write_comparison_report(dir / "r.png", r);
  const cv::Mat image = cv::imread((dir / "r.png").string(), cv::IMREAD_COLOR);
  ASSERT_FALSE(image.empty());
  EXPECT_EQ(image.cols, kComparisonReportWidth);
  // Panels are 770 px wide from x = 20 and x = 810; both 2:1 drawings fill a 770 x 385 box from y = 78.
  EXPECT_EQ(image.at<cv::Vec3b>(78 + 192, 20 + 385), cv::Vec3b(0, 0, 0));
  EXPECT_EQ(image.at<cv::Vec3b>(78 + 192, 810 + 385), cv::Vec3b(255, 255, 255));
  // Fragment panel: x in [20, 526), its plot from x = 60, y from 78 + 385 + 50 = 513. The blue
  // bar (the left pattern) fills the first of 24 bins, nothing of it in the right half.
  const cv::Vec3b blue(190, 140, 80);
  const int plot_x = 60, plot_w = (1600 - 80) / 3 - 50, plot_y = 517;
  EXPECT_GT(count_colour(image, {plot_x, plot_y, plot_w / 24, 250}, blue), 1000);
  EXPECT_EQ(count_colour(image, {plot_x + plot_w / 2, plot_y, plot_w / 2, 250}, blue), 0);
  // The red step (the right pattern) tops the last bin (at 1/1.1 of the plot's 260 px); over the
  // empty middle bins it lies on the plot's floor, below the band checked.
  const cv::Vec3b red(40, 70, 220);
  EXPECT_GT(count_colour(image, {plot_x + plot_w * 23 / 24, plot_y + 14, plot_w / 24, 20}, red, 40), 10);
  EXPECT_EQ(count_colour(image, {plot_x + plot_w / 4, plot_y + 14, plot_w / 2, 200}, red, 40), 0);
}

TEST(ComparisonReport, StatisticsOnlyAndBadInput) {
  const fs::path dir = test::fresh_temp_dir("comparison-report-bad");
  ComparisonReport r;
  r.left = bricks();
  r.right = r.left;
  write_comparison_report(dir / "stats-only.png", r);  // no drawings: blank panels with a note
  EXPECT_TRUE(fs::exists(dir / "stats-only.png"));
  ComparisonReport broken = r;
  broken.left_image = GreyImage{10, 10, std::vector<std::uint8_t>(5, 0)};
  try {
    write_comparison_report(dir / "broken.png", broken);
    ADD_FAILURE() << "an inconsistent image was drawn";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("broken.png"), std::string::npos) << e.what();
  }
  ComparisonReport other_bins = r;
  other_bins.right.crack_length_hist = Histogram::make(-4, 0, 8);
  EXPECT_THROW(write_comparison_report(dir / "bins.png", other_bins), InvalidInput);
  EXPECT_FALSE(fs::exists(dir / "broken.png"));
  EXPECT_FALSE(fs::exists(dir / "bins.png"));
  EXPECT_THROW(write_comparison_report(dir / "no" / "such" / "r.png", r), IoError);
}

}  // namespace
}  // namespace fissure
