// fissure fit IMAGE -o material.json: fit a fracture material to a traced exemplar by ABC (paper
// §6), and fissure fit merge SHARD... -o material.json: join the shards of a --shard fit.

#include "cli_common.hpp"
#include "command_table.hpp"
#include "commands.hpp"
#include "image_options.hpp"
#include "interruption.hpp"
#include "option_checks.hpp"
#include "terminal_progress.hpp"

#include "fissure/base/atomic_file.hpp"
#include "fissure/base/distinct_files.hpp"
#include "fissure/base/error.hpp"
#include "fissure/base/number_text.hpp"
#include "fissure/base/thread_count.hpp"
#include "fissure/exemplar/stats_json.hpp"
#include "fissure/fit/fit_files.hpp"
#include "fissure/fit/fit_report.hpp"
#include "fissure/mesh/tile.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>

namespace fissure::cli {
namespace {

namespace fs = std::filesystem;

struct FitArgs {
  std::string image;
  std::string base = kDefaultMaterialName;
  long long trials = 20000;
  std::uint64_t seed = 1;
  std::string method = "smc";
  double age = 3.0;
  std::string body;
  int tets = 0;
  int population = 0;
  int evaluation_seeds = 8;
  std::string name;
  std::string output;
  std::string checkpoint;
  std::string report;
  bool resume = false;
  std::string shard;
  double max_megapixels = 64.0;
  bool quiet = false;
  // merge
  std::vector<std::string> shards;
};

std::string duration_text(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "?";
  const long long s = std::llround(seconds);
  if (s < 60) return std::to_string(s) + " s";
  if (s < 3600) return std::to_string(s / 60) + " min " + std::to_string(s % 60) + " s";
  return std::to_string(s / 3600) + " h " + std::to_string((s % 3600) / 60) + " min";
}

FitShard parse_shard(const std::string& text) {
  const auto slash = text.find('/');
  const auto bad = [&] { return InvalidInput("--shard " + text + " is not K/N with 1 <= K <= N (e.g. 3/8)"); };
  if (slash == std::string::npos) throw bad();
  const std::vector<double> k = parse_number_list(text.substr(0, slash), "--shard", 1, "K");
  const std::vector<double> n = parse_number_list(text.substr(slash + 1), "--shard", 1, "N");
  if (k[0] != std::floor(k[0]) || n[0] != std::floor(n[0]) || k[0] < 1 || n[0] < 1 || k[0] > n[0] || n[0] > 100000) throw bad();
  return {static_cast<int>(k[0]), static_cast<int>(n[0])};
}

// Progress on the terminal, and the checkpoint after every block (at most once a second).
class FitMonitor {
public:
  FitMonitor(TerminalProgress& progress, fs::path checkpoint, Hash128 settings, TrialRecords trials)
      : m_progress(progress), m_checkpoint(std::move(checkpoint)), m_settings(settings), m_trials(std::move(trials)) {}

  void on_trials(const std::vector<TrialRecord>& finished) {
    // After every block (a few per second at most), so a killed fit loses only the block it
    // was in: the file is replaced atomically, never left half written.
    for (const TrialRecord& r : finished) m_trials[r.key] = r;
    save();
  }
  void save() {
    if (m_checkpoint.empty()) return;
    save_fit_checkpoint(m_checkpoint, m_settings, m_trials);
  }
  void on_progress(const FitProgress& p) {
    const double fraction = p.trials_total > 0 ? static_cast<double>(p.trials_done) / static_cast<double>(p.trials_total) : 1.0;
    std::string text = "fit: " + std::to_string(p.trials_done) + "/" + std::to_string(p.trials_total) + " trials";
    if (p.generation > 0) text += ", generation " + std::to_string(p.generation);
    text += ", " + format_number(p.trials_per_second, 3) + " trials/s, best " +
            (std::isfinite(p.best_error) ? format_number(p.best_error, 4) : std::string("-")) + ", ETA " +
            duration_text(p.eta_seconds);
    m_progress.report(text, std::min(fraction, 1.0));
  }
  const TrialRecords& trials() const { return m_trials; }

private:
  TerminalProgress& m_progress;
  fs::path m_checkpoint;
  Hash128 m_settings;
  TrialRecords m_trials;
};

void print_summary(const FitSettings& settings, const FitProblem& problem, const FitResult& r, const std::string& output,
                   double seconds) {
  const FitBodyPlan& plan = problem.body->plan();
  const auto f = [](double x) { return format_number(x, 4); };
  std::printf("fit body: %s x %s x %s m tile, %d tets (asked %d), %d load positions\n", format_number(plan.tile.width).c_str(),
              format_number(plan.tile.height).c_str(), format_number(plan.tile.thickness).c_str(), problem.body->mesh().tet_count(),
              plan.tets, problem.body->load_positions());
  if (plan.capped) std::printf("note: %s\n", plan.note.c_str());
  std::printf("%s: %lld trials (%lld stopped early), %d generation%s, %s\n", to_string(r.method), r.trials, r.rejected,
              r.generations, r.generations == 1 ? "" : "s", duration_text(seconds).c_str());
  std::printf("best: Eq. 5 score %s; on %zu fresh seeds %s +- %s\n", f(r.best.error).c_str(), r.evaluation_errors.size(),
              f(r.error_mean).c_str(), f(r.error_stddev).c_str());
  for (std::size_t k = 0; k < kFitDimensions; ++k) {
    const double span = problem.box.hi[k] - problem.box.lo[k];
    std::printf("  %-18s %-12s (posterior %s +- %s)\n", table3_priors()[k].name,
                format_number(parameter_value(r.params, problem.box.row[k]), 4).c_str(),
                format_number(problem.box.lo[k] + r.posterior_mean[k] * span, 4).c_str(),
                format_number(r.posterior_stddev[k] * span, 4).c_str());
  }
  std::printf("wrote %s (material \"%s\", age %s)\n", output.c_str(), settings.output_name.c_str(), format_number(settings.age).c_str());
}

int run_fit_command(const FitArgs& args) {
  Stopwatch watch;
  FitSettings settings;
  settings.options.method = *parse_fit_method(args.method);
  settings.options.trials = args.trials;
  settings.options.seed = args.seed;
  settings.options.population = args.population;
  settings.options.evaluation_seeds = args.evaluation_seeds;
  settings.options.threads = thread_count();
  if (!args.shard.empty()) settings.options.shard = parse_shard(args.shard);
  const bool sharded = settings.options.shard.count > 1;
  if (sharded && !args.report.empty()) {
    throw InvalidInput("--report draws the fit's winner, which a shard does not know: give --report to fissure fit merge");
  }
  {
    const auto problems = settings.options.problems();
    if (!problems.empty()) throw InvalidInput(problems.front());
  }
  settings.age = args.age;
  if (!args.body.empty()) {
    const std::vector<double> b = parse_number_list(args.body, "--body", 3, "W,H,T");
    settings.body.tile = TileSpec{b[0], b[1], b[2]};
  }
  settings.body.tets = args.tets;
  {
    const auto problems = settings.body.problems();
    if (!problems.empty()) throw InvalidInput(problems.front());
  }
  check_output_path(args.output);
  const fs::path checkpoint = args.checkpoint.empty() ? fs::path(args.output + ".checkpoint") : fs::path(args.checkpoint);
  check_output_path(checkpoint);
  if (!args.report.empty()) check_output_path(args.report);
  check_distinct_files({{"the exemplar", args.image}, {"--base", args.base}},
                       {{"-o", args.output}, {"the checkpoint", checkpoint}, {"--report", args.report}});

  TerminalProgress progress(args.quiet);
  settings.base = load_material(find_material(args.base));
  settings.base.fit.reset();
  {
    AbandonableWork work;
    progress.stage("analysing " + args.image);
    ExemplarAnalysisOptions options;
    options.image.max_pixels = max_pixels(args.max_megapixels);
    set_fit_exemplar(settings, analyze_image(args.image, options), args.image, args.name);
  }
  const Hash128 hash = fit_settings_hash(settings);

  TrialRecords resumed;
  std::error_code error;
  if (args.resume) {
    if (!fs::exists(checkpoint, error)) throw InvalidInput("--resume: there is no checkpoint " + checkpoint.string() + " to resume");
    resumed = load_fit_checkpoint(checkpoint, hash);
  } else if (fs::exists(checkpoint, error)) {
    throw InvalidInput(checkpoint.string() + " holds the finished trials of an earlier fit: resume it with --resume, or "
                       "delete it to start afresh");
  }

  FitMonitor monitor(progress, checkpoint, hash, resumed);
  FitResult result;
  FitProblem problem;
  {
    AbandonableWork work;
    progress.stage("preparing the fit body");
    problem = make_fit_problem(settings, thread_count(), &progress, &interrupt_token());
    FitOptions options = settings.options;
    options.resume = &resumed;
    options.cancel = &interrupt_token();
    options.on_trials = [&](const std::vector<TrialRecord>& t) { monitor.on_trials(t); };
    options.on_progress = [&](const FitProgress& p) { monitor.on_progress(p); };
    try {
      result = run_fit(problem, options);
    } catch (const Cancelled&) {
      monitor.save();
      progress.clear();
      std::fprintf(stderr, "fissure: %zu finished trials kept in %s; run the same command with --resume to go on\n",
                   monitor.trials().size(), checkpoint.string().c_str());
      throw;
    }
  }
  throw_if_interrupted();
  progress.clear();
  if (sharded) {
    save_fit_shard(args.output, {settings, settings.options.shard, result});
    std::printf("shard %d/%d: %lld trials (%lld stopped early), best score %s, %s; wrote %s\n", settings.options.shard.index,
                settings.options.shard.count, result.trials, result.rejected,
                result.population.empty() ? "-" : format_number(result.population.front().error, 4).c_str(),
                duration_text(watch.milliseconds() / 1000).c_str(), args.output.c_str());
  } else {
    save_material(args.output, fitted_material(settings, problem, result));
    print_summary(settings, problem, result, args.output, watch.milliseconds() / 1000);
  }
  fs::remove(checkpoint, error);
  if (!args.report.empty()) {
    progress.stage("drawing the report");
    write_fit_report(args.report, load_grey_image(args.image, max_pixels(args.max_megapixels)), settings, problem, result);
    progress.clear();
    std::printf("wrote %s\n", args.report.c_str());
  }
  return kExitOk;
}

int run_merge_command(const FitArgs& args) {
  Stopwatch watch;
  check_output_path(args.output);
  if (!args.report.empty()) {
    if (args.image.empty()) throw InvalidInput("--report needs --image: the shard files keep only the exemplar's statistics");
    check_output_path(args.report);
  }
  {
    std::vector<RoleAndPath> inputs = {{"--image", args.image}};
    for (const std::string& path : args.shards) inputs.push_back({"the input shard", path});
    check_distinct_files(inputs, {{"-o", args.output}, {"--report", args.report}});
  }
  std::vector<FitShardFile> shards;
  for (const std::string& path : args.shards) shards.push_back(load_fit_shard(path));
  const Hash128 hash = fit_settings_hash(shards.front().settings);
  const int count = shards.front().shard.count;
  std::map<int, std::string> seen;
  for (std::size_t i = 0; i < shards.size(); ++i) {
    if (fit_settings_hash(shards[i].settings) != hash) {
      throw InvalidInput(args.shards[i] + " is a shard of another fit than " + args.shards[0] + " (other image, material or options)");
    }
    if (shards[i].shard.count != count) {
      throw InvalidInput(args.shards[i] + " is shard " + std::to_string(shards[i].shard.index) + "/" + std::to_string(shards[i].shard.count) +
                         ", but " + args.shards[0] + " is one of " + std::to_string(count));
    }
    const auto [it, fresh] = seen.emplace(shards[i].shard.index, args.shards[i]);
    if (!fresh) throw InvalidInput(args.shards[i] + " and " + it->second + " are both shard " + std::to_string(shards[i].shard.index) + "/" + std::to_string(count));
  }
  for (int k = 1; k <= count; ++k) {
    if (!seen.count(k)) throw InvalidInput("shard " + std::to_string(k) + "/" + std::to_string(count) + " is missing");
  }
  FitSettings settings = shards.front().settings;
  settings.options.threads = thread_count();
  TerminalProgress progress(args.quiet);
  FitResult result;
  FitProblem problem;
  {
    AbandonableWork work;
    progress.stage("preparing the fit body");
    problem = make_fit_problem(settings, thread_count(), &progress, &interrupt_token());
    std::vector<FitResult> results;
    for (const FitShardFile& s : shards) results.push_back(s.result);
    FitOptions options = settings.options;
    options.cancel = &interrupt_token();
    progress.stage("re-simulating the winner on fresh seeds");
    result = merge_fit_shards(problem, results, options);
  }
  throw_if_interrupted();
  progress.clear();
  save_material(args.output, fitted_material(settings, problem, result));
  print_summary(settings, problem, result, args.output, watch.milliseconds() / 1000);
  if (!args.report.empty()) {
    write_fit_report(args.report, load_grey_image(args.image, max_pixels(args.max_megapixels)), settings, problem, result);
    std::printf("wrote %s\n", args.report.c_str());
  }
  return kExitOk;
}

}  // namespace

void register_fit(CLI::App& app, Action& action) {
  auto args = std::make_shared<FitArgs>();
  auto* cmd = app.add_subcommand("fit", std::string(command_info("fit").summary));
  add_threads_option(*cmd);
  cmd->add_option("IMAGE", args->image, "Traced crack image (white cracks on black, or black on white)");
  cmd->add_option("--base", args->base, "Material whose physical values and noise the fit keeps (bundled name or file)")
      ->default_val(kDefaultMaterialName);
  cmd->add_option("--trials", args->trials, "Trial budget, every seed repeat counted")->default_val(20000);
  cmd->add_option("--seed", args->seed, "Seed of every draw of the fit")->check(seed_value())->default_val(1);
  cmd->add_option("--method", args->method, "paper: the best of N prior draws, as published; smc: ABC population Monte Carlo")
      ->check(CLI::IsMember({"paper", "smc"}))
      ->default_val("smc");
  cmd->add_option("--age", args->age, "Age the fit simulates to, age units (written into the material)")
      ->check(finite_in(1e-6, 1e6))
      ->default_val(3.0);
  cmd->add_option("--body", args->body, "Fit body W,H,T (m) instead of the exemplar's aspect on a 1 m x 2 cm tile");
  cmd->add_option("--tets", args->tets, "Tets of the fit body instead of the resolution rule")->type_name("N")->check(count_in(100, 2000000));
  cmd->add_option("--population", args->population, "Population kept (0: trials/100 within [20, 200])")->type_name("N")->check(count_in(0, 100000));
  cmd->add_option("--eval-seeds", args->evaluation_seeds, "Fresh seeds the winner is re-simulated on for the reported error")
      ->type_name("N")->check(count_in(0, 1000))
      ->default_val(8);
  cmd->add_option("--name", args->name, "Name of the fitted material (default: the image's file name without extension)");
  cmd->add_option("-o,--output", args->output, "Fitted material file (with --shard: the shard's result); required");
  cmd->add_option("--checkpoint", args->checkpoint, "Checkpoint file (default: OUTPUT.checkpoint; removed on success)");
  cmd->add_option("--report", args->report, "Also draw the exemplar beside a fitted pattern, their histograms overlaid (PNG)")->check(png_path());
  cmd->add_flag("--resume", args->resume, "Go on from the checkpoint of an interrupted run of the same command");
  cmd->add_option("--shard", args->shard, "Run slice K of N of the trials (paper method; join with fissure fit merge)");
  add_max_megapixels_option(*cmd, args->max_megapixels);
  cmd->add_flag("-q,--quiet", args->quiet, "No progress on stderr");

  auto merge_args = std::make_shared<FitArgs>();
  auto* merge = cmd->add_subcommand("merge", "Join the shard files of a --shard fit into the material an unsharded run writes");
  add_threads_option(*merge);
  merge->add_option("SHARD", merge_args->shards, "Shard files written by fissure fit --shard K/N")->required();
  merge->add_option("-o,--output", merge_args->output, "Fitted material file")->required();
  merge->add_option("--image", merge_args->image, "The exemplar image (for --report: the shards keep only its statistics)");
  merge->add_option("--report", merge_args->report, "Also draw the exemplar beside a fitted pattern (PNG; needs --image)")->check(png_path());
  merge->add_flag("-q,--quiet", merge_args->quiet, "No progress on stderr");
  merge->callback([&action, merge_args] { action = [merge_args] { return run_merge_command(*merge_args); }; });

  cmd->callback([&action, args, cmd] {
    if (cmd->got_subcommand("merge")) return;
    if (args->image.empty()) throw CLI::RequiredError("IMAGE");
    if (args->output.empty()) throw CLI::RequiredError("--output");
    action = [args] { return run_fit_command(*args); };
  });
}

}  // namespace fissure::cli
