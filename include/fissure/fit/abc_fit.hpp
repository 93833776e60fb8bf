#pragma once
/// Fitting the five parameters to an exemplar by Approximate Bayesian Computation (paper §6.2).
///
/// - FitMethod::Paper, exactly as published: N uniform draws from the prior, one trial each, the
///   lowest Eq. 5 error wins. Beyond the paper it also keeps the best P trials (the accepted
///   population, the posterior's samples).
/// - FitMethod::Smc, ABC population Monte Carlo (Beaumont et al. 2009; paper-gaps §8): generation
///   0 is a quarter of the budget drawn from the prior, its best P the first population, each
///   re-scored as the mean over `smc_seeds` trials; each next generation's threshold ε is the
///   median score of the last population, and candidates come from a particle (picked by weight)
///   plus a Gaussian step of twice the population's weighted covariance, each scored by the mean
///   error over `smc_seeds` trials with their own draws, so a lucky seed does not win; the first
///   P candidates under ε (in proposal order) make the next population, weighted
///   1 / Σ_j w_j N(θ; θ_j, Σ). The generations end when their budget (all but `smc_race_share`)
///   is spent or one accepts fewer than `smc_min_acceptance` of its candidates; the rest of the
///   budget races the best 16 particles by successive halving, and the race's winner is chosen.
///
/// Both are deterministic: every trial draws from its own stream (seed, key), trials run in
/// blocks of a fixed size whose order never depends on the thread count, and every threshold used
/// for early rejection (fit_trial.hpp) comes from finished blocks. The paper method's top P does
/// not depend on the thresholds at all (a rejected trial is worse than P others), which is why
/// shards of it merge to the unsharded result. Finally the winner is re-simulated on
/// `evaluation_seeds` fresh streams: the error a user will see.
#include "fissure/base/progress.hpp"
#include "fissure/fit/fit_trial.hpp"

#include <cstdint>
#include <functional>
#include <optional>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace fissure {

enum class FitMethod { Paper, Smc };
const char* to_string(FitMethod method);
std::optional<FitMethod> parse_fit_method(std::string_view text);

/// A finished trial as a checkpoint keeps it: enough to replay a fit without re-running it.
struct TrialRecord {
  std::uint64_t key = 0;  ///< the trial's stream index
  double error = 0.0;     ///< +∞ when rejected
  int fragments = 0;
};
using TrialRecords = std::unordered_map<std::uint64_t, TrialRecord>;

struct FitProgress {
  long long trials_done = 0;  ///< trials finished (resumed ones included)
  long long trials_total = 0;
  double best_error = 0.0;    ///< +∞ before the first finished trial
  double trials_per_second = 0.0;  ///< of the trials run by this process
  double eta_seconds = 0.0;
  int generation = 0;
};

struct FitShard {
  int index = 1;  ///< K, from 1
  int count = 1;  ///< N
};

struct FitOptions {
  FitMethod method = FitMethod::Smc;
  long long trials = 20000;       ///< the budget, every seed repeat counted
  std::uint64_t seed = 1;
  int threads = 1;
  int population = 0;             ///< P; 0: trials/100 within [20, 200]
  int block = 64;                 ///< trials per block (fixed: results must not depend on threads)
  int evaluation_seeds = 8;       ///< re-simulations of the winner for the reported error
  int smc_seeds = 2;              ///< trials per candidate from generation 1
  double smc_quantile = 0.5;      ///< ε_t = this quantile of the last population's errors
  double smc_min_acceptance = 0.02;
  double smc_race_share = 0.1;    ///< of the budget kept for the final race of the best particles
  FitShard shard;                 ///< Paper only: run blocks b with b mod N = K − 1
  const TrialRecords* resume = nullptr;  ///< finished trials of an earlier run (same settings)
  /// Called after every block with its finished trials (the checkpoint's hook), also with the
  /// finished part of a block a cancel interrupted.
  std::function<void(const std::vector<TrialRecord>&)> on_trials;
  std::function<void(const FitProgress&)> on_progress;
  const CancelToken* cancel = nullptr;

  /// Readable problems naming the option ("--trials 0 is below 1"); empty when valid.
  std::vector<std::string> problems() const;
  int population_size() const;
};

struct Particle {
  UnitPoint u{};
  double error = 0.0;   ///< the method's score: one trial (Paper, SMC generation 0) or a seed mean
  double weight = 1.0;  ///< normalised over the population
  std::uint64_t key = 0;
  int samples = 1;      ///< trials in the error's mean
};

struct FitResult {
  FitMethod method = FitMethod::Smc;
  long long trials = 0;           ///< trials run, resumed ones included
  long long rejected = 0;         ///< of which stopped early
  int generations = 0;
  std::vector<Particle> population;  ///< the chosen particle first, the rest by error, then key
  Particle best;
  FractureParams params;             ///< best's parameters (the base's other values)
  /// best re-simulated as trials 0, 1, … of the fresh stream fit_evaluation_seed(seed)
  std::vector<double> evaluation_errors;
  double error_mean = 0.0, error_stddev = 0.0;
  UnitPoint posterior_mean{}, posterior_stddev{};  ///< weighted, unit-cube coordinates
};

/// The seed of the evaluation's trials: run_trial(problem, best.u, fit_evaluation_seed(seed), i)
/// is evaluation i (a seed of its own, derived from the fit's, so no trial of the fit is reused).
std::uint64_t fit_evaluation_seed(std::uint64_t seed);

/// Runs the fit. A shard (Paper only) returns its population without the evaluation
/// (evaluation_errors empty): merge shards with merge_fit_shards. Throws InvalidInput for bad
/// options (SMC with a shard: "--shard needs --method paper: ..."), Cancelled when cancelled.
FitResult run_fit(const FitProblem& problem, const FitOptions& options);

/// Joins the populations of every shard of a Paper fit (the same problem and options but the
/// shard) into exactly the unsharded result: the top P of the union, then the evaluation.
FitResult merge_fit_shards(const FitProblem& problem, const std::vector<FitResult>& shards, const FitOptions& options);

}  // namespace fissure
