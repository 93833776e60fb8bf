#pragma once
// Pieces shared by the subcommands: material flags read from the parameter table, the modal
// basis with its cache, image analysis with the CLI's hints, and a stopwatch.

#include "fissure/exemplar/exemplar_analysis.hpp"
#include "fissure/fem/elastic_material.hpp"
#include "fissure/fem/modal_basis.hpp"

#include "terminal_progress.hpp"

#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
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

/// analyze_exemplar, its refusal of an image above the pixel limit completed with the flag that
/// raises it: "... megapixels (raise it with --max-megapixels)".
ExemplarAnalysis analyze_image(const std::filesystem::path& path, const ExemplarAnalysisOptions& options);

/// --max-megapixels (default 64, finite, in [0.001, 10000]) on every command that decodes images.
void add_max_megapixels_option(CLI::App& cmd, double& max_megapixels);
/// The pixel limit of CrackImageOptions for a --max-megapixels value.
std::int64_t max_pixels(double max_megapixels);

/// --threads N (1–1024) on every command and on `fissure` itself: sets fissure::set_thread_count
/// while parsing, so assembly, CHOLMOD, OpenBLAS and every later parallel loop use N threads.
/// Default: $FISSURE_THREADS, else the hardware threads. Results are identical at any count.
void add_threads_option(CLI::App& cmd);

/// Where a command's summary goes: stdout, unless a result is written to stdout ("-").
std::FILE* summary_stream(const std::string& output);

class Stopwatch {
public:
  double milliseconds() const {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - m_start).count();
  }

private:
  std::chrono::steady_clock::time_point m_start = std::chrono::steady_clock::now();
};

}  // namespace fissure::cli
