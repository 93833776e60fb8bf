#include "fissure/fit/fit_report.hpp"

#include "fissure/exemplar/comparison_report.hpp"
#include "fissure/fracture/pattern_image.hpp"

#include <algorithm>
#include <limits>
#include <numeric>

namespace fissure {

std::uint64_t median_evaluation_trial(const FitResult& r) {
  if (r.evaluation_errors.empty()) return 0;
  std::vector<std::uint64_t> order(r.evaluation_errors.size());
  std::iota(order.begin(), order.end(), std::uint64_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::uint64_t a, std::uint64_t b) { return r.evaluation_errors[a] < r.evaluation_errors[b]; });
  return order[(order.size() - 1) / 2];
}

void write_fit_report(const std::filesystem::path& path, const GreyImage& exemplar_drawing, const FitSettings& settings,
                      const FitProblem& problem, const FitResult& r) {
  const std::uint64_t pick = median_evaluation_trial(r);
  PatternStats stats;
  std::vector<CrackSurface> cracks;
  const TrialOutcome trial = run_trial(problem, r.best.u, fit_evaluation_seed(settings.options.seed), pick,
                                       std::numeric_limits<double>::infinity(), &stats, &cracks);
  const PreparedBody& prepared = problem.body->prepared();
  const VisiblePattern visible =
      extract_visible_pattern(prepared.mesh(), cracks, trial.cracks, prepared.scenario().up, problem.visible);
  ComparisonReport report;
  report.title = "fissure fit " + settings.exemplar_name + " (" + to_string(r.method) + ", " + std::to_string(r.trials) +
                 " trials, seed " + std::to_string(settings.options.seed) + "): material \"" + settings.output_name + "\"";
  report.left_label = "exemplar " + settings.exemplar_name;
  report.right_label = "fitted: fresh seed " + std::to_string(pick + 1) + " of " +
                       std::to_string(std::max<std::size_t>(1, r.evaluation_errors.size())) + " (the median)";
  report.left_image = exemplar_drawing;
  report.right_image = render_pattern_image(visible).drawing;
  report.left = settings.exemplar;
  report.right = std::move(stats);
  report.weights = problem.weights;
  write_comparison_report(path, report);
}

}  // namespace fissure
