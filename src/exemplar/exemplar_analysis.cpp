#include "fissure/exemplar/exemplar_analysis.hpp"

#include "fissure/base/error.hpp"

#include <string>

namespace fissure {

ExemplarAnalysis analyze_crack_mask(CrackMask mask, const ExemplarAnalysisOptions& options) {
  ExemplarAnalysis a;
  a.mask = std::move(mask);
  a.graph = extract_crack_graph(a.mask, options.graph, &a.diagnostics, options.keep_pixel_layers ? &a.skeleton : nullptr,
                                options.keep_pixel_layers ? &a.fragment_labels : nullptr);
  if (a.graph.cracks.empty()) {
    throw InvalidInput(a.mask.source + ": no crack found (only specks below the spur length of " +
                       std::to_string(static_cast<int>(a.diagnostics.spur_length_px)) + " px)");
  }
  a.stats = compute_pattern_stats(a.graph, options.stats);
  return a;
}

ExemplarAnalysis analyze_exemplar(const std::filesystem::path& path, const ExemplarAnalysisOptions& options) {
  return analyze_crack_mask(load_crack_mask(path, options.image), options);
}

}  // namespace fissure
