#pragma once
/// A line drawing of a visible crack pattern, like the tracing of a photograph the exemplar module
/// analyses (`fissure analyze`): black crack lines on white, the visible face filling the image in
/// its aspect. Analysing the drawing gives the geometric statistics of the pattern back
/// (tests/fracture/visible_pattern_test.cpp measures how closely), which is what lets a fit compare
/// a simulation with an exemplar either way.
#include "fissure/exemplar/crack_image.hpp"
#include "fissure/fracture/visible_pattern.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace fissure {

struct PatternImageOptions {
  /// The image's long side, pixels; the short side follows the visible face's aspect.
  int long_side_px = 1024;
  /// Crack line width, pixels. Every pixel within half of it from a crack is drawn, so at 3 px a
  /// line is 4-connected at any slope (a 1 px line is only 8-connected on diagonals, which the
  /// analysis accepts but a resampling viewer may open). The analysis loses what is thinner than
  /// the line (a fragment under about a line width across, or under 32 px²) and free-end stubs
  /// shorter than 2 widths (its spur length): 6 px, 0.6 % of the default long side. Measured on
  /// the test patterns: fragment, junction and crack counts equal at every width from 1 to 8 px.
  /// Keep it equal to VisiblePatternOptions::line_width_px, which sets the geometric side's probe.
  double line_width_px = 3.0;

  /// Readable problems naming the field (a long side below kMinImageSide or above 16384, a width
  /// that is not in [1, 64]); empty when valid.
  std::vector<std::string> problems() const;
  void validate() const;
};

struct PatternImage {
  GreyImage drawing;  ///< 0 on cracks, 255 elsewhere
  /// 255 on the visible face, 0 off it; empty when every pixel centre is on the face (a tile's
  /// top face). Pass it to the analysis as the region of interest (`fissure analyze --roi`).
  GreyImage roi;
  double metres_per_pixel = 0.0;
};

/// Draws `pattern` (which must have a visible face: throws InvalidInput naming its source
/// otherwise, or for invalid options). Pixel (i, j) covers u ∈ frame_min.u + [i, i+1)·m, v ∈
/// frame_max.v − [j, j+1)·m, m = metres_per_pixel: rows run against v, so the image shows the
/// face seen from above with v up. A pixel is crack when its centre lies within half the line
/// width of a crack polyline. O(pixels + crack length · width).
PatternImage render_pattern_image(const VisiblePattern& pattern, const PatternImageOptions& options = {});

/// Writes the drawing as a greyscale PNG (atomically) and, when `roi_path` is not empty and the
/// image has a mask, the mask beside it. Throws IoError naming the file that cannot be written.
void write_pattern_image(const std::filesystem::path& path, const PatternImage& image,
                         const std::filesystem::path& roi_path = {});

}  // namespace fissure
