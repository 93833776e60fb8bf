#pragma once
// Flags and helpers of the commands that decode images (analyze, compare). Its own file so that a
// command that reads no image links no image library (docs/architecture.md).

#include "fissure/exemplar/exemplar_analysis.hpp"

#include <CLI/CLI.hpp>

#include <cstdint>
#include <filesystem>

namespace fissure::cli {

/// analyze_exemplar, its refusal of an image above the pixel limit completed with the flag that
/// raises it: "... megapixels (raise it with --max-megapixels)".
ExemplarAnalysis analyze_image(const std::filesystem::path& path, const ExemplarAnalysisOptions& options);

/// --max-megapixels (default 64, finite, in [0.001, 10000]) on every command that decodes images.
void add_max_megapixels_option(CLI::App& cmd, double& max_megapixels);
/// The pixel limit of CrackImageOptions for a --max-megapixels value.
std::int64_t max_pixels(double max_megapixels);

}  // namespace fissure::cli
