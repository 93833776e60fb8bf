// Self-recovery (issue 12): simulate with known parameters p*, take that pattern's statistics as
// the exemplar, fit it, and compare. On the small fit body (4K tets), 2,000 trials: seconds.

#include "fissure/fit/abc_fit.hpp"

#include "provisional_exemplar.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

namespace fissure {
namespace {

// The weighted q-quantile of one coordinate of the population.
double weighted_quantile(const std::vector<Particle>& pop, std::size_t k, double q) {
  std::vector<std::pair<double, double>> v;
  for (const Particle& p : pop) v.emplace_back(p.u[k], p.weight);
  std::sort(v.begin(), v.end());
  double total = 0.0;
  for (const auto& [x, w] : v) total += w;
  double c = 0.0;
  for (const auto& [x, w] : v) {
    c += w;
    if (c >= q * total) return x;
  }
  return v.back().first;
}

TEST(FitRecovery, KnownParametersAreRecoveredWithinTheSeedSpread) {
  FitBodyOptions o;
  o.tile = TileSpec{0.5, 0.5, 0.02};
  o.tets = 4000;
  o.load_grid = 4;
  FractureParams base;
  base.age = 3.0;
  auto body = std::make_shared<const FitBody>(plan_fit_body(10, 1.0, o), o, base.elastic(), 2);
  // The box needs an exemplar's fragment scale: a provisional one (0.1 m) fixes it, and the known
  // pattern is then fitted in that same box.
  const FitProblem bootstrap = make_fit_problem(test::provisional_exemplar(25), base, body);
  const UnitPoint known = {0.8, 0.3, 0.3, 0.3, 0.5};  // a dense pattern: p*'s own seed spread is ±0.06
  PatternStats exemplar;
  run_trial(bootstrap, known, 11, 0, std::numeric_limits<double>::infinity(), &exemplar);
  FitProblem problem = make_fit_problem(exemplar, base, body);
  problem.box = bootstrap.box;
  ASSERT_GT(exemplar.fragment_count, 5);

  // The spread of p* itself: its error to its own pattern when re-run on other streams.
  std::vector<double> own;
  for (std::uint64_t i = 0; i < 16; ++i) own.push_back(run_trial(problem, known, 12345, i).error);
  const double own_mean = std::accumulate(own.begin(), own.end(), 0.0) / own.size();
  double ss = 0.0;
  for (double e : own) ss += (e - own_mean) * (e - own_mean);
  const double own_sd = std::sqrt(ss / (own.size() - 1));

  FitOptions options;
  options.method = FitMethod::Smc;
  options.trials = 2000;
  options.seed = 3;
  options.threads = 2;
  options.evaluation_seeds = 16;
  const FitResult fit = run_fit(problem, options);
  std::printf("p* on fresh seeds: %.4f +- %.4f; fitted: %.4f +- %.4f (%d generations)\n", own_mean, own_sd,
              fit.error_mean, fit.error_stddev, fit.generations);
  // Within the spread of p* itself: the fitted parameters are as good as the true ones, up to the
  // seed noise (mean + 2 standard deviations of p*'s own re-runs).
  EXPECT_LE(fit.error_mean, own_mean + 2.0 * own_sd);
  // p* against the posterior's 90 % interval, per parameter. Measured (seed 3): dσ_e and r_relax
  // are identified (intervals under half the box: [0.60, 0.94] and [0.04, 0.39]); v_relax, R_cvar
  // and l are not (intervals over 60 % of it): the three statistics barely see them on this body.
  // p* must lie in the identified ones' intervals; the others are reported.
  int inside = 0;
  for (std::size_t k = 0; k < kFitDimensions; ++k) {
    const double lo = weighted_quantile(fit.population, k, 0.05), hi = weighted_quantile(fit.population, k, 0.95);
    const bool in = known[k] >= lo && known[k] <= hi;
    inside += in ? 1 : 0;
    std::printf("  %-18s p* %.2f  90 %% interval [%.2f, %.2f]%s\n", table3_priors()[k].name, known[k], lo, hi,
                in ? "" : "  (p* outside)");
    RecordProperty(std::string(table3_priors()[k].name) + "_inside", in ? 1 : 0);
    if (k == 0 || k == 1) {
      EXPECT_TRUE(in) << table3_priors()[k].name;
      EXPECT_LT(hi - lo, 0.5) << table3_priors()[k].name << " is no longer identified";
    }
  }
  RecordProperty("inside", inside);
}

}  // namespace
}  // namespace fissure
