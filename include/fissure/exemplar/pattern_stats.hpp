#pragma once
/// The statistics of a crack pattern (paper §4, §6.1): S1 fragments, S2 cracks, S3 junctions,
/// normalised so an exemplar (pixels) and a simulation (metres) compare directly, plus junction
/// angles, which choose the stress-relaxation mode (paper §5.2, Eq. 3 or Eq. 4).

#include "fissure/exemplar/histogram.hpp"
#include "fissure/exemplar/planar_crack_graph.hpp"

#include <string>
#include <vector>

namespace fissure {

enum class RelaxationMode {
  Directional,  ///< Eq. 3: relax along d; chosen when the mean junction angle is in [75°, 90°]
  Isotropic,    ///< Eq. 4: relax in every direction
};

enum class JunctionType { T, Y, X };

struct JunctionStat {
  int node = -1;  ///< index in the graph's nodes
  Eigen::Vector2d position = Eigen::Vector2d::Zero();  ///< normalised: frame mapped to area 1
  int degree = 0;
  JunctionType type = JunctionType::Y;
  /// Gaps between consecutive crack directions around the junction, degrees, summing to 360.
  std::vector<double> gaps_deg;
  /// The junction angle: its smallest gap, i.e. the angle at which the arriving crack meets the
  /// one it stops on (90° for a T, 120° for a symmetric Y, < 90° for a skewed T).
  double angle_deg = 0.0;
};

struct PatternStatsOptions {
  /// The direction of a crack at a junction is the secant between the points at arc lengths
  /// near = max(near_factor·w, probe_min/4) and far = max(far_factor·w, probe_min) from it (w the
  /// crack width; at most a quarter and half of the crack's length). Skipping the first width
  /// matters: a thinned T bends into a Y within about one width of its junction, and a chord
  /// from the junction itself makes T junctions read 10–20° too open (measured on the shared
  /// exemplars: T fractions 0.13 instead of 0.62 on ace-craquelure-fl187).
  double probe_near_factor = 2.0;
  double probe_far_factor = 4.0;
  double probe_min = 8.0;
  /// A degree-3 junction whose largest gap is at least this is a T (a crack ending on a straight
  /// one); otherwise a Y. Degree ≥ 4: X.
  double t_gap_deg = 160.0;
  /// S3: junction counts in a k × k grid of windows over the frame.
  int density_windows = 4;
  /// Eq. 3 when the mean junction angle lies in this range (degrees), else Eq. 4 (paper §5.2).
  double directional_min_deg = 75.0;
  double directional_max_deg = 90.0;
  /// Drop fragments cut by the border of the fractured area from S1 (their true size is
  /// unknown). Off by default, as in the shared reference statistics: on small exemplars most
  /// fragments touch the frame.
  bool exclude_border_fragments = false;

  /// Readable problems, each naming the field (negative or non-finite probe lengths, a T gap
  /// outside (0, 360], a window count outside [1, kMaxDensityWindows], a directional range that
  /// is not finite or has min > max). Empty when valid.
  std::vector<std::string> problems() const;
  /// Throws InvalidInput "pattern statistics options: <problems>" when problems() is not empty.
  void validate() const;
};

/// Upper bound of PatternStatsOptions::density_windows: k² counters are allocated.
constexpr int kMaxDensityWindows = 1000;

/// Normalised statistics. Areas are divided by the total fractured area A, lengths by √A; the
/// junction density is the count per unit normalised area (so equal to the count); histograms
/// are unit-mass on fixed bins (below), so patterns of any size compare.
struct PatternStats {
  std::string source;
  double total_area = 0.0;   ///< in the graph's units² (pixels² or m²), before normalisation
  double crack_width = 0.0;  ///< normalised by √A

  // S1: fragments
  int fragment_count = 0;
  int fragments_touching_border = 0;
  std::vector<double> fragment_areas;  ///< normalised, largest first
  Histogram fragment_area_hist;        ///< log10(area): [−6, 0] in 24 bins of 0.25

  // S2: cracks
  int crack_count = 0;
  double total_crack_length = 0.0;     ///< normalised
  std::vector<double> crack_lengths;   ///< normalised, longest first
  Histogram crack_length_hist;         ///< log10(length): [−4, 0] in 16 bins of 0.25

  // S3: junctions
  int junction_count = 0;
  double junction_density = 0.0;       ///< junctions per unit normalised area
  Histogram junction_density_hist;     ///< log10(1 + local density) over k×k windows: [0, 5], 20 bins
  int end_count = 0;                   ///< free crack ends inside the area
  int border_end_count = 0;            ///< cracks leaving the area
  int t_count = 0, y_count = 0, x_count = 0;
  std::vector<JunctionStat> junctions;
  /// Mean of JunctionStat::angle_deg over the degree-3 junctions (all junctions when there is no
  /// degree-3 one; 0 without junctions). Degree ≥ 4 nodes of real tracings are mostly two Ys
  /// merged by the stroke width, whose smallest gap says nothing about how a crack arrives:
  /// including them sent the Y-like kz-mudcrack-300 to Eq. 3 (88.6° instead of 92.9°).
  double mean_junction_angle_deg = 0.0;
  Histogram junction_angle_hist;         ///< all gaps, degrees: [0, 360], 36 bins of 10°
  RelaxationMode relaxation_mode = RelaxationMode::Isotropic;
};

/// Computes the statistics of a planar crack graph. Throws InvalidInput when the graph is
/// inconsistent (PlanarCrackGraph::validate, naming its source) or `options` are invalid.
/// O(points + junctions).
PatternStats compute_pattern_stats(const PlanarCrackGraph& graph, const PatternStatsOptions& options = {});

/// The relaxation mode a mean junction angle selects (Eq. 3 in [min, max], else Eq. 4).
RelaxationMode relaxation_mode_for(double mean_junction_angle_deg, const PatternStatsOptions& options = {});

const char* to_string(RelaxationMode mode);
const char* to_string(JunctionType type);

}  // namespace fissure
