#pragma once
/// PatternStats as JSON: what `fissure analyze --json` writes and `fissure compare` reads, and
/// what a material file will carry as its exemplar's statistics.

#include "fissure/exemplar/pattern_stats.hpp"

#include <filesystem>
#include <string>

namespace fissure {

/// Format version written as "format": readers refuse other versions.
constexpr int kPatternStatsFormat = 1;

std::string pattern_stats_to_json(const PatternStats& stats);
/// Parses JSON written by pattern_stats_to_json. Throws IoError naming `source` for malformed
/// JSON, another format version, or missing or ill-typed fields.
PatternStats pattern_stats_from_json(const std::string& text, const std::string& source);

/// Atomic write / read of a stats file (IoError naming the file).
void save_pattern_stats(const std::filesystem::path& path, const PatternStats& stats);
PatternStats load_pattern_stats(const std::filesystem::path& path);

}  // namespace fissure
