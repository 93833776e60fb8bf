// fit_exemplars: one exemplar's row of docs/fit.md's "Fits of the shared exemplars" (issue 12):
// the fit's error against the two references the issue sets, the median prior sample and a
// Voronoi fracture with the exemplar's fragment count. scripts/fit-exemplars.sh runs it on every
// closed network of ../shared/exemplars and writes the table.
//
//   fit_exemplars --image PNG --out row.json [--trials N] [--method paper|smc] [--seed S]
//                 [--eval-seeds K] [--prior-draws M] [--voronoi-seeds V] [--report fit.png]
//                 [--voronoi-report voronoi.png] [--threads T]
//
// All three are scored the same way, as the mean Eq. 5 error over fresh streams:
//  - the fit: `fissure fit`'s settings (default base material, the exemplar's fit body), its
//    winner re-simulated on K fresh seeds (FitResult::evaluation_errors);
//  - the prior: M uniform draws from the fit's box on the same body, each with its own stream
//    (no early rejection, so every draw has an error); the median;
//  - Voronoi: V drawings of the Voronoi diagram of F uniform points on the fit body's face (F the
//    exemplar's fragment count, voronoi_baseline.hpp), analysed like the exemplar's tracing.
// Deterministic for given options at any thread count.

#include "fissure/base/error.hpp"
#include "fissure/base/number_text.hpp"
#include "fissure/base/parallel.hpp"
#include "fissure/base/rng.hpp"
#include "fissure/exemplar/comparison_report.hpp"
#include "fissure/exemplar/exemplar_analysis.hpp"
#include "fissure/fit/fit_files.hpp"
#include "fissure/fit/fit_report.hpp"
#include "fissure/fit/voronoi_baseline.hpp"

#include "fissure/base/atomic_file.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

namespace {
using namespace fissure;

struct Args {
  std::string image, out, report, voronoi_report;
  std::string method = "smc";
  long long trials = 2000;
  std::uint64_t seed = 1;
  int evaluation_seeds = 16;
  int prior_draws = 64;
  int voronoi_seeds = 16;
  int threads = 2;
};

[[noreturn]] void usage(const std::string& problem) {
  throw InvalidInput(problem +
                     "\nusage: fit_exemplars --image PNG --out row.json [--trials N] [--method paper|smc] [--seed S] "
                     "[--eval-seeds K] [--prior-draws M] [--voronoi-seeds V] [--report PNG] [--voronoi-report PNG] "
                     "[--threads T]");
}

long long parse_integer(const std::string& text, const std::string& flag, double lo, double hi) {
  const double v = parse_number_list(text, flag, 1, "a number")[0];
  if (!(v >= lo && v <= hi) || v != std::floor(v)) usage(flag + " " + text + " is not an integer in [" + format_number(lo) + ", " + format_number(hi) + "]");
  return static_cast<long long>(v);
}

Args parse_args(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (i + 1 >= argc) usage(flag + " needs a value");
    const std::string value = argv[++i];
    if (flag == "--image") a.image = value;
    else if (flag == "--out") a.out = value;
    else if (flag == "--report") a.report = value;
    else if (flag == "--voronoi-report") a.voronoi_report = value;
    else if (flag == "--method") a.method = value;
    else if (flag == "--trials") a.trials = parse_integer(value, flag, 1, 1e8);
    else if (flag == "--seed") a.seed = static_cast<std::uint64_t>(parse_integer(value, flag, 0, 1e15));
    else if (flag == "--eval-seeds") a.evaluation_seeds = static_cast<int>(parse_integer(value, flag, 1, 1000));
    else if (flag == "--prior-draws") a.prior_draws = static_cast<int>(parse_integer(value, flag, 1, 1e6));
    else if (flag == "--voronoi-seeds") a.voronoi_seeds = static_cast<int>(parse_integer(value, flag, 1, 1000));
    else if (flag == "--threads") a.threads = static_cast<int>(parse_integer(value, flag, 1, 256));
    else usage("unknown option " + flag);
  }
  if (a.image.empty() || a.out.empty()) usage("--image and --out are required");
  if (!parse_fit_method(a.method)) usage("--method " + a.method + " is not paper or smc");
  return a;
}

struct Summary {
  double mean = 0.0, stddev = 0.0, median = 0.0;
};

Summary summarise(std::vector<double> v) {
  Summary s;
  if (v.empty()) return s;
  for (double x : v) s.mean += x;
  s.mean /= static_cast<double>(v.size());
  for (double x : v) s.stddev += (x - s.mean) * (x - s.mean);
  s.stddev = v.size() > 1 ? std::sqrt(s.stddev / static_cast<double>(v.size() - 1)) : 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  s.median = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  return s;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

int run(const Args& a) {
  const auto t0 = std::chrono::steady_clock::now();
  FitSettings settings;
  settings.options.method = *parse_fit_method(a.method);
  settings.options.trials = a.trials;
  settings.options.seed = a.seed;
  settings.options.evaluation_seeds = a.evaluation_seeds;
  settings.options.threads = a.threads;
  settings.base = load_material(find_material(kDefaultMaterialName));
  settings.base.fit.reset();
  const ExemplarAnalysis exemplar = analyze_exemplar(a.image, {});
  set_fit_exemplar(settings, exemplar, a.image);
  const FitProblem problem = make_fit_problem(settings, a.threads);
  const double prepare_s = seconds_since(t0);
  std::cerr << settings.exemplar_name << ": " << exemplar.stats.fragment_count << " fragments, "
            << problem.body->mesh().tet_count() << " tets; fitting\n";

  const auto t1 = std::chrono::steady_clock::now();
  FitOptions options = settings.options;
  const FitResult fit = run_fit(problem, options);
  const double fit_s = seconds_since(t1);
  if (!a.report.empty()) write_fit_report(a.report, load_grey_image(a.image, 64'000'000), settings, problem, fit);

  // The prior: its own streams, disjoint from the fit's (another seed purpose).
  std::cerr << settings.exemplar_name << ": " << a.prior_draws << " prior draws\n";
  const std::uint64_t prior_seed = Rng::derive(a.seed, "fit-exemplars-prior").next_u64();
  std::vector<double> prior(static_cast<std::size_t>(a.prior_draws));
  parallel_for_dynamic(prior.size(), a.threads, [&](std::size_t i) {
    Rng rng = Rng::derive(prior_seed, "unit point", i);
    UnitPoint u;
    for (double& x : u) x = rng.uniform();
    prior[i] = run_trial(problem, u, prior_seed, i).error;
  });

  // Voronoi with the exemplar's fragment count on the fit body's face, analysed as a tracing.
  std::cerr << settings.exemplar_name << ": " << a.voronoi_seeds << " Voronoi drawings\n";
  const TileSpec& tile = problem.body->plan().tile;
  PatternImageOptions drawing;
  drawing.long_side_px = problem.visible.reference_long_side_px;
  drawing.line_width_px = problem.visible.line_width_px;
  std::vector<double> voronoi(static_cast<std::size_t>(a.voronoi_seeds));
  std::vector<PatternStats> voronoi_stats(voronoi.size());
  std::vector<GreyImage> first_drawing(1);
  parallel_for_dynamic(voronoi.size(), a.threads, [&](std::size_t i) {
    GreyImage image = draw_voronoi_baseline(tile.width, tile.height, exemplar.stats.fragment_count, a.seed + i, drawing);
    voronoi_stats[i] = analyze_crack_mask(crack_mask_from_grey(image, {}, "voronoi")).stats;
    voronoi[i] = pattern_similarity(settings.exemplar, voronoi_stats[i], problem.weights).total;
    if (i == 0) first_drawing[0] = std::move(image);
  });
  if (!a.voronoi_report.empty()) {
    ComparisonReport report;
    report.title = "Voronoi baseline for " + settings.exemplar_name + ": " + std::to_string(exemplar.stats.fragment_count) +
                   " uniform points on the " + format_number(tile.width, 3) + " x " + format_number(tile.height, 3) + " m face";
    report.left_label = "exemplar " + settings.exemplar_name;
    report.right_label = "Voronoi, seed 1 of " + std::to_string(a.voronoi_seeds);
    report.left_image = load_grey_image(a.image, 64'000'000);
    report.right_image = first_drawing[0];
    report.left = settings.exemplar;
    report.right = voronoi_stats[0];
    report.weights = problem.weights;
    write_comparison_report(a.voronoi_report, report);
  }

  const Summary p = summarise(prior), v = summarise(voronoi);
  std::vector<double> voronoi_fragments;
  for (const PatternStats& s : voronoi_stats) voronoi_fragments.push_back(s.fragment_count);
  nlohmann::ordered_json row;
  row["exemplar"] = settings.exemplar_name;
  row["fragments"] = exemplar.stats.fragment_count;
  row["mean_junction_angle_deg"] = exemplar.stats.mean_junction_angle_deg;
  row["relaxation"] = to_string(problem.base.relaxation);
  row["tets"] = problem.body->mesh().tet_count();
  row["tile"] = {tile.width, tile.height, tile.thickness};
  row["capped"] = problem.body->plan().capped;
  row["method"] = a.method;
  row["trials"] = fit.trials;
  row["generations"] = fit.generations;
  row["seed"] = a.seed;
  row["prepare_s"] = prepare_s;
  row["fit_s"] = fit_s;
  row["fit_score"] = fit.best.error;
  row["evaluation_seeds"] = fit.evaluation_errors.size();
  row["fit_error_mean"] = fit.error_mean;
  row["fit_error_stddev"] = fit.error_stddev;
  row["fit_unit_point"] = fit.best.u;
  row["prior_draws"] = a.prior_draws;
  row["prior_error_median"] = p.median;
  row["prior_error_mean"] = p.mean;
  row["voronoi_seeds"] = a.voronoi_seeds;
  row["voronoi_error_mean"] = v.mean;
  row["voronoi_error_stddev"] = v.stddev;
  row["voronoi_fragments_mean"] = summarise(voronoi_fragments).mean;
  write_file_atomically(a.out, row.dump() + "\n");
  std::cerr << settings.exemplar_name << ": fit " << fit.error_mean << " +- " << fit.error_stddev << ", prior median " << p.median
            << ", Voronoi " << v.mean << " +- " << v.stddev << " (" << seconds_since(t0) << " s)\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(parse_args(argc, argv));
  } catch (const std::exception& e) {
    std::cerr << "fit_exemplars: " << e.what() << "\n";
    return 1;
  }
}
