#include "image_options.hpp"

#include "option_checks.hpp"

#include "fissure/base/error.hpp"

#include <cmath>

namespace fissure::cli {

ExemplarAnalysis analyze_image(const std::filesystem::path& path, const ExemplarAnalysisOptions& options) {
  try {
    return analyze_exemplar(path, options);
  } catch (const InvalidInput& e) {
    // The core's image size check names no CLI flag; the CLI knows which one raises the limit.
    const std::string message = e.what();
    if (message.find("megapixels") == std::string::npos || message.find("--max-megapixels") != std::string::npos) throw;
    throw InvalidInput(message + " (raise it with --max-megapixels)");
  }
}

void add_max_megapixels_option(CLI::App& cmd, double& max_megapixels) {
  // 1e4 MP (10^10 pixels) is far above any tracing and keeps the pixel count well inside int64.
  cmd.add_option("--max-megapixels", max_megapixels, "Refuse larger images before decoding them")
      ->default_val(64)
      ->check(finite_in(1e-3, 1e4));
}

std::int64_t max_pixels(double max_megapixels) { return std::llround(max_megapixels * 1e6); }

}  // namespace fissure::cli
