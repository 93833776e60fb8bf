#pragma once
/// The files of a fit: the fitted material (material file version 2), the checkpoint a killed fit
/// resumes from, and the shard files `fissure fit merge` joins.
///
/// FitSettings is everything that decides a fit's result (the exemplar's statistics, the base
/// material, the age, the body and the method's options; not the thread count, the shard or
/// where files go). Its hash keys the checkpoint and ties shards together: a checkpoint or shard
/// of other settings is refused by name, never silently mixed in.
#include "fissure/base/content_hash.hpp"
#include "fissure/exemplar/exemplar_analysis.hpp"
#include "fissure/fit/abc_fit.hpp"
#include "fissure/fracture/material_file.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace fissure {

struct FitSettings {
  std::string exemplar_name;  ///< the image's file name (provenance only)
  PatternStats exemplar;
  double aspect = 1.0;        ///< the exemplar frame's width / height
  FractureMaterial base;
  double age = 3.0;
  FitBodyOptions body;
  FitOptions options;         ///< the method's settings (threads, shard, hooks ignored)
  std::string output_name;    ///< the fitted material's name
};

/// Sets the exemplar's part of `settings` from its analysis: the statistics (through their JSON
/// form, so a merge, which reads them back from shard files, starts from the very same numbers),
/// the frame's aspect, the image's file name and the output name (`name`, or the image's stem).
/// Throws InvalidInput naming `image` when the pattern has fewer than 2 fragments.
void set_fit_exemplar(FitSettings& settings, const ExemplarAnalysis& exemplar, const std::filesystem::path& image,
                      const std::string& name = {});

/// The settings as JSON text (canonical: the hash is of this text) and back. The exemplar's
/// statistics go through pattern_stats_to_json, so a reader gets them bit for bit.
std::string fit_settings_to_json(const FitSettings& settings);
FitSettings fit_settings_from_json(const std::string& text, const std::string& source);
Hash128 fit_settings_hash(const FitSettings& settings);

/// The problem of the settings: the exemplar's statistics, the base with the fit's age and the
/// exemplar's relaxation mode, on the fit body (meshed and tabulated here).
FitProblem make_fit_problem(const FitSettings& settings, int threads, ProgressSink* progress = nullptr,
                            const CancelToken* cancel = nullptr);

/// The fitted material: the base's physical values, the winner's five parameters, the fit's age
/// and relaxation, and the fit record (MaterialFit). Deterministic: the same settings and result
/// give the same bytes.
FractureMaterial fitted_material(const FitSettings& settings, const FitProblem& problem, const FitResult& result);

/// Checkpoint: the finished trials of a fit, written atomically. load_fit_checkpoint throws
/// IoError "<file>: not a valid fit checkpoint: …" for a damaged file and InvalidInput
/// "<file> is a checkpoint of another fit (…)" when its settings differ.
void save_fit_checkpoint(const std::filesystem::path& path, const Hash128& settings, const TrialRecords& trials);
TrialRecords load_fit_checkpoint(const std::filesystem::path& path, const Hash128& settings);

/// A shard's result (`fissure fit --shard K/N`): its settings, K/N and its population.
struct FitShardFile {
  FitSettings settings;
  FitShard shard;
  FitResult result;
};
void save_fit_shard(const std::filesystem::path& path, const FitShardFile& shard);
FitShardFile load_fit_shard(const std::filesystem::path& path);

}  // namespace fissure
