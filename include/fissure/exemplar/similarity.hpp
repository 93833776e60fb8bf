#pragma once
/// The perceptual distance between two crack patterns (paper Eq. 5):
///   err = w_frag·EMD(fragment areas) + w_crack·EMD(crack lengths) + w_junc·EMD(junction density)
/// with the user study's weights 3, 1, 1 (paper §4, §6.2). Each EMD is dimensionless in [0, 1).

#include "fissure/exemplar/pattern_stats.hpp"

#include <string>
#include <vector>

namespace fissure {

struct SimilarityWeights {
  double fragment = 3.0;
  double crack = 1.0;
  double junction = 1.0;
  /// Readable problems (negative or non-finite weights, all zero), empty when valid.
  std::vector<std::string> problems() const;
};

struct Similarity {
  double total = 0.0;
  double fragment = 0.0;  ///< the EMD terms, unweighted
  double crack = 0.0;
  double junction = 0.0;
};

/// Eq. 5 between two patterns. Throws InvalidInput for bad weights or histograms on different
/// bins. Symmetric; zero for identical statistics.
Similarity pattern_similarity(const PatternStats& a, const PatternStats& b, const SimilarityWeights& weights = {});

}  // namespace fissure
