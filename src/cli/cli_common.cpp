#include "cli_common.hpp"

#include "fissure/base/error.hpp"

#include <charconv>
#include <cmath>

namespace fissure::cli {

void add_material_options(CLI::App& cmd, ElasticMaterial& material, bool require_density) {
  const auto& table = elastic_material_parameters();
  double* targets[3] = {&material.youngs_modulus, &material.poisson_ratio, &material.density};
  for (std::size_t i = 0; i < table.size(); ++i) {
    const ParameterInfo& info = table[i];
    const std::string unit = info.unit[0] ? std::string(" [") + info.unit + "]" : std::string();
    auto* option = cmd.add_option(info.flag, *targets[i], std::string(info.help) + unit);
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

std::array<double, 3> parse_triple(const std::string& text, const std::string& flag) {
  std::array<double, 3> out{};
  std::size_t pos = 0;
  for (int i = 0; i < 3; ++i) {
    const std::size_t comma = i < 2 ? text.find(',', pos) : text.size();
    if (comma == std::string::npos) throw InvalidInput(flag + " '" + text + "': expected three numbers x,y,z");
    const std::string item = text.substr(pos, comma - pos);
    const auto [end, ec] = std::from_chars(item.data(), item.data() + item.size(), out[static_cast<std::size_t>(i)]);
    if (item.empty() || ec != std::errc() || end != item.data() + item.size() || !std::isfinite(out[static_cast<std::size_t>(i)])) {
      throw InvalidInput(flag + " '" + text + "': '" + item + "' is not a finite number");
    }
    pos = comma + 1;
  }
  return out;
}

ModalBasis modal_basis_for(std::shared_ptr<const ElasticBody> body, const std::vector<int>& fixed,
                           const ModalOptions& options, bool no_cache, const std::string& cache_dir, bool& loaded) {
  loaded = false;
  if (no_cache) return ModalBasis::compute(std::move(body), fixed, options);
  const std::filesystem::path dir = cache_dir.empty() ? default_cache_directory() : std::filesystem::path(cache_dir);
  return cached_modal_basis(std::move(body), fixed, options, dir, &loaded);
}

MassKind mass_kind(const std::string& flag) { return flag == "consistent" ? MassKind::Consistent : MassKind::Lumped; }

}  // namespace fissure::cli
