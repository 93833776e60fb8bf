#include "fissure/fit/abc_fit.hpp"

#include "fissure/base/error.hpp"
#include "fissure/base/number_text.hpp"
#include "fissure/base/parallel.hpp"
#include "fissure/base/rng.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>

namespace fissure {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// SMC keys: generation in the high bits, candidate·seeds + repeat below.
constexpr int kGenerationShift = 40;

std::uint64_t smc_key(int generation, std::uint64_t trial) {
  return (static_cast<std::uint64_t>(generation) << kGenerationShift) | trial;
}

bool by_error(const Particle& a, const Particle& b) { return a.error < b.error || (a.error == b.error && a.key < b.key); }

// One unit of work in a block: a trial at u, rejected early above `threshold`.
struct Job {
  std::uint64_t key;
  UnitPoint u;
  double threshold;
};

class Runner {
public:
  Runner(const FitProblem& problem, const FitOptions& options) : m_problem(problem), m_options(options) {
    m_start = std::chrono::steady_clock::now();
  }

  // Runs the jobs (taking finished ones from options.resume), in parallel, and reports them.
  std::vector<TrialRecord> run(const std::vector<Job>& jobs, int generation) {
    std::vector<TrialRecord> out(jobs.size());
    std::vector<char> done(jobs.size(), 0);
    std::vector<char> fresh(jobs.size(), 0);
    try {
      parallel_for_dynamic(jobs.size(), m_options.threads, [&](std::size_t i) {
        const Job& job = jobs[i];
        if (m_options.resume) {
          const auto it = m_options.resume->find(job.key);
          if (it != m_options.resume->end()) {
            out[i] = it->second;
            done[i] = 1;
            return;
          }
        }
        if (m_options.cancel) m_options.cancel->throw_if_cancelled();
        const TrialOutcome t = run_trial(m_problem, job.u, m_options.seed, job.key, job.threshold);
        out[i] = {job.key, t.error, t.fragments};
        done[i] = fresh[i] = 1;
      });
    } catch (const Cancelled&) {
      std::vector<TrialRecord> finished;
      for (std::size_t i = 0; i < jobs.size(); ++i)
        if (fresh[i]) finished.push_back(out[i]);
      if (m_options.on_trials && !finished.empty()) m_options.on_trials(finished);
      throw;
    }
    std::vector<TrialRecord> finished;
    for (std::size_t i = 0; i < jobs.size(); ++i) {
      if (fresh[i]) {
        finished.push_back(out[i]);
        ++m_run_here;
      }
      ++m_trials;
      if (!std::isfinite(out[i].error)) ++m_rejected;
      m_best = std::min(m_best, out[i].error);
    }
    if (m_options.on_trials && !finished.empty()) m_options.on_trials(finished);
    report(generation);
    return out;
  }

  long long trials() const { return m_trials; }
  long long rejected() const { return m_rejected; }

private:
  void report(int generation) {
    if (!m_options.on_progress) return;
    FitProgress p;
    p.trials_done = m_trials;
    p.trials_total = m_options.trials;
    if (m_options.shard.count > 1) p.trials_total = (m_options.trials + m_options.shard.count - 1) / m_options.shard.count;
    p.best_error = m_best;
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
    p.trials_per_second = seconds > 0.0 ? static_cast<double>(m_run_here) / seconds : 0.0;
    p.eta_seconds = p.trials_per_second > 0.0 ? static_cast<double>(std::max(0LL, p.trials_total - m_trials)) / p.trials_per_second : 0.0;
    p.generation = generation;
    m_options.on_progress(p);
  }

  const FitProblem& m_problem;
  const FitOptions& m_options;
  std::chrono::steady_clock::time_point m_start;
  long long m_trials = 0, m_rejected = 0, m_run_here = 0;
  double m_best = kInf;
};

UnitPoint prior_draw(std::uint64_t seed, std::uint64_t index) {
  Rng rng = Rng::derive(seed, "fit-prior", index);
  UnitPoint u{};
  for (double& x : u) x = rng.uniform();
  return u;
}

// The P-th smallest error of `kept` (+∞ while fewer than P): the early-rejection threshold of a
// method that keeps the best P.
double pth_error(std::vector<double>& errors, std::size_t p) {
  if (errors.size() < p) return kInf;
  std::nth_element(errors.begin(), errors.begin() + static_cast<std::ptrdiff_t>(p - 1), errors.end());
  return errors[p - 1];
}

// Prior draws for trial indices in `blocks` (block b holds [b·B, min((b+1)·B, n))), keeping the
// best P. Thresholds from the blocks run before.
std::vector<Particle> best_of_prior(Runner& runner, const FitOptions& o, long long n, std::size_t p,
                                    const std::function<bool(long long)>& run_block, int generation) {
  std::vector<Particle> kept;
  std::vector<double> errors;
  const long long blocks = (n + o.block - 1) / o.block;
  for (long long b = 0; b < blocks; ++b) {
    if (!run_block(b)) continue;
    const double threshold = pth_error(errors, p);
    std::vector<Job> jobs;
    for (long long i = b * o.block; i < std::min(n, (b + 1) * o.block); ++i) {
      // Prior draws are trials 0, 1, … in both methods (SMC's generation 0: smc_key(0, i) = i).
      const std::uint64_t key = static_cast<std::uint64_t>(i);
      jobs.push_back({key, prior_draw(o.seed, static_cast<std::uint64_t>(i)), threshold});
    }
    const std::vector<TrialRecord> out = runner.run(jobs, generation);
    for (std::size_t i = 0; i < jobs.size(); ++i) {
      if (!std::isfinite(out[i].error)) continue;
      kept.push_back({jobs[i].u, out[i].error, 1.0, jobs[i].key});
      errors.push_back(out[i].error);
    }
    // Keep the list short: only the best P can matter.
    if (kept.size() > 4 * p) {
      std::sort(kept.begin(), kept.end(), by_error);
      kept.resize(p);
      errors.clear();
      for (const Particle& k : kept) errors.push_back(k.error);
    }
  }
  std::sort(kept.begin(), kept.end(), by_error);
  if (kept.size() > p) kept.resize(p);
  for (Particle& k : kept) k.weight = 1.0 / static_cast<double>(kept.size());
  return kept;
}

Eigen::Matrix<double, 5, 1> vec(const UnitPoint& u) { return Eigen::Map<const Eigen::Matrix<double, 5, 1>>(u.data()); }

void weighted_moments(const std::vector<Particle>& pop, Eigen::Matrix<double, 5, 1>& mean, Eigen::Matrix<double, 5, 5>& cov) {
  mean.setZero();
  cov.setZero();
  double wsum = 0.0;
  for (const Particle& q : pop) {
    mean += q.weight * vec(q.u);
    wsum += q.weight;
  }
  if (wsum > 0.0) mean /= wsum;
  for (const Particle& q : pop) {
    const Eigen::Matrix<double, 5, 1> d = vec(q.u) - mean;
    cov += q.weight * d * d.transpose();
  }
  if (wsum > 0.0) cov /= wsum;
}

// Keys of extra repeats of population particles (generation 0's re-scoring and the final race):
// the last stage number, numbered in the order they are issued.
constexpr std::uint64_t kRepeatStage = (std::uint64_t{1} << (64 - kGenerationShift)) - 1;

// Adds `repeats[i]` more trials to pop[i] (with their own streams) and makes its error the mean
// over all of them.
void add_repeats(Runner& runner, std::vector<Particle>& pop, const std::vector<int>& repeats,
                 std::uint64_t& next_repeat, int block, int generation) {
  std::vector<Job> jobs;
  std::vector<std::size_t> owner;
  for (std::size_t i = 0; i < pop.size(); ++i) {
    for (int r = 0; r < repeats[i]; ++r) {
      jobs.push_back({smc_key(static_cast<int>(kRepeatStage), next_repeat++), pop[i].u, kInf});
      owner.push_back(i);
    }
  }
  for (std::size_t b = 0; b < jobs.size(); b += static_cast<std::size_t>(block)) {
    const std::vector<Job> slice(jobs.begin() + static_cast<std::ptrdiff_t>(b),
                                 jobs.begin() + static_cast<std::ptrdiff_t>(std::min(jobs.size(), b + static_cast<std::size_t>(block))));
    const std::vector<TrialRecord> out = runner.run(slice, generation);
    for (std::size_t k = 0; k < slice.size(); ++k) {
      const std::size_t i = owner[b + k];
      pop[i].error = (pop[i].error * pop[i].samples + out[k].error) / (pop[i].samples + 1);
      ++pop[i].samples;
    }
  }
}

// The final race (successive halving): the best K particles share what is left of the budget in
// rounds; each round gives every one still in the race the same number of further trials, and the
// better half by mean goes on. The winner leads the population. Picking the lowest of P two-seed
// means favours a lucky particle; the race spends the last trials where the choice is made.
void race(Runner& runner, const FitOptions& o, std::vector<Particle>& pop, std::uint64_t& next_repeat, int generation) {
  const auto rounds_for = [](std::size_t k) {
    int rounds = 0;
    for (; k > 1; k = (k + 1) / 2) ++rounds;
    return rounds;
  };
  // As many racers as the budget gives each at least one trial per round (16 at most).
  std::size_t k = std::min<std::size_t>(pop.size(), 16);
  while (k > 1 && (o.trials - runner.trials()) / rounds_for(k) / static_cast<long long>(k) < 1) k = (k + 1) / 2;
  std::vector<std::size_t> in_race(k);
  std::iota(in_race.begin(), in_race.end(), std::size_t{0});
  for (int rounds = rounds_for(k); rounds > 0 && in_race.size() > 1; --rounds) {
    const long long each = (o.trials - runner.trials()) / rounds / static_cast<long long>(in_race.size());
    if (each < 1) break;
    std::vector<Particle> racers;
    for (std::size_t i : in_race) racers.push_back(pop[i]);
    add_repeats(runner, racers, std::vector<int>(racers.size(), static_cast<int>(each)), next_repeat, o.block, generation);
    for (std::size_t r = 0; r < racers.size(); ++r) pop[in_race[r]] = racers[r];
    std::stable_sort(in_race.begin(), in_race.end(), [&](std::size_t a, std::size_t b) { return by_error(pop[a], pop[b]); });
    in_race.resize((in_race.size() + 1) / 2);
  }
  const std::uint64_t winner = in_race.empty() ? 0 : pop[in_race.front()].key;
  std::sort(pop.begin(), pop.end(), by_error);
  if (in_race.empty()) return;
  const auto it = std::find_if(pop.begin(), pop.end(), [&](const Particle& q) { return q.key == winner; });
  std::rotate(pop.begin(), it, it + 1);
}

std::vector<Particle> smc(Runner& runner, const FitOptions& o, int& generations) {
  const std::size_t p = static_cast<std::size_t>(o.population_size());
  const int seeds = std::max(1, o.smc_seeds);
  // The final race's share is kept back from the generations.
  const long long race_budget = static_cast<long long>(std::floor(o.smc_race_share * static_cast<double>(o.trials)));
  const long long generations_budget = o.trials - race_budget;
  const long long first = std::max<long long>(o.trials / 4, 5 * static_cast<long long>(p));
  std::vector<Particle> pop = best_of_prior(runner, o, std::min(first, generations_budget), p, [](long long) { return true; }, 0);
  generations = 1;
  std::uint64_t next_repeat = 0;
  // Generation 0's errors are single trials, the minima of many: a lucky seed sits on top. Its
  // population is re-scored on `seeds` trials each, so ε and every later comparison are seed
  // means on the same footing (without it, ε is too low for any candidate's mean and the
  // generations stop at once).
  if (seeds > 1 && runner.trials() + static_cast<long long>(pop.size()) * (seeds - 1) <= generations_budget) {
    add_repeats(runner, pop, std::vector<int>(pop.size(), seeds - 1), next_repeat, o.block, 0);
    std::sort(pop.begin(), pop.end(), by_error);
  }
  for (int g = 1; runner.trials() < generations_budget && pop.size() >= 2; ++g) {
    std::vector<double> errors;
    for (const Particle& q : pop) errors.push_back(q.error);
    std::sort(errors.begin(), errors.end());
    const double epsilon = errors[static_cast<std::size_t>(std::floor(o.smc_quantile * static_cast<double>(errors.size() - 1)))];
    Eigen::Matrix<double, 5, 1> mean;
    Eigen::Matrix<double, 5, 5> cov;
    weighted_moments(pop, mean, cov);
    Eigen::Matrix<double, 5, 5> sigma = 2.0 * cov + 1e-12 * Eigen::Matrix<double, 5, 5>::Identity();
    const Eigen::LLT<Eigen::Matrix<double, 5, 5>> llt(sigma);
    const Eigen::Matrix<double, 5, 5> L = llt.matrixL();
    const Eigen::Matrix<double, 5, 5> inverse = llt.solve(Eigen::Matrix<double, 5, 5>::Identity());
    std::vector<double> cumulative;
    double c = 0.0;
    for (const Particle& q : pop) cumulative.push_back(c += q.weight);

    std::vector<Particle> accepted;
    long long candidates = 0;
    const long long per_block = std::max(1, o.block / seeds);
    while (accepted.size() < p) {
      // One block of candidates, each `seeds` trials; the last block is cut to the budget.
      const long long count = std::min<long long>(per_block, (generations_budget - runner.trials()) / seeds);
      if (count <= 0) break;
      std::vector<UnitPoint> points;
      std::vector<Job> jobs;
      for (long long i = 0; i < count; ++i) {
        const std::uint64_t candidate = static_cast<std::uint64_t>(candidates + i);
        Rng rng = Rng::derive(o.seed, "fit-smc-candidate", smc_key(g, candidate));
        const double pick = rng.uniform() * c;
        const std::size_t j = std::min<std::size_t>(
            static_cast<std::size_t>(std::upper_bound(cumulative.begin(), cumulative.end(), pick) - cumulative.begin()),
            pop.size() - 1);
        UnitPoint u = pop[j].u;
        // A step outside the box has prior density 0: draw again (no simulation is spent on it).
        for (int attempt = 0; attempt < 1000; ++attempt) {
          Eigen::Matrix<double, 5, 1> z;
          for (int k = 0; k < 5; ++k) z(k) = rng.normal();
          const Eigen::Matrix<double, 5, 1> x = vec(pop[j].u) + L * z;
          if ((x.array() >= 0.0).all() && (x.array() <= 1.0).all()) {
            for (int k = 0; k < 5; ++k) u[static_cast<std::size_t>(k)] = x(k);
            break;
          }
        }
        points.push_back(u);
        for (int s = 0; s < seeds; ++s) {
          // The first repeat may stop once it alone exceeds what the mean allows.
          jobs.push_back({smc_key(g, candidate * static_cast<std::uint64_t>(seeds) + static_cast<std::uint64_t>(s)), u,
                          seeds * epsilon});
        }
      }
      const std::vector<TrialRecord> out = runner.run(jobs, g);
      for (long long i = 0; i < count && accepted.size() < p; ++i) {
        double sum = 0.0;
        for (int s = 0; s < seeds; ++s) sum += out[static_cast<std::size_t>(i * seeds + s)].error;
        const double score = sum / seeds;
        if (score <= epsilon) accepted.push_back({points[static_cast<std::size_t>(i)], score, 0.0, smc_key(g, static_cast<std::uint64_t>(candidates + i)), seeds});
      }
      candidates += count;
    }
    if (accepted.size() < p) {
      // The budget ended inside this generation: the best P of both populations, equal weights.
      for (Particle& q : accepted) pop.push_back(q);
      std::sort(pop.begin(), pop.end(), by_error);
      if (pop.size() > p) pop.resize(p);
      for (Particle& q : pop) q.weight = 1.0 / static_cast<double>(pop.size());
      ++generations;
      break;
    }
    // Importance weights: uniform prior over the box, so w_i ∝ 1 / Σ_j w_j N(θ_i; θ_j, Σ).
    for (Particle& q : accepted) {
      double denominator = 0.0;
      for (const Particle& r : pop) {
        const Eigen::Matrix<double, 5, 1> d = vec(q.u) - vec(r.u);
        denominator += r.weight * std::exp(-0.5 * d.dot(inverse * d));
      }
      q.weight = denominator > 0.0 ? 1.0 / denominator : 0.0;
    }
    double total = 0.0;
    for (const Particle& q : accepted) total += q.weight;
    for (Particle& q : accepted) q.weight = total > 0.0 ? q.weight / total : 1.0 / static_cast<double>(accepted.size());
    pop = std::move(accepted);
    std::sort(pop.begin(), pop.end(), by_error);
    ++generations;
    const double acceptance = static_cast<double>(p) / static_cast<double>(candidates);
    if (acceptance < o.smc_min_acceptance) break;
  }
  race(runner, o, pop, next_repeat, generations);
  return pop;
}

void finish(const FitProblem& problem, const FitOptions& o, FitResult& r) {
  if (r.population.empty()) {
    throw InvalidInput("fit: no trial of " + std::to_string(r.trials) + " was scored; raise --trials");
  }
  r.best = r.population.front();
  r.params = problem.box.params_at(problem.base, r.best.u);
  Eigen::Matrix<double, 5, 1> mean;
  Eigen::Matrix<double, 5, 5> cov;
  weighted_moments(r.population, mean, cov);
  for (int k = 0; k < 5; ++k) {
    r.posterior_mean[static_cast<std::size_t>(k)] = mean(k);
    r.posterior_stddev[static_cast<std::size_t>(k)] = std::sqrt(std::max(0.0, cov(k, k)));
  }
  const std::uint64_t evaluation_seed = fit_evaluation_seed(o.seed);
  r.evaluation_errors.assign(static_cast<std::size_t>(o.evaluation_seeds), 0.0);
  parallel_for_dynamic(r.evaluation_errors.size(), o.threads, [&](std::size_t i) {
    if (o.cancel) o.cancel->throw_if_cancelled();
    r.evaluation_errors[i] = run_trial(problem, r.best.u, evaluation_seed, i).error;
  });
  double sum = 0.0, ss = 0.0;
  for (double e : r.evaluation_errors) sum += e;
  const double n = static_cast<double>(r.evaluation_errors.size());
  r.error_mean = n > 0 ? sum / n : r.best.error;
  for (double e : r.evaluation_errors) ss += (e - r.error_mean) * (e - r.error_mean);
  r.error_stddev = n > 1 ? std::sqrt(ss / (n - 1)) : 0.0;
}

}  // namespace

std::uint64_t fit_evaluation_seed(std::uint64_t seed) { return Rng::derive(seed, "fit-evaluation").next_u64(); }

const char* to_string(FitMethod method) { return method == FitMethod::Paper ? "paper" : "smc"; }

std::optional<FitMethod> parse_fit_method(std::string_view text) {
  if (text == "paper") return FitMethod::Paper;
  if (text == "smc") return FitMethod::Smc;
  return std::nullopt;
}

int FitOptions::population_size() const {
  if (population > 0) return population;
  return static_cast<int>(std::clamp<long long>(trials / 100, 20, 200));
}

std::vector<std::string> FitOptions::problems() const {
  std::vector<std::string> out;
  if (trials < 1 || trials > 100000000) out.push_back("--trials " + std::to_string(trials) + " is outside [1, 100000000]");
  if (threads < 1) out.push_back("--threads " + std::to_string(threads) + " is below 1");
  if (population < 0) out.push_back("the population " + std::to_string(population) + " is negative");
  if (block < 1) out.push_back("the block size " + std::to_string(block) + " is below 1");
  if (evaluation_seeds < 0 || evaluation_seeds > 1000) out.push_back("the evaluation seeds " + std::to_string(evaluation_seeds) + " are outside [0, 1000]");
  if (smc_seeds < 1 || smc_seeds > 64) out.push_back("the SMC seeds per candidate " + std::to_string(smc_seeds) + " are outside [1, 64]");
  if (!(smc_race_share >= 0.0 && smc_race_share <= 0.5)) out.push_back("the SMC race share " + format_number(smc_race_share) + " is outside [0, 0.5]");
  if (!(smc_quantile > 0.0 && smc_quantile <= 1.0)) out.push_back("the SMC quantile " + format_number(smc_quantile) + " is outside (0, 1]");
  if (shard.count < 1 || shard.index < 1 || shard.index > shard.count) {
    out.push_back("--shard " + std::to_string(shard.index) + "/" + std::to_string(shard.count) +
                  " is not K/N with 1 ≤ K ≤ N");
  } else if (shard.count > 1 && method != FitMethod::Paper) {
    out.push_back("--shard needs --method paper: the sequential method's generations depend on each other, so it runs "
                  "on one machine (use --threads)");
  }
  return out;
}

FitResult run_fit(const FitProblem& problem, const FitOptions& options) {
  const auto list = options.problems();
  if (!list.empty()) throw InvalidInput(list.front());
  Runner runner(problem, options);
  FitResult r;
  r.method = options.method;
  const std::size_t p = static_cast<std::size_t>(options.population_size());
  if (options.method == FitMethod::Paper) {
    const FitShard shard = options.shard;
    r.population = best_of_prior(runner, options, options.trials, p,
                                 [&](long long b) { return b % shard.count == shard.index - 1; }, 0);
    r.generations = 1;
  } else {
    r.population = smc(runner, options, r.generations);
  }
  r.trials = runner.trials();
  r.rejected = runner.rejected();
  if (options.shard.count > 1) return r;
  finish(problem, options, r);
  return r;
}

FitResult merge_fit_shards(const FitProblem& problem, const std::vector<FitResult>& shards, const FitOptions& options) {
  FitOptions whole = options;
  whole.shard = {};
  const auto list = whole.problems();
  if (!list.empty()) throw InvalidInput(list.front());
  if (whole.method != FitMethod::Paper) throw InvalidInput("fit merge: only --method paper fits are sharded");
  FitResult r;
  r.method = FitMethod::Paper;
  r.generations = 1;
  for (const FitResult& s : shards) {
    r.trials += s.trials;
    r.rejected += s.rejected;
    r.population.insert(r.population.end(), s.population.begin(), s.population.end());
  }
  std::sort(r.population.begin(), r.population.end(), by_error);
  const std::size_t p = static_cast<std::size_t>(whole.population_size());
  if (r.population.size() > p) r.population.resize(p);
  for (Particle& q : r.population) q.weight = 1.0 / static_cast<double>(r.population.size());
  finish(problem, whole, r);
  return r;
}

}  // namespace fissure
