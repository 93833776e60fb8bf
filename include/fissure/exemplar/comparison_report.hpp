#pragma once
/// A picture that shows why two crack patterns score what they score under Eq. 5: the two
/// drawings side by side and, under them, the three histograms the error compares (fragment
/// areas, crack lengths, junction density), each with both patterns overlaid and its EMD term.
/// `fissure fit --report` draws the exemplar against the fitted pattern with it, `fissure
/// compare --report` any two patterns.
#include "fissure/exemplar/crack_image.hpp"
#include "fissure/exemplar/pattern_stats.hpp"
#include "fissure/exemplar/similarity.hpp"

#include <filesystem>
#include <string>

namespace fissure {

struct ComparisonReport {
  std::string title;
  std::string left_label;   ///< e.g. "exemplar kz-mudcrack-300.png"
  std::string right_label;  ///< e.g. "fitted pattern (seed 1)"
  /// The drawings; an empty image (0 x 0) leaves its panel blank with a note (statistics read
  /// from JSON have no picture).
  GreyImage left_image;
  GreyImage right_image;
  PatternStats left;
  PatternStats right;
  SimilarityWeights weights;
};

/// Width of the report, pixels (the height follows the drawings' aspect).
constexpr int kComparisonReportWidth = 1600;

/// Draws the report and writes it as an RGB PNG, atomically. Throws InvalidInput naming `path` for
/// an inconsistent image or histograms on other bins than the statistics' own, IoError when the
/// file cannot be written.
void write_comparison_report(const std::filesystem::path& path, const ComparisonReport& report);

}  // namespace fissure
