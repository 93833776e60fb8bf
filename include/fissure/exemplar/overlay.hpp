#pragma once
/// A picture of what the analysis saw, drawn over the tracing: fragments in colours, the
/// skeleton, cracks, junctions by type (T red, Y blue, X magenta), free ends (yellow) and ends
/// on the border (green). For checking an exemplar by eye.

#include "fissure/exemplar/exemplar_analysis.hpp"

#include <filesystem>

namespace fissure {

/// Writes a PNG (atomically), scaled up by an integer factor so the short side is at least
/// `min_side` pixels. Throws IoError naming the file when it cannot be written.
void write_overlay(const std::filesystem::path& path, const ExemplarAnalysis& analysis, int min_side = 768);

}  // namespace fissure
