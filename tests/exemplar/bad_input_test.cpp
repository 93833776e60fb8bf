#include "fissure/base/atomic_file.hpp"
#include "fissure/base/error.hpp"
#include "fissure/exemplar/exemplar_analysis.hpp"

#include "drawings.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include <limits>

namespace fissure {
namespace {
namespace fs = std::filesystem;

std::string error_of(const fs::path& path, const CrackImageOptions& options = {}) {
  try {
    ExemplarAnalysisOptions o;
    o.image = options;
    analyze_exemplar(path, o);
  } catch (const IoError& e) {
    return std::string("IoError: ") + e.what();
  } catch (const InvalidInput& e) {
    return std::string("InvalidInput: ") + e.what();
  }
  return "no error";
}

void expect(const std::string& error, const std::string& kind, const fs::path& file, const std::string& words) {
  EXPECT_EQ(error.rfind(kind, 0), 0u) << error;
  EXPECT_NE(error.find(file.string()), std::string::npos) << error;
  EXPECT_NE(error.find(words), std::string::npos) << error;
}

TEST(ExemplarBadInput, FilesAreNamed) {
  const fs::path dir = test::fresh_temp_dir("exemplar-bad");
  expect(error_of(dir / "missing.png"), "IoError", dir / "missing.png", "no such file");
  write_file_atomically(dir / "zero.png", "");
  expect(error_of(dir / "zero.png"), "IoError", dir / "zero.png", "empty");
  write_file_atomically(dir / "noise.png", std::string(5000, '\x42'));
  expect(error_of(dir / "noise.png"), "IoError", dir / "noise.png", "cannot decode");
  // A valid PNG cut in half.
  std::vector<std::uint8_t> png;
  cv::imencode(".png", test::grid_drawing(200, 50, 3), png);
  write_file_atomically(dir / "cut.png", std::string(png.begin(), png.begin() + static_cast<long>(png.size() / 2)));
  // Used to accept either error class: a cut file is a file problem, and says so.
  expect(error_of(dir / "cut.png"), "IoError", dir / "cut.png", "truncated");

  cv::imwrite((dir / "blank.png").string(), test::blank_canvas(64, 64));
  expect(error_of(dir / "blank.png"), "InvalidInput", dir / "blank.png", "blank");
  // All crack, as a user would save it: a uniformly white tracing.
  cv::Mat all(64, 64, CV_8U, cv::Scalar(255));
  cv::imwrite((dir / "allcrack.png").string(), all);
  expect(error_of(dir / "allcrack.png"), "InvalidInput", dir / "allcrack.png", "nothing but crack");
  // Only a speck: no crack to measure.
  all.setTo(0);
  all.at<std::uint8_t>(30, 30) = 255;
  cv::imwrite((dir / "speck.png").string(), all);
  expect(error_of(dir / "speck.png"), "InvalidInput", dir / "speck.png", "no crack found");
  cv::imwrite((dir / "tiny.png").string(), test::grid_drawing(3, 2, 1));
  expect(error_of(dir / "tiny.png"), "InvalidInput", dir / "tiny.png", "smaller than");
}

TEST(ExemplarBadInput, AllCrackIsRefused) {
  GreyImage image;
  image.width = image.height = 64;
  image.pixels.assign(64 * 64, 255);
  image.pixels[5] = 254;  // Otsu splits 254 | 255; with --threshold 0 every pixel is crack
  CrackImageOptions options;
  options.threshold = 0;
  options.polarity = CrackPolarity::LightOnDark;
  try {
    crack_mask_from_grey(image, options, "white.png");
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("white.png: every pixel is crack"), std::string::npos) << e.what();
  }
}

TEST(ExemplarBadInput, RoiOfTheWrongSize) {
  const fs::path dir = test::fresh_temp_dir("exemplar-roi");
  cv::imwrite((dir / "grid.png").string(), test::grid_drawing(200, 50, 3));
  cv::imwrite((dir / "roi.png").string(), cv::Mat(100, 100, CV_8U, cv::Scalar(255)));
  CrackImageOptions options;
  options.roi_path = dir / "roi.png";
  expect(error_of(dir / "grid.png", options), "InvalidInput", dir / "roi.png", "100 x 100");
  // A correct ROI restricts the area: the left half of the grid.
  cv::Mat half(200, 200, CV_8U, cv::Scalar(0));
  half.colRange(0, 100).setTo(255);
  cv::imwrite((dir / "half.png").string(), half);
  options.roi_path = dir / "half.png";
  ExemplarAnalysisOptions o;
  o.image = options;
  const ExemplarAnalysis a = analyze_exemplar(dir / "grid.png", o);
  EXPECT_DOUBLE_EQ(a.stats.total_area, 200.0 * 100.0);
  // Inside the ROI: columns [0, 25), [25, 75), [75, 100) between the lines at 25 and 75, by the
  // five rows the horizontal lines at 25, 75, 125, 175 make.
  EXPECT_EQ(a.stats.fragment_count, 3 * 5);
}

// A 100-megapixel image is refused from its header, before any decoding, with the limit named.
TEST(ExemplarBadInput, HugeImageRefusedBeforeDecoding) {
  const fs::path dir = test::fresh_temp_dir("exemplar-huge");
  // PNG signature + IHDR claiming 10000 × 10000 (the pixel data is never reached).
  std::string png("\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR", 16);
  const unsigned char size[8] = {0, 0, 0x27, 0x10, 0, 0, 0x27, 0x10};
  png.append(reinterpret_cast<const char*>(size), 8);
  png.append("\x08\x00\x00\x00\x00", 5);
  png.append(64, '\0');
  write_file_atomically(dir / "huge.png", png);
  expect(error_of(dir / "huge.png"), "InvalidInput", dir / "huge.png", "100 megapixels, above the limit of 64");
  // The core names no command-line flag (used to say "raise it with --max-megapixels", which
  // `fissure compare` does not have): the CLI adds its own hint.
  EXPECT_EQ(error_of(dir / "huge.png").find("--"), std::string::npos) << error_of(dir / "huge.png");
  CrackImageOptions raised;
  raised.max_pixels = 200'000'000;
  // With the limit raised the file is decoded and found corrupt (its IHDR checksum is zero): an
  // IoError, no crash, nothing allocated for the 100 megapixels.
  expect(error_of(dir / "huge.png", raised), "IoError", dir / "huge.png", "CRC error");
}

// Used to segfault: minmax_element on an empty pixel vector dereferenced end().
TEST(ExemplarBadInput, GreyImageOfTheWrongSizeIsRefused) {
  GreyImage image;
  image.width = image.height = 64;
  image.pixels.assign(10, 255);
  try {
    crack_mask_from_grey(image, {}, "render");
    FAIL() << "accepted";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(std::string(e.what()), "render: image: holds 10 pixels, not 64 x 64 = 4096");
  }
  image.pixels.clear();
  EXPECT_THROW(crack_mask_from_grey(image, {}, "render"), InvalidInput);
  image.width = -3;
  EXPECT_THROW(crack_mask_from_grey(image, {}, "render"), InvalidInput);
}

std::string options_error(const ExemplarAnalysisOptions& options) {
  try {
    options.validate();
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "valid";
}

// Used to be accepted: a NaN spur factor (every comparison with it is false, so nothing is
// pruned), a non-positive pixel limit, an impossible threshold. Options are checked before any
// work, naming the field.
TEST(ExemplarBadInput, OptionsAreValidated) {
  EXPECT_EQ(options_error({}), "valid");
  struct Case {
    const char* expected;
    void (*spoil)(ExemplarAnalysisOptions&);
  };
  const Case cases[] = {
      {"graph: spur_factor nan is negative or not finite",
       [](ExemplarAnalysisOptions& o) { o.graph.spur_factor = std::numeric_limits<double>::quiet_NaN(); }},
      {"graph: merge_factor -1 is negative", [](ExemplarAnalysisOptions& o) { o.graph.merge_factor = -1; }},
      {"graph: simplify_px inf", [](ExemplarAnalysisOptions& o) { o.graph.simplify_px = std::numeric_limits<double>::infinity(); }},
      {"graph: min_fragment_px -4 is negative", [](ExemplarAnalysisOptions& o) { o.graph.min_fragment_px = -4; }},
      {"graph: smoothing_points 5000 is outside [0, 1000]", [](ExemplarAnalysisOptions& o) { o.graph.smoothing_points = 5000; }},
      {"image: max_pixels 0 is not positive", [](ExemplarAnalysisOptions& o) { o.image.max_pixels = 0; }},
      {"image: max_pixels -5 is not positive", [](ExemplarAnalysisOptions& o) { o.image.max_pixels = -5; }},
      {"image: threshold 300 is outside [0, 255]", [](ExemplarAnalysisOptions& o) { o.image.threshold = 300; }},
      {"image: polarity 7 is not auto, light or dark", [](ExemplarAnalysisOptions& o) { o.image.polarity = static_cast<CrackPolarity>(7); }},
      {"stats: density_windows 0 is outside [1, 1000]", [](ExemplarAnalysisOptions& o) { o.stats.density_windows = 0; }},
      {"stats: t_gap_deg nan is outside (0, 360]",
       [](ExemplarAnalysisOptions& o) { o.stats.t_gap_deg = std::numeric_limits<double>::quiet_NaN(); }},
      {"stats: directional range [90, 75] deg", [](ExemplarAnalysisOptions& o) { std::swap(o.stats.directional_min_deg, o.stats.directional_max_deg); }},
      {"stats: probe_min -8", [](ExemplarAnalysisOptions& o) { o.stats.probe_min = -8; }},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.expected);
    ExemplarAnalysisOptions o;
    c.spoil(o);
    const std::string message = options_error(o);
    EXPECT_EQ(message.rfind("exemplar analysis options: ", 0), 0u) << message;
    EXPECT_NE(message.find(c.expected), std::string::npos) << message;
    // Refused at the entry of the pipeline, before the (missing) file is opened.
    try {
      analyze_exemplar("/nonexistent/tracing.png", o);
      ADD_FAILURE() << "accepted";
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find(c.expected), std::string::npos) << e.what();
    }
  }
  // Each stage checks its own options too (callers may enter the pipeline anywhere).
  CrackGraphOptions nan_spur;
  nan_spur.spur_factor = std::numeric_limits<double>::quiet_NaN();
  const CrackMask mask = crack_mask_from_grey(test::to_grey_image(test::grid_drawing(64, 32, 2)), {}, "grid");
  EXPECT_THROW(extract_crack_graph(mask, nan_spur), InvalidInput);
  CrackImageOptions zero;
  zero.max_pixels = 0;
  EXPECT_THROW(load_crack_mask("/nonexistent/tracing.png", zero), InvalidInput);
}

}  // namespace
}  // namespace fissure
