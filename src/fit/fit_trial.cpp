#include "fissure/fit/fit_trial.hpp"

#include "fissure/base/error.hpp"
#include "fissure/base/rng.hpp"
#include "fissure/fracture/fracture_scenario.hpp"
#include "fissure/fracture/resistance_field.hpp"
#include "fissure/fracture/simulation.hpp"

#include <cmath>

namespace fissure {

namespace {

// The bin position h(a) = bins·(log10(a + 10^lo) − lo)/(hi − lo) of a normalised area: concave in
// a and at least the bin index an area a is counted in (its floor, clamped to [0, bins − 1]).
double bin_bound(const Histogram& hist, double area) {
  const double lo = hist.edges.front(), hi = hist.edges.back();
  const double bins = static_cast<double>(hist.p.size());
  return bins * (std::log10(area + std::pow(10.0, lo)) - lo) / (hi - lo);
}

double mean_bin(const Histogram& hist) {
  const double total = hist.total();
  if (!(total > 0.0)) return 0.0;
  double sum = 0.0;
  for (std::size_t i = 0; i < hist.p.size(); ++i) sum += static_cast<double>(i) * hist.p[i];
  return sum / total;
}

}  // namespace

FitProblem make_fit_problem(const PatternStats& exemplar, const FractureParams& base,
                            std::shared_ptr<const FitBody> body, const SimilarityWeights& weights) {
  if (!body) throw InvalidInput("fit: no body");
  const auto weight_problems = weights.problems();
  if (!weight_problems.empty()) throw InvalidInput("fit: " + weight_problems.front());
  base.validate();
  FitProblem problem;
  problem.exemplar = exemplar;
  problem.base = base;
  problem.box = make_prior_box(base, exemplar_fragment_scale(exemplar, body->visible_area()));
  problem.body = std::move(body);
  problem.weights = weights;
  problem.exemplar_mean_bin = mean_bin(exemplar.fragment_area_hist);
  return problem;
}

TrialDraws draw_trial(const FitProblem& problem, std::uint64_t seed, std::uint64_t index) {
  Rng rng = Rng::derive(seed, "fit-trial", index);
  TrialDraws d;
  d.load_position = static_cast<int>(rng.uniform_index(static_cast<std::uint64_t>(problem.body->load_positions())));
  d.resistance_seed = rng.next_u64();
  d.noise_seed = rng.next_u64();
  return d;
}

double fragment_error_lower_bound(const FitProblem& problem, int fragments) {
  if (fragments < 1) return 0.0;
  const Histogram& hist = problem.exemplar.fragment_area_hist;
  // Areas sum to the visible area up to round-off: 1.001/N covers it.
  const double gap = problem.exemplar_mean_bin - bin_bound(hist, 1.001 / fragments);
  return gap > 0.0 ? problem.weights.fragment * gap / static_cast<double>(hist.p.size()) : 0.0;
}

TrialOutcome run_trial(const FitProblem& problem, const UnitPoint& u, std::uint64_t seed, std::uint64_t index,
                       double reject_above, PatternStats* stats_out, std::vector<CrackSurface>* cracks_out) {
  const FitBody& body = *problem.body;
  const PreparedBody& prepared = body.prepared();
  const TrialDraws draws = draw_trial(problem, seed, index);
  const FractureParams p = problem.box.params_at(problem.base, u);
  StressField initial;
  body.initial_stress(draws.load_position, p.load_factor * prepared.fracture_body().mass(p.density) * kStandardGravity,
                      initial);
  const Eigen::VectorXd resistance = draw_resistance(prepared.mesh().centroids(), p, draws.resistance_seed);

  TrialOutcome outcome;
  SimulationOptions options;
  options.label_fragments = false;
  const Eigen::Vector3d up = prepared.scenario().up;
  if (std::isfinite(reject_above)) {
    // The fewest visible fragments whose bound exceeds the threshold; checks start at half as
    // many cracks and go on every 1.5×, so a rejected trial runs at most ~1.5× past the point
    // where it could have stopped, and the ~1 ms pattern extraction is paid a few times.
    int first = -1;
    for (int n = 2; n < (1 << 22); n = n + std::max(1, n / 8)) {
      if (fragment_error_lower_bound(problem, n) > reject_above) {
        first = n;
        break;
      }
    }
    if (first > 0) {
      options.stop_check_at = std::max(8, first / 2);
      options.stop_check = [&](const std::vector<CrackSurface>& cracks) {
        const VisiblePattern v =
            extract_visible_pattern(prepared.mesh(), cracks, static_cast<int>(cracks.size()), up, problem.visible);
        const int fragments = static_cast<int>(v.graph.fragments.size());
        if (fragment_error_lower_bound(problem, fragments) > reject_above) {
          outcome.fragments = fragments;
          return 0;
        }
        return static_cast<int>(cracks.size()) * 3 / 2 + 1;
      };
    }
  }
  FractureResult result = simulate_fracture(prepared.fracture_body(), p, initial, resistance, draws.noise_seed, options);
  outcome.cracks = static_cast<int>(result.cracks.size());
  if (result.stopped_early) {
    outcome.rejected = true;
    return outcome;
  }
  const VisiblePattern visible =
      extract_visible_pattern(prepared.mesh(), result.cracks, outcome.cracks, up, problem.visible);
  if (!visible.has_visible_face) throw InvalidInput("fit: the fit body has no visible face: " + visible.empty_reason);
  PatternStats stats = compute_pattern_stats(visible.graph, visible.stats_options);
  outcome.terms = pattern_similarity(problem.exemplar, stats, problem.weights);
  outcome.error = outcome.terms.total;
  outcome.fragments = stats.fragment_count;
  if (stats_out) *stats_out = std::move(stats);
  if (cracks_out) *cracks_out = std::move(result.cracks);
  return outcome;
}

}  // namespace fissure
