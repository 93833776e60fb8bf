#include "fissure/fracture/material_file.hpp"

#include "fissure/base/atomic_file.hpp"
#include "fissure/base/error.hpp"
#include "fissure/base/json_error_text.hpp"
#include "fissure/exemplar/stats_json.hpp"

#include "json_fields.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdlib>
#include <cmath>
#include <cstdint>
#include <set>
#include <system_error>

namespace fissure {
namespace {

using nlohmann::json;

using namespace json_fields;

std::vector<std::string> parameter_keys() {
  std::vector<std::string> keys;
  for (const ParameterInfo& info : fracture_parameter_table()) keys.emplace_back(info.name);
  keys.emplace_back("relaxation");
  return keys;
}

double number_field(const json& object, const std::string& parent, const std::string& key) {
  const json& value = required(object, parent, key);
  if (!value.is_number()) throw FieldError{parent + key + " is " + type_of(value) + ", not a number"};
  const double v = value.get<double>();
  if (!std::isfinite(v)) throw FieldError{parent + key + " is not finite"};
  return v;
}

long long integer_field(const json& object, const std::string& parent, const std::string& key, long long lo, long long hi) {
  const json& value = required(object, parent, key);
  if (!value.is_number_integer()) throw FieldError{parent + key + " is " + type_of(value) + ", not an integer"};
  const long long v = value.is_number_unsigned() && value.get<std::uint64_t>() > static_cast<std::uint64_t>(hi)
                          ? hi + 1
                          : value.get<long long>();
  if (v < lo || v > hi) throw FieldError{parent + key + " " + value.dump() + " is outside [" + std::to_string(lo) + ", " + std::to_string(hi) + "]"};
  return v;
}

std::array<double, 5> five_numbers(const json& value, const std::string& path) {
  if (!value.is_array() || value.size() != 5) throw FieldError{path + " is not an array of 5 numbers"};
  std::array<double, 5> out{};
  for (std::size_t k = 0; k < 5; ++k) {
    if (!value[k].is_number() || !std::isfinite(value[k].get<double>())) throw FieldError{path + "[" + std::to_string(k) + "] is not a finite number"};
    out[k] = value[k].get<double>();
  }
  return out;
}

const std::vector<std::string>& fit_keys() {
  static const std::vector<std::string> keys = {
      "method", "trials", "seed", "error", "error_stddev", "error_seeds", "score", "age", "exemplar", "body",
      "resolution", "load", "supports", "fragment_scale", "posterior"};
  return keys;
}

MaterialFit read_fit(const json& j) {
  const std::string p = "fit.";
  if (!j.is_object()) throw FieldError{"fit is " + type_of(j) + ", not an object"};
  refuse_unknown_keys(j, p, fit_keys());
  MaterialFit f;
  f.method = string_field(required(j, p, "method"), p + "method");
  if (f.method != "paper" && f.method != "smc") throw FieldError{p + "method " + json(f.method).dump() + " is not \"paper\" or \"smc\""};
  f.trials = integer_field(j, p, "trials", 1, 100000000);
  const json& seed = required(j, p, "seed");
  if (!seed.is_number_unsigned() && !(seed.is_number_integer() && seed.get<long long>() >= 0)) throw FieldError{p + "seed is not a non-negative integer"};
  f.seed = seed.get<std::uint64_t>();
  f.error = number_field(j, p, "error");
  f.error_stddev = number_field(j, p, "error_stddev");
  f.error_seeds = static_cast<int>(integer_field(j, p, "error_seeds", 0, 1000));
  f.score = number_field(j, p, "score");
  f.age = number_field(j, p, "age");
  try {
    f.exemplar = pattern_stats_from_json(required(j, p, "exemplar").dump(), "fit.exemplar");
  } catch (const IoError& e) {
    throw FieldError{e.what()};
  }
  const json& body = required(j, p, "body");
  if (!body.is_object()) throw FieldError{p + "body is not an object"};
  refuse_unknown_keys(body, p + "body.", {"width", "height", "thickness", "tets"});
  f.body_width = number_field(body, p + "body.", "width");
  f.body_height = number_field(body, p + "body.", "height");
  f.body_thickness = number_field(body, p + "body.", "thickness");
  f.body_tets = static_cast<int>(integer_field(body, p + "body.", "tets", 1, 100000000));
  const json& res = required(j, p, "resolution");
  if (!res.is_object()) throw FieldError{p + "resolution is not an object"};
  refuse_unknown_keys(res, p + "resolution.", {"tets_per_fragment", "min_tets", "max_tets", "capped", "note"});
  f.tets_per_fragment = static_cast<int>(integer_field(res, p + "resolution.", "tets_per_fragment", 1, 1000000));
  f.min_tets = static_cast<int>(integer_field(res, p + "resolution.", "min_tets", 1, 100000000));
  f.max_tets = static_cast<int>(integer_field(res, p + "resolution.", "max_tets", 1, 100000000));
  const json& capped = required(res, p + "resolution.", "capped");
  if (!capped.is_boolean()) throw FieldError{p + "resolution.capped is not true or false"};
  f.capped = capped.get<bool>();
  f.note = string_field(required(res, p + "resolution.", "note"), p + "resolution.note");
  const json& load = required(j, p, "load");
  if (!load.is_object()) throw FieldError{p + "load is not an object"};
  refuse_unknown_keys(load, p + "load.", {"rule", "grid", "inset", "reference_stress"});
  if (string_field(required(load, p + "load.", "rule"), p + "load.rule") != "uniform-grid") throw FieldError{p + "load.rule is not \"uniform-grid\""};
  f.load_grid = static_cast<int>(integer_field(load, p + "load.", "grid", 1, 32));
  f.load_inset = number_field(load, p + "load.", "inset");
  if (load.contains("reference_stress")) {
    f.load_reference_stress = number_field(load, p + "load.", "reference_stress");
    if (!(f.load_reference_stress > 0.0)) throw FieldError{p + "load.reference_stress is not a positive number"};
  }
  f.supports = string_field(required(j, p, "supports"), p + "supports");
  if (f.supports != "rim-rollers") throw FieldError{p + "supports " + json(f.supports).dump() + " is not \"rim-rollers\""};
  f.fragment_scale = number_field(j, p, "fragment_scale");
  const json& post = required(j, p, "posterior");
  if (!post.is_object()) throw FieldError{p + "posterior is not an object"};
  refuse_unknown_keys(post, p + "posterior.", {"parameters", "mean", "stddev", "samples", "weights"});
  const json& names = required(post, p + "posterior.", "parameters");
  json expected = json::array();
  for (const FitPrior& prior : table3_priors()) expected.push_back(prior.name);
  if (names != expected) throw FieldError{p + "posterior.parameters is not " + expected.dump()};
  f.posterior_mean = five_numbers(required(post, p + "posterior.", "mean"), p + "posterior.mean");
  f.posterior_stddev = five_numbers(required(post, p + "posterior.", "stddev"), p + "posterior.stddev");
  const json& samples = required(post, p + "posterior.", "samples");
  const json& weights = required(post, p + "posterior.", "weights");
  if (!samples.is_array() || !weights.is_array() || samples.size() != weights.size() || samples.empty()) {
    throw FieldError{p + "posterior.samples and weights are not two arrays of one equal, non-zero length"};
  }
  for (std::size_t i = 0; i < samples.size(); ++i) {
    f.samples.push_back(five_numbers(samples[i], p + "posterior.samples[" + std::to_string(i) + "]"));
    if (!weights[i].is_number() || !(weights[i].get<double>() >= 0.0)) throw FieldError{p + "posterior.weights[" + std::to_string(i) + "] is not a number ≥ 0"};
    f.weights.push_back(weights[i].get<double>());
  }
  return f;
}

nlohmann::ordered_json fit_to_json(const MaterialFit& f) {
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  j["method"] = f.method;
  j["trials"] = f.trials;
  j["seed"] = f.seed;
  j["error"] = f.error;
  j["error_stddev"] = f.error_stddev;
  j["error_seeds"] = f.error_seeds;
  j["score"] = f.score;
  j["age"] = f.age;
  j["exemplar"] = nlohmann::ordered_json::parse(pattern_stats_to_json(f.exemplar));
  j["body"] = {{"width", f.body_width}, {"height", f.body_height}, {"thickness", f.body_thickness}, {"tets", f.body_tets}};
  j["resolution"] = {{"tets_per_fragment", f.tets_per_fragment}, {"min_tets", f.min_tets}, {"max_tets", f.max_tets},
                     {"capped", f.capped}, {"note", f.note}};
  j["load"] = {{"rule", "uniform-grid"}, {"grid", f.load_grid}, {"inset", f.load_inset}};
  if (f.load_reference_stress > 0.0) j["load"]["reference_stress"] = f.load_reference_stress;
  j["supports"] = f.supports;
  j["fragment_scale"] = f.fragment_scale;
  nlohmann::ordered_json names = nlohmann::ordered_json::array();
  for (const FitPrior& prior : table3_priors()) names.push_back(prior.name);
  j["posterior"] = {{"parameters", names}, {"mean", f.posterior_mean}, {"stddev", f.posterior_stddev},
                    {"samples", f.samples}, {"weights", f.weights}};
  return j;
}

FractureMaterial read_fields(const json& j, std::vector<std::string>& range_problems) {
  if (!j.is_object()) throw FieldError{"the document is " + type_of(j) + ", not an object"};
  // Schema and version first: a file of another kind or version is named as such, not as a
  // list of missing keys.
  const json& schema = required(j, "", "schema");
  if (schema != kMaterialSchema) {
    throw FieldError{"schema " + schema.dump() + " is not \"" + kMaterialSchema + "\" (not a Fissure material file)"};
  }
  const json& version = required(j, "", "version");
  if (!version.is_number_integer() || version.get<std::int64_t>() < 1 || version.get<std::int64_t>() > kMaterialVersion) {
    throw FieldError{"version " + version.dump() + " is not a supported version (1 to " + std::to_string(kMaterialVersion) + ")"};
  }
  if (version.get<std::int64_t>() == 1) {
    refuse_unknown_keys(j, "", {"schema", "version", "name", "description", "provenance", "parameters"});
  } else {
    refuse_unknown_keys(j, "", {"schema", "version", "name", "description", "provenance", "parameters", "fit"});
  }

  FractureMaterial m;
  m.name = string_field(required(j, "", "name"), "name");
  if (m.name.empty()) throw FieldError{"name is empty"};
  if (j.contains("description")) m.description = string_field(j["description"], "description");
  if (j.contains("provenance")) {
    const json& p = j["provenance"];
    if (!p.is_array()) throw FieldError{"provenance is " + type_of(p) + ", not an array of strings"};
    for (std::size_t i = 0; i < p.size(); ++i) {
      m.provenance.push_back(string_field(p[i], "provenance[" + std::to_string(i) + "]"));
    }
  }

  const json& params = required(j, "", "parameters");
  if (!params.is_object()) throw FieldError{"parameters is " + type_of(params) + ", not an object"};
  refuse_unknown_keys(params, "parameters.", parameter_keys());
  const auto& table = fracture_parameter_table();
  for (std::size_t i = 0; i < table.size(); ++i) {
    const std::string path = std::string("parameters.") + table[i].name;
    const json& value = required(params, "parameters.", table[i].name);
    if (!value.is_number()) throw FieldError{path + " is " + type_of(value) + ", not a number"};
    const double v = value.get<double>();
    parameter_value(m.params, i) = v;
    std::string problem = parameter_problem(table[i], v, path);
    if (!problem.empty()) range_problems.push_back(std::move(problem));
  }
  const json& relaxation = required(params, "parameters.", "relaxation");
  const std::optional<RelaxationChoice> choice =
      relaxation.is_string() ? parse_relaxation_choice(relaxation.get<std::string>()) : std::nullopt;
  if (!choice) {
    throw FieldError{"parameters.relaxation is " + relaxation.dump() + ", not one of " + relaxation_choice_names()};
  }
  m.params.relaxation = *choice;
  if (j.contains("fit")) m.fit = read_fit(j["fit"]);
  return m;
}

std::string material_context(const std::string& name) { return "material " + json(name).dump(); }

}  // namespace

std::string material_to_json(const FractureMaterial& m) {
  if (m.name.empty()) throw InvalidInput("material: the name is empty");
  throw_if_problems(material_context(m.name), m.params.problems());
  // ordered_json: the file lists keys in the table's order, the order a reader expects.
  nlohmann::ordered_json params = nlohmann::ordered_json::object();
  const auto& table = fracture_parameter_table();
  for (std::size_t i = 0; i < table.size(); ++i) params[table[i].name] = parameter_value(m.params, i);
  params["relaxation"] = to_string(m.params.relaxation);
  nlohmann::ordered_json out = nlohmann::ordered_json::object();
  out["schema"] = kMaterialSchema;
  out["version"] = kMaterialVersion;
  out["name"] = m.name;
  out["description"] = m.description;
  out["provenance"] = m.provenance;
  out["parameters"] = std::move(params);
  if (m.fit) out["fit"] = fit_to_json(*m.fit);
  // nlohmann writes doubles in their shortest round-trip form: reading gives the same bits.
  return out.dump(2) + "\n";
}

FractureMaterial material_from_json(const std::string& text, const std::string& source) {
  const std::string bad = source + ": not a valid material file: ";
  json j;
  try {
    j = json::parse(text, RepeatedKeyCheck{});
  } catch (const json::exception& e) {  // parse_error, or out_of_range for a number like 1e999
    throw IoError(bad + json_error_text(e.what()));
  } catch (const FieldError& e) {
    throw IoError(bad + e.text);
  }
  std::vector<std::string> range_problems;
  FractureMaterial m;
  try {
    m = read_fields(j, range_problems);
  } catch (const FieldError& e) {
    throw IoError(bad + e.text);
  }
  throw_if_problems(source + ": " + material_context(m.name), range_problems);
  return m;
}

void save_material(const std::filesystem::path& path, const FractureMaterial& material) {
  const std::string text = material_to_json(material);
  // Read back before writing: material_to_json checks the parameters, the reader every key of
  // a fit record too (a fit with no resolution rule or empty exemplar statistics), and a file
  // Fissure writes must be one it reads.
  material_from_json(text, path.string());
  write_file_atomically(path, text);
}

FractureMaterial load_material(const std::filesystem::path& path) {
  return material_from_json(read_file(path), path.string());
}

std::vector<std::filesystem::path> material_directories() {
  namespace fs = std::filesystem;
  std::vector<fs::path> candidates;
  std::error_code error;
  const fs::path self = fs::read_symlink("/proc/self/exe", error);
  if (!error) {
    // bin/fissure and tests sit one level below the prefix, libexec/fissure/fissure-<command>
    // two.
    const fs::path dir = self.parent_path();
    candidates.push_back(dir.parent_path() / "share" / "fissure" / "materials");
    candidates.push_back(dir.parent_path().parent_path() / "share" / "fissure" / "materials");
  }
  candidates.emplace_back(FISSURE_ASSETS_DIR "/materials");
  // The user library last: a bundled name always means the bundled file.
  if (const char* xdg = std::getenv("XDG_DATA_HOME"); xdg && *xdg) {
    candidates.push_back(fs::path(xdg) / "fissure" / "materials");
  } else if (const char* home = std::getenv("HOME"); home && *home) {
    candidates.push_back(fs::path(home) / ".local" / "share" / "fissure" / "materials");
  }
  std::vector<fs::path> out;
  for (const fs::path& c : candidates) {
    if (fs::is_directory(c, error) && std::find(out.begin(), out.end(), c) == out.end()) out.push_back(c);
  }
  return out;
}

std::vector<std::string> bundled_material_names() {
  namespace fs = std::filesystem;
  std::vector<std::string> names;
  for (const fs::path& dir : material_directories()) {
    std::vector<std::string> here;
    std::error_code error;
    for (const fs::directory_entry& entry : fs::directory_iterator(dir, error)) {
      if (entry.path().extension() == ".json" && entry.is_regular_file(error)) here.push_back(entry.path().stem().string());
    }
    std::sort(here.begin(), here.end());
    for (std::string& name : here)
      if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(std::move(name));
  }
  return names;
}

std::filesystem::path find_material(const std::string& name_or_path) {
  namespace fs = std::filesystem;
  const bool is_path = name_or_path.find('/') != std::string::npos ||
                       (name_or_path.size() >= 5 && name_or_path.ends_with(".json"));
  if (is_path) return name_or_path;
  if (!name_or_path.empty()) {
    for (const fs::path& dir : material_directories()) {
      const fs::path candidate = dir / (name_or_path + ".json");
      std::error_code error;
      if (fs::is_regular_file(candidate, error)) return candidate;
    }
  }
  std::string list;
  for (const std::string& name : bundled_material_names()) list += (list.empty() ? "" : ", ") + name;
  // The names listed are the bundled ones and the user library's (material_directories()).
  throw InvalidInput(material_context(name_or_path) + " is not a file or a known material (known: " +
                     (list.empty() ? std::string("none found") : list) +
                     "; your own go in $XDG_DATA_HOME/fissure/materials)");
}

}  // namespace fissure
