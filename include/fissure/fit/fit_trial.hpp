#pragma once
/// One trial of a fit (paper §6.2, Fig. 6): parameters p, a resistance field, a load position and
/// crack noise drawn from the trial's own stream, the simulation on the fit body, the visible
/// pattern's statistics and Eq. 5 against the exemplar's.
///
/// Early rejection. A method that only keeps trials under a threshold (the best-of-N's current
/// population, an ABC generation's ε) need not finish a trial that can no longer get under it.
/// The bound used is exact: the visible fragments only split as cracks are added, their
/// normalised areas sum to 1, so with N fragments the mean bin of log10(area) is at most
/// h(1/N) (h concave, Jensen), and EMD ≥ |difference of mean bins| / bins (the 1-D EMD is at
/// least the difference of the means). So w_frag·(mean bin of the exemplar − h(1/N))/bins bounds
/// the final Eq. 5 error from below; once it exceeds the threshold the trial stops. A rejected
/// trial has error +∞: it was worse than the threshold, which is all its method needs.
#include "fissure/exemplar/similarity.hpp"
#include "fissure/fit/fit_body.hpp"
#include "fissure/fit/fit_prior.hpp"
#include "fissure/fracture/crack_surface.hpp"
#include "fissure/fracture/visible_pattern.hpp"

#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

namespace fissure {

/// What every trial of one fit shares. Immutable once made: trials run on it from any thread.
struct FitProblem {
  PatternStats exemplar;
  FractureParams base;  ///< the base material with the fit's age; the five fitted values are the trial's
  PriorBox box;
  std::shared_ptr<const FitBody> body;
  SimilarityWeights weights;
  VisiblePatternOptions visible;
  double exemplar_mean_bin = 0.0;  ///< the exemplar's mean fragment-area bin (for the bound)
};

/// Builds the problem: the box from `base` and the exemplar's fragment scale on `body`.
FitProblem make_fit_problem(const PatternStats& exemplar, const FractureParams& base,
                            std::shared_ptr<const FitBody> body, const SimilarityWeights& weights = {});

/// The draws of one trial from its stream (seed, "fit-trial", index).
struct TrialDraws {
  int load_position = 0;
  std::uint64_t resistance_seed = 0;
  std::uint64_t noise_seed = 0;
};
TrialDraws draw_trial(const FitProblem& problem, std::uint64_t seed, std::uint64_t index);

struct TrialOutcome {
  double error = std::numeric_limits<double>::infinity();  ///< Eq. 5; +∞ when rejected
  Similarity terms;
  int fragments = 0;  ///< visible fragments (at the stop when rejected)
  int cracks = 0;
  bool rejected = false;
};

/// The lower bound above on the Eq. 5 error of any pattern with at least `fragments` visible
/// fragments (0 when it says nothing).
double fragment_error_lower_bound(const FitProblem& problem, int fragments);

/// Runs trial `index` of a fit seeded `seed` at unit point `u`. `reject_above` (+∞: never) turns on
/// early rejection. When `stats` / `cracks` are given (and the trial is not rejected) they receive
/// the pattern's statistics and the cracks (for drawing the fitted pattern).
TrialOutcome run_trial(const FitProblem& problem, const UnitPoint& u, std::uint64_t seed, std::uint64_t index,
                       double reject_above = std::numeric_limits<double>::infinity(), PatternStats* stats = nullptr,
                       std::vector<CrackSurface>* cracks = nullptr);

}  // namespace fissure
