#include "cli_common.hpp"

#include "option_checks.hpp"

#include "fissure/base/error.hpp"
#include "fissure/base/thread_count.hpp"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <iostream>
#include <unistd.h>

namespace fissure::cli {

void add_material_options(CLI::App& cmd, ElasticMaterial& material, bool require_density) {
  const auto& table = elastic_material_parameters();
  double* targets[3] = {&material.youngs_modulus, &material.poisson_ratio, &material.density};
  for (std::size_t i = 0; i < table.size(); ++i) {
    const ParameterInfo& info = table[i];
    const std::string unit = info.unit[0] ? std::string(" [") + info.unit + "]" : std::string();
    auto* option = cmd.add_option(info.flag, *targets[i], std::string(info.help) + unit)->check(finite_number());
    const bool required = i < 2 || require_density;
    if (required) {
      option->required();
    } else {
      option->default_val(info.default_value);
    }
  }
}

void validate_material_flags(const ElasticMaterial& material) {
  const auto& table = elastic_material_parameters();
  const double values[3] = {material.youngs_modulus, material.poisson_ratio, material.density};
  std::string message;
  for (std::size_t i = 0; i < table.size(); ++i) {
    const std::string problem = parameter_problem(table[i], values[i], table[i].flag);
    if (!problem.empty()) message += (message.empty() ? "" : "; ") + problem;
  }
  if (!message.empty()) throw InvalidInput(message);
}

ModalBasis modal_basis_for(std::shared_ptr<const ElasticBody> body, const std::vector<int>& fixed,
                           const ModalOptions& options, bool no_cache, const std::string& cache_dir, bool& loaded,
                           TerminalProgress& progress, const CancelToken* cancel) {
  loaded = false;
  if (no_cache) return ModalBasis::compute(std::move(body), fixed, options, &progress, cancel);
  const std::filesystem::path dir = cache_dir.empty() ? default_cache_directory() : std::filesystem::path(cache_dir);
  // A cache that cannot be written does not fail the command, but the user hears it once.
  std::string warning;
  ModalBasis basis = cached_modal_basis(std::move(body), fixed, options, dir, &loaded, &progress, cancel, &warning);
  if (!warning.empty()) {
    progress.clear();
    std::cerr << "fissure: warning: " << warning << '\n';
  }
  return basis;
}

MassKind mass_kind(const std::string& flag) { return flag == "consistent" ? MassKind::Consistent : MassKind::Lumped; }

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

void add_threads_option(CLI::App& cmd) {
  cmd.add_option_function<int>("--threads", [](int n) { set_thread_count(n); },
                               "Threads for all work (default $FISSURE_THREADS, else every hardware thread); "
                               "results are identical at any count")
      ->check(CLI::Range(1, 1024));
}

std::int64_t max_pixels(double max_megapixels) { return std::llround(max_megapixels * 1e6); }

std::FILE* summary_stream(const std::string& output) { return output == "-" ? stderr : stdout; }

}  // namespace fissure::cli
