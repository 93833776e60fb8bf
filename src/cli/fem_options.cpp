#include "fem_options.hpp"

#include "option_checks.hpp"

#include "fissure/base/disk_cache.hpp"
#include "fissure/base/error.hpp"

#include <iostream>

namespace fissure::cli {

void add_material_options(CLI::App& cmd, ElasticMaterial& material, bool require_density) {
  const auto& table = elastic_material_parameters();
  double* targets[3] = {&material.youngs_modulus, &material.poisson_ratio, &material.density};
  for (std::size_t i = 0; i < table.size(); ++i) {
    const ParameterInfo& info = table[i];
    // The unit is in the range the check shows ("FLOAT:in (0, inf] Pa").
    auto* option = cmd.add_option(info.flag, *targets[i], std::string(info.help))->check(parameter_range(info));
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

}  // namespace fissure::cli
