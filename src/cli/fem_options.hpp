#pragma once
// Flags and helpers of the commands that solve (solve, modes): material flags read from the
// parameter table and the modal basis with its cache. Its own file so that a command that does not
// solve links no sparse solver (each command is its own executable: docs/architecture.md).

#include "fissure/fem/elastic_material.hpp"
#include "fissure/fem/modal_basis.hpp"

#include "terminal_progress.hpp"

#include <CLI/CLI.hpp>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace fissure::cli {

/// Adds --E, --nu, --rho to `cmd` from elastic_material_parameters(); `required` per flag name.
/// Each refuses a non-finite value while parsing; the ranges are checked by validate_material_flags.
void add_material_options(CLI::App& cmd, ElasticMaterial& material, bool require_density);

/// Throws InvalidInput naming the flag ("--nu 0.6 is outside [0, 0.5)") for an out-of-range value.
void validate_material_flags(const ElasticMaterial& material);

/// The modal basis for a CLI command: from the cache in `cache_dir` (empty: the default cache
/// directory) unless `no_cache`; `loaded` tells whether it came from the cache. A cache directory
/// that cannot be written is said once on stderr ("fissure: warning: cannot write the modal cache
/// in DIR: reason; continuing without it") and the basis is computed anyway.
ModalBasis modal_basis_for(std::shared_ptr<const ElasticBody> body, const std::vector<int>& fixed,
                           const ModalOptions& options, bool no_cache, const std::string& cache_dir, bool& loaded,
                           TerminalProgress& progress, const CancelToken* cancel);

/// "lumped" or "consistent" (the --mass flag) as a MassKind.
MassKind mass_kind(const std::string& flag);

}  // namespace fissure::cli
