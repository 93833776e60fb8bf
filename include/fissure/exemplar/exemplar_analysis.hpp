#pragma once
/// The whole exemplar pipeline in one call: traced image → crack mask → crack graph → statistics.

#include "fissure/exemplar/crack_graph.hpp"
#include "fissure/exemplar/crack_image.hpp"
#include "fissure/exemplar/pattern_stats.hpp"

#include <cstdint>
#include <filesystem>
#include <vector>

namespace fissure {

struct ExemplarAnalysisOptions {
  CrackImageOptions image;
  CrackGraphOptions graph;
  PatternStatsOptions stats;
  /// Keep the skeleton and the per-pixel fragment labels (for overlays): 5 bytes a pixel.
  bool keep_pixel_layers = false;

  /// The problems of the three option sets, each prefixed by its set's name.
  std::vector<std::string> problems() const;
  /// Throws InvalidInput "exemplar analysis options: <problems>" before any work.
  void validate() const;
};

struct ExemplarAnalysis {
  CrackMask mask;
  PlanarCrackGraph graph;
  PatternStats stats;
  CrackGraphDiagnostics diagnostics;
  std::vector<std::uint8_t> skeleton;          ///< when keep_pixel_layers
  std::vector<std::int32_t> fragment_labels;  ///< per pixel: fragment index or −1, when keep_pixel_layers
};

/// Analyses a tracing file (errors as load_crack_mask; invalid options are refused first). For a pixel-unit graph the junction probe
/// floor is the reference's 8 px.
ExemplarAnalysis analyze_exemplar(const std::filesystem::path& path, const ExemplarAnalysisOptions& options = {});

/// Same from a mask already in memory.
ExemplarAnalysis analyze_crack_mask(CrackMask mask, const ExemplarAnalysisOptions& options = {});

}  // namespace fissure
