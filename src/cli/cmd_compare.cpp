// fissure compare A B: the paper's Eq. 5 between two patterns (images or stats JSON files).

#include "cli_common.hpp"
#include "commands.hpp"

#include "fissure/exemplar/exemplar_analysis.hpp"
#include "fissure/exemplar/similarity.hpp"
#include "fissure/exemplar/stats_json.hpp"

#include <cstdio>

namespace fissure::cli {
namespace {

struct CompareArgs {
  std::string a, b;
  std::string weights = "3,1,1";
  bool json = false;
};

PatternStats stats_of(const std::string& input) {
  const std::filesystem::path path(input);
  if (path.extension() == ".json") return load_pattern_stats(path);
  return analyze_exemplar(path).stats;
}

int run_compare(const CompareArgs& args) {
  const auto w = parse_triple(args.weights, "--weights");
  const SimilarityWeights weights{w[0], w[1], w[2]};
  const PatternStats a = stats_of(args.a);
  const PatternStats b = stats_of(args.b);
  const Similarity s = pattern_similarity(a, b, weights);
  if (args.json) {
    std::printf("{\"error\": %.6g, \"emd_fragment\": %.6g, \"emd_crack\": %.6g, \"emd_junction\": %.6g, "
                "\"weights\": [%g, %g, %g]}\n",
                s.total, s.fragment, s.crack, s.junction, w[0], w[1], w[2]);
  } else {
    std::printf("Eq. 5 error %.4f = %g x %.4f (fragment areas) + %g x %.4f (crack lengths) + %g x %.4f (junction density)\n",
                s.total, w[0], s.fragment, w[1], s.crack, w[2], s.junction);
  }
  return kExitOk;
}

}  // namespace

void register_compare(CLI::App& app, Action& action) {
  auto args = std::make_shared<CompareArgs>();
  auto* cmd = app.add_subcommand("compare", "Statistical distance between two crack patterns (paper Eq. 5)");
  cmd->add_option("A", args->a, "Traced image or statistics JSON (from fissure analyze --json)")->required();
  cmd->add_option("B", args->b, "Traced image or statistics JSON")->required();
  cmd->add_option("--weights", args->weights, "Weights of the fragment, crack and junction terms")->default_val("3,1,1");
  cmd->add_flag("--json", args->json, "Print the result as JSON");
  cmd->callback([&action, args] { action = [args] { return run_compare(*args); }; });
}

}  // namespace fissure::cli
