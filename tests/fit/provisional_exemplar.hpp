#pragma once
// The exemplar statistics a fit test or benchmark starts from before it has a pattern: only the
// fragment scale matters (it sets r_relax's prior range, fit_prior.hpp), so `fragments` equal
// fragments on the histograms' bins (those of compute_pattern_stats) make a valid PatternStats.
// The self-recovery setting then simulates a pattern in that box and fits it.
#include "fissure/exemplar/pattern_stats.hpp"

#include <vector>

namespace fissure::test {

inline PatternStats provisional_exemplar(int fragments) {
  PatternStats s;
  s.source = "provisional";
  s.fragment_areas = std::vector<double>(static_cast<std::size_t>(fragments), 1.0 / fragments);
  s.fragment_area_hist = Histogram::make(-6.0, 0.0, 24);
  s.crack_length_hist = Histogram::make(-4.0, 0.0, 16);
  s.junction_density_hist = Histogram::make(0.0, 5.0, 20);
  return s;
}

}  // namespace fissure::test
