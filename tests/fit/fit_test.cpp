// The fit (issue 12): the prior box, the fit body's tabulated loads, the early-rejection bound,
// and the two ABC methods' determinism, resume and shard merge. Small bodies (≈ 4K tets) and
// small budgets, so the whole file runs in seconds; the accuracy of the fit on real exemplars is
// measured by bench_fit and scripts/fit-table.sh, not here.

#include "fissure/base/atomic_file.hpp"
#include "fissure/base/error.hpp"
#include "fissure/base/rng.hpp"
#include "fissure/base/progress.hpp"
#include "fissure/fit/abc_fit.hpp"
#include "fissure/fit/fit_files.hpp"
#include "fissure/fracture/fracture_scenario.hpp"
#include "fissure/fracture/resistance_field.hpp"
#include "fissure/fracture/simulation.hpp"
#include "fissure/fem/load.hpp"

#include "provisional_exemplar.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>

namespace fissure {
namespace {

namespace fs = std::filesystem;

FitBodyOptions small_body_options() {
  FitBodyOptions o;
  o.tile = TileSpec{0.5, 0.5, 0.02};
  o.tets = 4000;
  o.load_grid = 4;
  return o;
}

std::shared_ptr<const FitBody> small_body() {
  static const std::shared_ptr<const FitBody> body = [] {
    const FitBodyOptions o = small_body_options();
    return std::make_shared<const FitBody>(plan_fit_body(10, 1.0, o), o, FractureParams{}.elastic(), 2);
  }();
  return body;
}

FractureParams fit_base() {
  FractureParams p;
  p.age = 3.0;
  return p;
}

// The statistics of one simulation on the body at unit point u: an exemplar whose parameters are
// known (the self-recovery setting). The box needs an exemplar first: a provisional one sets the
// fragment scale, which the known pattern then keeps.
FitProblem problem_from_known(const UnitPoint& u, std::uint64_t seed, PatternStats* exemplar_out = nullptr) {
  // 25 fragments on 0.25 m²: a fragment scale of 0.1 m.
  FitProblem p = make_fit_problem(test::provisional_exemplar(25), fit_base(), small_body());
  PatternStats stats;
  const TrialOutcome t = run_trial(p, u, seed, 0, std::numeric_limits<double>::infinity(), &stats);
  EXPECT_GT(t.fragments, 3) << "the known parameters should break the tile";
  stats.source = "known";
  FitProblem q = make_fit_problem(stats, fit_base(), small_body());
  // Keep the provisional box: the known u then means the same parameters.
  q.box = p.box;
  if (exemplar_out) *exemplar_out = stats;
  return q;
}

const UnitPoint kKnown = {0.5, 0.5, 0.4, 0.3, 0.5};

TEST(FitPrior, BoxIsTable3AndUnitPointsMapBothWays) {
  FractureParams base;
  const PriorBox box = make_prior_box(base, 0.2);
  // Table 3: dσ_e 0–33 % of R_cm, r_relax 0–100 % of √(fragment area), v_relax 0–33 %, R_cvar 0–100 %, l 0–30.
  EXPECT_DOUBLE_EQ(box.hi[0], 0.33 * base.resistance_mean);
  EXPECT_DOUBLE_EQ(box.hi[1], 0.2);
  EXPECT_DOUBLE_EQ(box.hi[2], 0.33 * base.resistance_mean);
  EXPECT_DOUBLE_EQ(box.hi[3], base.resistance_mean);
  EXPECT_DOUBLE_EQ(box.hi[4], 30.0);
  for (double x : box.lo) EXPECT_EQ(x, 0.0);
  const UnitPoint u = {0.1, 0.7, 0.25, 0.9, 0.5};
  const FractureParams p = box.params_at(base, u);
  EXPECT_DOUBLE_EQ(p.stress_rate, 0.1 * 0.33 * base.resistance_mean);
  EXPECT_DOUBLE_EQ(p.load_factor, 15.0);
  const UnitPoint back = box.unit_of(p);
  for (std::size_t k = 0; k < 5; ++k) EXPECT_NEAR(back[k], u[k], 1e-12);
  // r_relax's range excludes 0: the low corner is still a valid material.
  EXPECT_TRUE(box.params_at(base, UnitPoint{}).problems().empty());
  EXPECT_GT(box.params_at(base, UnitPoint{}).relax_radius, 0.0);
  EXPECT_THROW(make_prior_box(base, 0.0), InvalidInput);
}

TEST(FitBody, PlanFollowsTheExemplarWithinTheCap) {
  FitBodyOptions o;
  const FitBodyPlan wide = plan_fit_body(36, 1.5, o);
  EXPECT_DOUBLE_EQ(wide.tile.width, 1.0);
  EXPECT_DOUBLE_EQ(wide.tile.height, 1.0 / 1.5);
  EXPECT_DOUBLE_EQ(wide.tile.thickness, 0.02);
  EXPECT_EQ(wide.tets, 24000);  // 36 × 120 is below the paper's 24,000
  EXPECT_FALSE(wide.capped);
  const FitBodyPlan tall = plan_fit_body(300, 0.5, o);
  EXPECT_DOUBLE_EQ(tall.tile.height, 1.0);
  EXPECT_DOUBLE_EQ(tall.tile.width, 0.5);
  EXPECT_EQ(tall.tets, 36000);
  const FitBodyPlan dense = plan_fit_body(1000, 1.0, o);
  EXPECT_EQ(dense.tets, 60000);
  EXPECT_TRUE(dense.capped);
  EXPECT_NE(dense.note.find("1000 fragments want 120000 tets"), std::string::npos) << dense.note;
  EXPECT_THROW(plan_fit_body(10, 0.0, o), InvalidInput);
  o.load_grid = 0;
  EXPECT_THROW(plan_fit_body(10, 1.0, o), InvalidInput);
}

TEST(FitBody, TabulatedFieldIsTheDirectSolveOfThatPosition) {
  const FitBody& body = *small_body();
  ASSERT_EQ(body.load_positions(), 16);
  for (int k : {0, 5, 15}) {
    const LoadSpec load = patch_load(body.mesh(), Eigen::Vector3d::UnitZ(), body.load_position(k), 250.0);
    const StressField direct = body.prepared().stress_of_forces(assemble_load(body.mesh(), load));
    StressField table;
    body.initial_stress(k, 250.0, table);
    // Stored in float: relative error ≤ 2⁻²⁴ per entry, so 1e-6 of the peak covers it; a wrong
    // position or scale would be off by order 1.
    const double peak = direct.cwiseAbs().maxCoeff();
    EXPECT_GT(peak, 0.0);
    EXPECT_LE((direct - table).cwiseAbs().maxCoeff(), 1e-6 * peak) << "position " << k;
  }
  // Positions cover the grid's cells over the inner 70 % of the top face, at its height.
  const Eigen::Vector2d first = body.load_fraction(0), last = body.load_fraction(15);
  EXPECT_NEAR(first.x(), 0.15 + 0.7 / 8, 1e-12);
  EXPECT_NEAR(last.y(), 0.85 - 0.7 / 8, 1e-12);
  EXPECT_NEAR(body.load_position(3).z(), body.mesh().bounding_box()(1, 2), 1e-12);
}

TEST(FitTrial, LowerBoundHoldsAndRejectionIsExact) {
  const FitProblem problem = problem_from_known(kKnown, 11);
  int checked = 0, rejected = 0;
  for (std::uint64_t i = 0; i < 24; ++i) {
    UnitPoint u{};
    Rng rng(100 + i);
    for (double& x : u) x = rng.uniform();
    const TrialOutcome full = run_trial(problem, u, 5, i);
    // The bound is a bound: never above the true error of the finished pattern.
    EXPECT_LE(fragment_error_lower_bound(problem, full.fragments), full.error + 1e-12) << "trial " << i;
    ++checked;
    // Under a threshold below its error a trial may stop early, or finish with the same score;
    // under one at or above its error it must finish, scoring exactly as unrejected (a bound
    // that overshot would reject it here).
    const TrialOutcome below = run_trial(problem, u, 5, i, 0.5 * full.error);
    if (below.rejected) {
      ++rejected;
    } else {
      EXPECT_EQ(below.error, full.error);
    }
    const TrialOutcome above = run_trial(problem, u, 5, i, full.error * 1.0000001 + 1e-12);
    EXPECT_FALSE(above.rejected) << "trial " << i;
    EXPECT_EQ(above.error, full.error);
  }
  EXPECT_EQ(checked, 24);
  RecordProperty("rejected_at_half_error", rejected);
  // A threshold of 0 rejects whatever breaks into many fragments: the bound must be able to act.
  int zero_rejected = 0;
  for (std::uint64_t i = 0; i < 8; ++i) {
    const UnitPoint shattering = {1.0, 0.05, 0.05, 0.5, 0.5};
    zero_rejected += run_trial(problem, shattering, 9, i, 0.0).rejected ? 1 : 0;
  }
  EXPECT_GT(zero_rejected, 0);
}

FitOptions small_options(FitMethod method, long long trials) {
  FitOptions o;
  o.method = method;
  o.trials = trials;
  o.seed = 42;
  o.population = 16;
  o.block = 16;
  o.evaluation_seeds = 3;
  return o;
}

void expect_same_result(const FitResult& a, const FitResult& b) {
  ASSERT_EQ(a.population.size(), b.population.size());
  for (std::size_t i = 0; i < a.population.size(); ++i) {
    EXPECT_EQ(a.population[i].key, b.population[i].key) << i;
    EXPECT_EQ(a.population[i].error, b.population[i].error) << i;
    EXPECT_EQ(std::memcmp(a.population[i].u.data(), b.population[i].u.data(), sizeof(UnitPoint)), 0) << i;
    EXPECT_EQ(a.population[i].weight, b.population[i].weight) << i;
  }
  EXPECT_EQ(a.evaluation_errors, b.evaluation_errors);
  EXPECT_EQ(a.trials, b.trials);
  EXPECT_EQ(a.generations, b.generations);
}

TEST(AbcFit, SameResultAtOneAndTwoThreads) {
  const FitProblem problem = problem_from_known(kKnown, 11);
  for (FitMethod method : {FitMethod::Paper, FitMethod::Smc}) {
    SCOPED_TRACE(to_string(method));
    FitOptions o = small_options(method, 160);
    o.threads = 1;
    const FitResult one = run_fit(problem, o);
    o.threads = 2;
    const FitResult two = run_fit(problem, o);
    expect_same_result(one, two);
    EXPECT_EQ(one.trials, 160);
    EXPECT_EQ(one.population.size(), 16u);
    EXPECT_EQ(one.evaluation_errors.size(), 3u);
    if (method == FitMethod::Smc) {
      EXPECT_GE(one.generations, 2);
    }
  }
}

TEST(AbcFit, ResumeAfterACancelEqualsAnUnbrokenRun) {
  const FitProblem problem = problem_from_known(kKnown, 11);
  for (FitMethod method : {FitMethod::Paper, FitMethod::Smc}) {
    SCOPED_TRACE(to_string(method));
    FitOptions o = small_options(method, 160);
    o.threads = 2;
    const FitResult unbroken = run_fit(problem, o);
    // Cancel after the fourth block; the checkpoint hook has every finished trial.
    TrialRecords saved;
    CancelToken cancel;
    int blocks = 0;
    FitOptions broken = o;
    broken.cancel = &cancel;
    broken.on_trials = [&](const std::vector<TrialRecord>& t) {
      for (const TrialRecord& r : t) saved[r.key] = r;
    };
    broken.on_progress = [&](const FitProgress&) {
      if (++blocks == 4) cancel.cancel();
    };
    EXPECT_THROW(run_fit(problem, broken), Cancelled);
    EXPECT_GE(saved.size(), 64u);
    EXPECT_LT(saved.size(), 160u);
    // Resume: the saved trials are not run again (a counting hook sees only the others).
    FitOptions resumed = o;
    resumed.resume = &saved;
    std::size_t fresh = 0;
    resumed.on_trials = [&](const std::vector<TrialRecord>& t) { fresh += t.size(); };
    const FitResult after = run_fit(problem, resumed);
    expect_same_result(after, unbroken);
    EXPECT_EQ(fresh + saved.size(), static_cast<std::size_t>(unbroken.trials));
  }
}

TEST(AbcFit, MergedShardsEqualTheUnshardedRun) {
  const FitProblem problem = problem_from_known(kKnown, 11);
  FitOptions o = small_options(FitMethod::Paper, 200);  // 13 blocks, the last one short
  o.threads = 2;
  const FitResult whole = run_fit(problem, o);
  std::vector<FitResult> shards;
  long long trials = 0;
  for (int k = 1; k <= 3; ++k) {
    FitOptions s = o;
    s.shard = {k, 3};
    shards.push_back(run_fit(problem, s));
    EXPECT_TRUE(shards.back().evaluation_errors.empty());
    trials += shards.back().trials;
  }
  EXPECT_EQ(trials, 200);
  expect_same_result(merge_fit_shards(problem, shards, o), whole);
  // The sequential method refuses to be sharded, naming the way out.
  FitOptions smc = small_options(FitMethod::Smc, 200);
  smc.shard = {1, 2};
  try {
    run_fit(problem, smc);
    ADD_FAILURE() << "SMC with --shard was accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("--shard needs --method paper"), std::string::npos) << e.what();
  }
}

TEST(AbcFit, BadOptionsAreNamed) {
  const FitProblem problem = problem_from_known(kKnown, 11);
  const auto message = [&](FitOptions o) {
    try {
      run_fit(problem, o);
    } catch (const InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  FitOptions o = small_options(FitMethod::Paper, 0);
  EXPECT_NE(message(o).find("--trials 0 is outside"), std::string::npos) << message(o);
  o = small_options(FitMethod::Paper, 10);
  o.shard = {3, 2};
  EXPECT_NE(message(o).find("--shard 3/2 is not K/N"), std::string::npos) << message(o);
}

TEST(FitFiles, CheckpointRoundTripsAndRefusesAnotherFit) {
  const fs::path dir = test::fresh_temp_dir("fit-checkpoint");
  TrialRecords trials;
  trials[3] = {3, 0.25 + 1e-17, 12};
  trials[1] = {1, std::numeric_limits<double>::infinity(), 400};
  const Hash128 a = ContentHasher().add(std::string_view("a")).finish();
  const Hash128 b = ContentHasher().add(std::string_view("b")).finish();
  save_fit_checkpoint(dir / "c.json", a, trials);
  const TrialRecords back = load_fit_checkpoint(dir / "c.json", a);
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back.at(3).error, 0.25 + 1e-17);
  EXPECT_TRUE(std::isinf(back.at(1).error));
  EXPECT_EQ(back.at(1).fragments, 400);
  EXPECT_THROW(load_fit_checkpoint(dir / "c.json", b), InvalidInput);
  // Every truncation is refused as damaged, never read as fewer trials.
  const std::string text = read_file(dir / "c.json");
  for (std::size_t n = 0; n + 2 < text.size(); ++n) {
    write_file_atomically(dir / "t.json", text.substr(0, n));
    EXPECT_THROW(load_fit_checkpoint(dir / "t.json", a), IoError) << n;
  }
}

}  // namespace
}  // namespace fissure
