// fissure compare A B: the paper's Eq. 5 between two patterns (images or stats JSON files).

#include "cli_common.hpp"
#include "option_checks.hpp"
#include "image_options.hpp"
#include "command_table.hpp"
#include "commands.hpp"
#include "interruption.hpp"
#include "terminal_progress.hpp"

#include "fissure/base/atomic_file.hpp"
#include "fissure/base/distinct_files.hpp"
#include "fissure/base/number_text.hpp"
#include "fissure/exemplar/comparison_report.hpp"
#include "fissure/exemplar/similarity.hpp"
#include "fissure/exemplar/stats_json.hpp"

#include <cstdio>

namespace fissure::cli {
namespace {

struct CompareArgs {
  std::string a, b;
  std::string weights = "3,1,1";
  std::string report;
  double max_megapixels = 64.0;
  bool json = false;
  bool quiet = false;
};

bool is_stats_file(const std::string& input) { return std::filesystem::path(input).extension() == ".json"; }

PatternStats stats_of(const std::string& input, const CompareArgs& args, TerminalProgress& progress) {
  const std::filesystem::path path(input);
  if (is_stats_file(input)) return load_pattern_stats(path);
  progress.stage("analysing " + input);
  ExemplarAnalysisOptions options;
  options.image.max_pixels = max_pixels(args.max_megapixels);
  return analyze_image(path, options).stats;
}

// The report shows each input's drawing (none for statistics JSON) above the histograms.
void write_report(const CompareArgs& args, const PatternStats& a, const PatternStats& b, const SimilarityWeights& weights) {
  ComparisonReport report;
  report.title = "fissure compare: Eq. 5 between two crack patterns";
  report.left_label = "A: " + std::filesystem::path(args.a).filename().string();
  report.right_label = "B: " + std::filesystem::path(args.b).filename().string();
  if (!is_stats_file(args.a)) report.left_image = load_grey_image(args.a, max_pixels(args.max_megapixels));
  if (!is_stats_file(args.b)) report.right_image = load_grey_image(args.b, max_pixels(args.max_megapixels));
  report.left = a;
  report.right = b;
  report.weights = weights;
  write_comparison_report(args.report, report);
}

int run_compare(const CompareArgs& args) {
  const auto w = parse_number_list(args.weights, "--weights", 3, "fragment,crack,junction");
  const SimilarityWeights weights{w[0], w[1], w[2]};
  if (!args.report.empty()) check_output_path(args.report);
  check_distinct_files({{"the first input", args.a}, {"the second input", args.b}}, {{"--report", args.report}});
  TerminalProgress progress(args.quiet);
  PatternStats a, b;
  {
    AbandonableWork work;
    a = stats_of(args.a, args, progress);
    b = stats_of(args.b, args, progress);
  }
  throw_if_interrupted();
  progress.clear();
  const Similarity s = pattern_similarity(a, b, weights);
  if (!args.report.empty()) write_report(args, a, b, weights);
  const auto g = [](double x) { return format_number(x); };
  if (args.json) {
    std::printf("{\"error\": %s, \"emd_fragment\": %s, \"emd_crack\": %s, \"emd_junction\": %s, \"weights\": [%s, %s, %s]}\n",
                g(s.total).c_str(), g(s.fragment).c_str(), g(s.crack).c_str(), g(s.junction).c_str(), g(w[0]).c_str(),
                g(w[1]).c_str(), g(w[2]).c_str());
  } else {
    const auto f = [](double x) { return format_number(x, 4); };
    std::printf("Eq. 5 error %s = %s x %s (fragment areas) + %s x %s (crack lengths) + %s x %s (junction density)\n",
                f(s.total).c_str(), g(w[0]).c_str(), f(s.fragment).c_str(), g(w[1]).c_str(), f(s.crack).c_str(),
                g(w[2]).c_str(), f(s.junction).c_str());
  }
  return kExitOk;
}

}  // namespace

void register_compare(CLI::App& app, Action& action) {
  auto args = std::make_shared<CompareArgs>();
  auto* cmd = app.add_subcommand("compare", std::string(command_info("compare").summary));
  add_threads_option(*cmd);
  cmd->add_option("A", args->a, "Traced image or statistics JSON (from fissure analyze --json)")->required();
  cmd->add_option("B", args->b, "Traced image or statistics JSON")->required();
  cmd->add_option("--weights", args->weights, "Weights of the fragment, crack and junction terms")->default_val("3,1,1");
  cmd->add_option("--report", args->report, "Also draw both patterns and their three histograms overlaid into this PNG")->check(png_path());
  add_max_megapixels_option(*cmd, args->max_megapixels);
  cmd->add_flag("--json", args->json, "Print the result as JSON");
  cmd->add_flag("-q,--quiet", args->quiet, "No progress on stderr");
  cmd->callback([&action, args] { action = [args] { return run_compare(*args); }; });
}

}  // namespace fissure::cli
