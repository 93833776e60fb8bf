#include "fissure/fit/fit_files.hpp"

#include "fissure/base/atomic_file.hpp"
#include "fissure/base/error.hpp"
#include "fissure/base/json_error_text.hpp"
#include "fissure/base/number_text.hpp"
#include "fissure/exemplar/stats_json.hpp"
#include "fissure/fracture/fitted_transfer.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace fissure {

namespace {

using ojson = nlohmann::ordered_json;
using json = nlohmann::json;

constexpr const char* kSettingsSchema = "fissure-fit-settings";
constexpr const char* kCheckpointSchema = "fissure-fit-checkpoint";
constexpr const char* kShardSchema = "fissure-fit-shard";

ojson settings_object(const FitSettings& s) {
  ojson j = ojson::object();
  j["schema"] = kSettingsSchema;
  // 2: SMC re-scores generation 0 and ends with a race (smc_race_share).
  j["version"] = 2;
  j["exemplar_name"] = s.exemplar_name;
  j["exemplar"] = ojson::parse(pattern_stats_to_json(s.exemplar));
  j["aspect"] = s.aspect;
  j["base"] = ojson::parse(material_to_json(s.base));
  j["age"] = s.age;
  const FitBodyOptions& b = s.body;
  ojson body = {{"long_side", b.long_side}, {"thickness", b.thickness}};
  body["tile"] = b.tile ? ojson::array({b.tile->width, b.tile->height, b.tile->thickness}) : ojson(nullptr);
  body["tets"] = b.tets;
  body["tets_per_fragment"] = b.tets_per_fragment;
  body["min_tets"] = b.min_tets;
  body["max_tets"] = b.max_tets;
  body["load_grid"] = b.load_grid;
  body["load_inset"] = b.load_inset;
  j["body"] = body;
  const FitOptions& o = s.options;
  j["method"] = {{"method", to_string(o.method)}, {"trials", o.trials}, {"seed", o.seed},
                 {"population", o.population_size()}, {"block", o.block}, {"evaluation_seeds", o.evaluation_seeds},
                 {"smc_seeds", o.smc_seeds}, {"smc_quantile", o.smc_quantile},
                 {"smc_min_acceptance", o.smc_min_acceptance}, {"smc_race_share", o.smc_race_share}};
  j["output_name"] = s.output_name;
  return j;
}

FitSettings settings_from(const json& j, const std::string& source) {
  if (j.at("schema") != kSettingsSchema || j.at("version") != 2) throw IoError(source + ": fit settings of another kind or version");
  FitSettings s;
  s.exemplar_name = j.at("exemplar_name").get<std::string>();
  s.exemplar = pattern_stats_from_json(j.at("exemplar").dump(), source + " (exemplar)");
  s.aspect = j.at("aspect").get<double>();
  s.base = material_from_json(j.at("base").dump(), source + " (base material)");
  s.age = j.at("age").get<double>();
  const json& b = j.at("body");
  s.body.long_side = b.at("long_side").get<double>();
  s.body.thickness = b.at("thickness").get<double>();
  if (!b.at("tile").is_null()) {
    const auto t = b.at("tile").get<std::vector<double>>();
    if (t.size() != 3) throw IoError(source + ": body.tile is not W,H,T");
    s.body.tile = TileSpec{t[0], t[1], t[2]};
  }
  s.body.tets = b.at("tets").get<int>();
  s.body.tets_per_fragment = b.at("tets_per_fragment").get<int>();
  s.body.min_tets = b.at("min_tets").get<int>();
  s.body.max_tets = b.at("max_tets").get<int>();
  s.body.load_grid = b.at("load_grid").get<int>();
  s.body.load_inset = b.at("load_inset").get<double>();
  const json& m = j.at("method");
  const auto method = parse_fit_method(m.at("method").get<std::string>());
  if (!method) throw IoError(source + ": method.method is not paper or smc");
  s.options.method = *method;
  s.options.trials = m.at("trials").get<long long>();
  s.options.seed = m.at("seed").get<std::uint64_t>();
  s.options.population = m.at("population").get<int>();
  s.options.block = m.at("block").get<int>();
  s.options.evaluation_seeds = m.at("evaluation_seeds").get<int>();
  s.options.smc_seeds = m.at("smc_seeds").get<int>();
  s.options.smc_quantile = m.at("smc_quantile").get<double>();
  s.options.smc_min_acceptance = m.at("smc_min_acceptance").get<double>();
  s.options.smc_race_share = m.at("smc_race_share").get<double>();
  s.output_name = j.at("output_name").get<std::string>();
  const auto problems = s.options.problems();
  if (!problems.empty()) throw IoError(source + ": " + problems.front());
  const auto body_problems = s.body.problems();
  if (!body_problems.empty()) throw IoError(source + ": " + body_problems.front());
  return s;
}

// Parses `text` as JSON, turning every nlohmann error into one IoError naming the file.
template <class F>
auto parse_file(const std::string& text, const std::string& what, const std::filesystem::path& path, F&& read) {
  const std::string bad = path.string() + ": not a valid " + what + ": ";
  try {
    return read(json::parse(text));
  } catch (const json::exception& e) {
    throw IoError(bad + json_error_text(e.what()));
  }
}

}  // namespace

std::string fit_settings_to_json(const FitSettings& settings) { return settings_object(settings).dump(); }

FitSettings fit_settings_from_json(const std::string& text, const std::string& source) {
  return parse_file(text, "fit settings", source, [&](const json& j) { return settings_from(j, source); });
}

void set_fit_exemplar(FitSettings& settings, const ExemplarAnalysis& exemplar, const std::filesystem::path& image,
                      const std::string& name) {
  const int fragments = exemplar.stats.fragment_count;
  if (fragments < 2) {
    throw InvalidInput(image.string() + ": the traced image has " + std::to_string(fragments) + " fragment" +
                       (fragments == 1 ? "" : "s") + "; a fit needs a crack pattern that splits it into at least 2");
  }
  settings.exemplar = pattern_stats_from_json(pattern_stats_to_json(exemplar.stats), image.string());
  const Eigen::Vector2d frame = exemplar.graph.frame_max - exemplar.graph.frame_min;
  settings.aspect = frame.x() / frame.y();
  settings.exemplar_name = image.filename().string();
  settings.output_name = name.empty() ? image.stem().string() : name;
}

Hash128 fit_settings_hash(const FitSettings& settings) {
  return ContentHasher().add(std::string_view("fissure-fit-settings-2")).add(fit_settings_to_json(settings)).finish();
}

FitProblem make_fit_problem(const FitSettings& settings, int threads, ProgressSink* progress, const CancelToken* cancel) {
  FractureParams base = settings.base.params;
  if (!(settings.age > 0.0) || !std::isfinite(settings.age)) throw InvalidInput("--age " + format_number(settings.age) + " is not positive");
  base.age = settings.age;
  // The paper's rule (§5.2): Eq. 3 when the exemplar's mean junction angle is in [75°, 90°].
  base.relaxation = relaxation_mode_for(settings.exemplar.mean_junction_angle_deg) == RelaxationMode::Directional
                        ? RelaxationChoice::Directional
                        : RelaxationChoice::Isotropic;
  base.junction_density = settings.exemplar.junction_density;
  const FitBodyPlan plan = plan_fit_body(settings.exemplar.fragment_count, settings.aspect, settings.body);
  auto body = std::make_shared<const FitBody>(plan, settings.body, base.elastic(), threads, progress, cancel);
  return make_fit_problem(settings.exemplar, base, std::move(body));
}

FractureMaterial fitted_material(const FitSettings& settings, const FitProblem& problem, const FitResult& result) {
  FractureMaterial m;
  m.name = settings.output_name;
  m.params = result.params;
  const auto f = [](double x) { return format_number(x, 4); };
  m.description = "Fitted by fissure fit to " + settings.exemplar_name + " (" + to_string(result.method) + ", " +
                  std::to_string(settings.options.trials) + " trials): Eq. 5 error " + f(result.error_mean) + " +- " +
                  f(result.error_stddev) + " over " + std::to_string(result.evaluation_errors.size()) + " fresh seeds";
  m.provenance = settings.base.provenance;
  m.provenance.push_back("Physical values and noise from the base material \"" + settings.base.name +
                         "\"; dσ_e, r_relax, v_relax, R_cvar and l fitted by ABC (paper §6) to the exemplar " +
                         settings.exemplar_name + " on a " + format_number(problem.body->plan().tile.width) + " x " +
                         format_number(problem.body->plan().tile.height) + " x " +
                         format_number(problem.body->plan().tile.thickness) + " m tile");
  MaterialFit fit;
  fit.method = to_string(result.method);
  fit.trials = settings.options.trials;
  fit.seed = settings.options.seed;
  fit.error = result.error_mean;
  fit.error_stddev = result.error_stddev;
  fit.error_seeds = static_cast<int>(result.evaluation_errors.size());
  fit.score = result.best.error;
  fit.exemplar = settings.exemplar;
  fit.age = settings.age;
  const FitBodyPlan& plan = problem.body->plan();
  fit.body_width = plan.tile.width;
  fit.body_height = plan.tile.height;
  fit.body_thickness = plan.tile.thickness;
  fit.body_tets = plan.tets;
  fit.tets_per_fragment = settings.body.tets_per_fragment;
  fit.min_tets = settings.body.min_tets;
  fit.max_tets = settings.body.max_tets;
  fit.capped = plan.capped;
  fit.note = plan.note;
  fit.fragment_scale = problem.box.fragment_scale;
  fit.load_grid = settings.body.load_grid;
  fit.load_inset = settings.body.load_inset;
  {
    // The stress the fitted l = 1 puts in the fit body, so another body's load keeps it.
    const PreparedBody& prepared = problem.body->prepared();
    fit.load_reference_stress = reference_stress_per_newton(prepared) *
                                prepared.fracture_body().mass(problem.base.density) * kStandardGravity;
  }
  fit.supports = "rim-rollers";
  for (std::size_t k = 0; k < kFitDimensions; ++k) {
    const double span = problem.box.hi[k] - problem.box.lo[k];
    fit.posterior_mean[k] = problem.box.lo[k] + result.posterior_mean[k] * span;
    fit.posterior_stddev[k] = result.posterior_stddev[k] * span;
  }
  for (const Particle& q : result.population) {
    const FractureParams p = problem.box.params_at(problem.base, q.u);
    std::array<double, 5> v{};
    for (std::size_t k = 0; k < kFitDimensions; ++k) v[k] = parameter_value(p, problem.box.row[k]);
    fit.samples.push_back(v);
    fit.weights.push_back(q.weight);
  }
  m.fit = std::move(fit);
  return m;
}

void save_fit_checkpoint(const std::filesystem::path& path, const Hash128& settings, const TrialRecords& trials) {
  std::vector<TrialRecord> sorted;
  sorted.reserve(trials.size());
  for (const auto& [key, record] : trials) sorted.push_back(record);
  std::sort(sorted.begin(), sorted.end(), [](const TrialRecord& a, const TrialRecord& b) { return a.key < b.key; });
  std::string text = "{\"schema\":\"" + std::string(kCheckpointSchema) + "\",\"version\":1,\"settings\":\"" + settings.hex() +
                     "\",\"trials\":[";
  for (std::size_t i = 0; i < sorted.size(); ++i) {
    const TrialRecord& r = sorted[i];
    text += (i ? ",[" : "[") + std::to_string(r.key) + "," + (std::isfinite(r.error) ? ojson(r.error).dump() : "null") + "," +
            std::to_string(r.fragments) + "]";
  }
  text += "]}\n";
  write_file_atomically(path, text);
}

TrialRecords load_fit_checkpoint(const std::filesystem::path& path, const Hash128& settings) {
  const std::string text = read_file(path);
  return parse_file(text, "fit checkpoint", path, [&](const json& j) {
    if (!j.is_object() || j.value("schema", "") != kCheckpointSchema) {
      throw IoError(path.string() + ": not a valid fit checkpoint: the schema is not " + kCheckpointSchema);
    }
    if (j.at("version") != 1) throw IoError(path.string() + ": not a valid fit checkpoint: version " + j.at("version").dump());
    if (j.at("settings").get<std::string>() != settings.hex()) {
      throw InvalidInput(path.string() + " is a checkpoint of another fit (other image, material or options); "
                         "delete it or drop --resume to start afresh");
    }
    TrialRecords out;
    for (const json& t : j.at("trials")) {
      if (!t.is_array() || t.size() != 3) throw IoError(path.string() + ": not a valid fit checkpoint: a trial is not [key, error, fragments]");
      TrialRecord r;
      r.key = t[0].get<std::uint64_t>();
      r.error = t[1].is_null() ? std::numeric_limits<double>::infinity() : t[1].get<double>();
      if (!(r.error >= 0.0)) throw IoError(path.string() + ": not a valid fit checkpoint: trial " + std::to_string(r.key) + " has a negative error");
      r.fragments = t[2].get<int>();
      out[r.key] = r;
    }
    return out;
  });
}

void save_fit_shard(const std::filesystem::path& path, const FitShardFile& shard) {
  ojson j = ojson::object();
  j["schema"] = kShardSchema;
  j["version"] = 1;
  j["settings"] = settings_object(shard.settings);
  j["shard"] = {shard.shard.index, shard.shard.count};
  j["trials"] = shard.result.trials;
  j["rejected"] = shard.result.rejected;
  ojson population = ojson::array();
  for (const Particle& q : shard.result.population) {
    population.push_back({q.key, q.error, q.u[0], q.u[1], q.u[2], q.u[3], q.u[4]});
  }
  j["population"] = population;
  write_file_atomically(path, j.dump(1) + "\n");
}

FitShardFile load_fit_shard(const std::filesystem::path& path) {
  const std::string text = read_file(path);
  return parse_file(text, "fit shard", path, [&](const json& j) {
    if (!j.is_object() || j.value("schema", "") != kShardSchema) {
      throw IoError(path.string() + ": not a valid fit shard: the schema is not " + kShardSchema +
                    " (give the files written by fissure fit --shard K/N)");
    }
    FitShardFile f;
    f.settings = settings_from(j.at("settings"), path.string());
    const auto k = j.at("shard").get<std::vector<int>>();
    if (k.size() != 2 || k[0] < 1 || k[0] > k[1]) throw IoError(path.string() + ": not a valid fit shard: shard is not [K, N]");
    f.shard = {k[0], k[1]};
    f.result.method = FitMethod::Paper;
    f.result.trials = j.at("trials").get<long long>();
    f.result.rejected = j.at("rejected").get<long long>();
    for (const json& q : j.at("population")) {
      if (!q.is_array() || q.size() != 7) throw IoError(path.string() + ": not a valid fit shard: a particle is not [key, error, u×5]");
      Particle p;
      p.key = q[0].get<std::uint64_t>();
      p.error = q[1].get<double>();
      for (std::size_t d = 0; d < kFitDimensions; ++d) p.u[d] = q[2 + d].get<double>();
      f.result.population.push_back(p);
    }
    return f;
  });
}

}  // namespace fissure
