#pragma once
/// From a binary crack mask to a planar crack graph: skeleton, junction clusters, end points,
/// cracks as pixel polylines between nodes, spur and false-junction pruning scaled by the
/// measured crack width, and fragments as the regions the crack pixels enclose.

#include "fissure/exemplar/crack_image.hpp"
#include "fissure/exemplar/planar_crack_graph.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace fissure {

/// Lengths are multiples of the measured crack width w (crack pixels / skeleton length), so a
/// tracing drawn with a thicker pen gives the same graph; the *_min_px floors keep hair-thin
/// (1–2 px) tracings from pruning nothing. Defaults follow the shared reference statistics.
struct CrackGraphOptions {
  double spur_factor = 2.0;     ///< free-end branches shorter than max(spur_min_px, 2w) are spurs
  double spur_min_px = 6.0;
  double merge_factor = 1.0;    ///< junctions closer than w along a crack are one junction
  /// Regions under max(min_fragment_px, (fragment_width_factor·w)²) pixels are crack noise
  /// (specks of background between parallel strokes), not fragments.
  int min_fragment_px = 32;
  double fragment_width_factor = 0.0;
  /// Give every crack pixel to its nearest fragment (ties by scan order), so fragment areas sum to
  /// the whole area and do not depend on the pen width, like the zero-width cracks of a
  /// simulated pattern. Off: fragments are their background pixels only.
  bool assign_crack_pixels = true;
  /// Ends within max(border_px, w/2 + 2) of the frame or ROI edge leave the fractured area.
  int border_px = 2;
  /// Crack polylines are the skeleton chains smoothed by a moving average over ±smoothing_points
  /// pixels, then simplified (Douglas–Peucker) to simplify_px. The raw 8-connected staircase
  /// overstates a slanted crack's length by up to 8 % (1 per axial, √2 per diagonal step);
  /// smoothing removes that without the straight-chord bias a coarse simplification puts on
  /// the first segment at a junction (which tilted measured T junctions by 2°).
  int smoothing_points = 2;
  double simplify_px = 0.25;

  /// Readable problems, each naming the field: a factor or length that is negative or not finite
  /// (NaN compares false with every bound, so it would silently prune nothing or everything), a
  /// negative pixel count, more than kMaxSmoothingPoints smoothing points. Empty when valid.
  std::vector<std::string> problems() const;
  /// Throws InvalidInput "crack graph options: <problems>" when problems() is not empty.
  void validate() const;
};

/// Upper bound of CrackGraphOptions::smoothing_points: the moving average costs
/// (2·smoothing_points + 1) a chain point, and beyond a few pixels it bends real cracks.
constexpr int kMaxSmoothingPoints = 1000;

struct CrackGraphDiagnostics {
  double crack_width_px = 0.0;
  long crack_pixels = 0;
  long skeleton_pixels = 0;
  int raw_end_nodes = 0;
  int raw_junction_clusters = 0;
  int raw_cracks = 0;
  int spurs_pruned = 0;
  int specks_removed = 0;
  int junctions_contracted = 0;
  int tiny_loops_removed = 0;
  int small_fragments_dropped = 0;
  double spur_length_px = 0.0;
  double merge_length_px = 0.0;
  double border_tolerance_px = 0.0;
};

/// Builds the crack graph of `mask` in pixel units (x right, y down, pixel centres at integers).
/// `skeleton`, when given, receives the thinned mask (for overlays). Throws InvalidInput for
/// invalid `options` or a mask whose layers do not match its size. O(pixels).
PlanarCrackGraph extract_crack_graph(const CrackMask& mask, const CrackGraphOptions& options = {},
                                     CrackGraphDiagnostics* diagnostics = nullptr,
                                     std::vector<std::uint8_t>* skeleton = nullptr,
                                     std::vector<std::int32_t>* fragment_labels = nullptr);

}  // namespace fissure
