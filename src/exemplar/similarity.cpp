#include "fissure/exemplar/similarity.hpp"

#include "fissure/base/error.hpp"
#include "fissure/base/number_text.hpp"

#include <cmath>

namespace fissure {

std::vector<std::string> SimilarityWeights::problems() const {
  std::vector<std::string> out;
  for (const auto& [name, value] : {std::pair{"fragment weight", fragment}, std::pair{"crack weight", crack},
                                    std::pair{"junction weight", junction}}) {
    if (!std::isfinite(value) || value < 0.0) out.push_back(std::string(name) + " " + format_number(value) + " is negative or not finite");
  }
  if (out.empty() && fragment + crack + junction <= 0.0) out.push_back("all similarity weights are zero");
  return out;
}

Similarity pattern_similarity(const PatternStats& a, const PatternStats& b, const SimilarityWeights& weights) {
  const auto list = weights.problems();
  if (!list.empty()) throw InvalidInput(list.front());
  Similarity s;
  s.fragment = earth_movers_distance(a.fragment_area_hist, b.fragment_area_hist, "fragment area histogram");
  s.crack = earth_movers_distance(a.crack_length_hist, b.crack_length_hist, "crack length histogram");
  s.junction = earth_movers_distance(a.junction_density_hist, b.junction_density_hist, "junction density histogram");
  s.total = weights.fragment * s.fragment + weights.crack * s.crack + weights.junction * s.junction;
  return s;
}

}  // namespace fissure
