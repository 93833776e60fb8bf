#pragma once
// Pieces shared by the subcommands: material flags read from the parameter table, support and
// load lists, and a stopwatch.

#include "fissure/fem/elastic_material.hpp"
#include "fissure/fem/modal_basis.hpp"

#include <CLI/CLI.hpp>

#include <chrono>
#include <string>
#include <vector>

namespace fissure::cli {

/// Adds --E, --nu, --rho to `cmd` from elastic_material_parameters(); `required` per flag name.
void add_material_options(CLI::App& cmd, ElasticMaterial& material, bool require_density);

/// Throws InvalidInput naming the flag ("--nu 0.6 is outside [0, 0.5)") for an out-of-range value.
void validate_material_flags(const ElasticMaterial& material);

/// Parses "a,b,c" into three finite numbers; throws InvalidInput naming `flag`.
std::array<double, 3> parse_triple(const std::string& text, const std::string& flag);

/// The modal basis for a CLI command: from the cache in `cache_dir` (empty: the default cache
/// directory) unless `no_cache`; `loaded` tells whether it came from the cache.
ModalBasis modal_basis_for(std::shared_ptr<const ElasticBody> body, const std::vector<int>& fixed,
                           const ModalOptions& options, bool no_cache, const std::string& cache_dir, bool& loaded);

/// "lumped" or "consistent" (the --mass flag) as a MassKind.
MassKind mass_kind(const std::string& flag);

class Stopwatch {
public:
  double milliseconds() const {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - m_start).count();
  }

private:
  std::chrono::steady_clock::time_point m_start = std::chrono::steady_clock::now();
};

}  // namespace fissure::cli
