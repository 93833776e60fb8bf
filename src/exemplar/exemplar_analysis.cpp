#include "fissure/exemplar/exemplar_analysis.hpp"

#include "fissure/base/error.hpp"
#include "fissure/base/number_text.hpp"

#include <string>

namespace fissure {

std::vector<std::string> ExemplarAnalysisOptions::problems() const {
  std::vector<std::string> out;
  for (const std::string& p : image.problems()) out.push_back("image: " + p);
  for (const std::string& p : graph.problems()) out.push_back("graph: " + p);
  for (const std::string& p : stats.problems()) out.push_back("stats: " + p);
  return out;
}

void ExemplarAnalysisOptions::validate() const { throw_if_problems("exemplar analysis options", problems()); }

ExemplarAnalysis analyze_crack_mask(CrackMask mask, const ExemplarAnalysisOptions& options) {
  options.validate();
  ExemplarAnalysis a;
  a.mask = std::move(mask);
  a.graph = extract_crack_graph(a.mask, options.graph, &a.diagnostics, options.keep_pixel_layers ? &a.skeleton : nullptr,
                                options.keep_pixel_layers ? &a.fragment_labels : nullptr);
  if (a.graph.cracks.empty()) {
    throw InvalidInput(a.mask.source + ": no crack found (only specks below the spur length of " +
                       format_number(a.diagnostics.spur_length_px, 3) + " px)");
  }
  a.stats = compute_pattern_stats(a.graph, options.stats);
  return a;
}

ExemplarAnalysis analyze_exemplar(const std::filesystem::path& path, const ExemplarAnalysisOptions& options) {
  options.validate();
  return analyze_crack_mask(load_crack_mask(path, options.image), options);
}

}  // namespace fissure
