#include "fissure/exemplar/stats_json.hpp"

#include "fissure/base/atomic_file.hpp"
#include "fissure/base/error.hpp"
#include "fissure/base/json_error_text.hpp"
#include "fissure/base/number_text.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <limits>

namespace fissure {
namespace {

using nlohmann::json;

json histogram_json(const Histogram& h) { return json{{"edges", h.edges}, {"p", h.p}}; }

// A field's failure: "<key path>: <what is wrong>", turned into one IoError naming the file.
struct FieldError {
  std::string text;
};

std::string path_of(const std::string& parent, const std::string& key) { return parent.empty() ? key : parent + "." + key; }

const json& field(const json& object, const std::string& parent, const std::string& key) {
  if (!object.is_object()) throw FieldError{(parent.empty() ? std::string("the document") : parent) + " is not an object"};
  const auto it = object.find(key);
  if (it == object.end()) throw FieldError{"missing key " + path_of(parent, key)};
  return *it;
}

double number(const json& value, const std::string& path) {
  if (!value.is_number()) throw FieldError{path + " is " + std::string(value.type_name()) + ", not a number"};
  const double v = value.get<double>();
  if (!std::isfinite(v)) throw FieldError{path + " is not finite"};
  return v;
}

double non_negative(const json& value, const std::string& path) {
  const double v = number(value, path);
  if (v < 0.0) throw FieldError{path + " is " + format_number(v) + ", negative"};
  return v;
}

int count(const json& value, const std::string& path) {
  if (!value.is_number_integer()) throw FieldError{path + " is " + (value.is_number() ? value.dump() : std::string(value.type_name())) + ", not an integer"};
  const auto v = value.get<std::int64_t>();
  if (v < 0 || v > std::numeric_limits<int>::max()) throw FieldError{path + " is " + std::to_string(v) + ", not a count"};
  return static_cast<int>(v);
}

// Optional fields: absent means the default, present means checked like a required one.
double optional_non_negative(const json& object, const std::string& parent, const std::string& key, double fallback) {
  return object.contains(key) ? non_negative(object.at(key), path_of(parent, key)) : fallback;
}
int optional_count(const json& object, const std::string& parent, const std::string& key) {
  return object.contains(key) ? count(object.at(key), path_of(parent, key)) : 0;
}

std::vector<double> non_negative_list(const json& value, const std::string& path) {
  if (!value.is_array()) throw FieldError{path + " is " + std::string(value.type_name()) + ", not an array"};
  std::vector<double> out;
  out.reserve(value.size());
  for (std::size_t i = 0; i < value.size(); ++i) out.push_back(non_negative(value[i], path + "[" + std::to_string(i) + "]"));
  return out;
}

// Equal-width bins with increasing finite edges and a unit (or zero) mass of non-negative p.
Histogram histogram_from(const json& object, const std::string& parent, const std::string& key) {
  const std::string path = path_of(parent, key);
  const json& j = field(object, parent, key);
  Histogram h;
  const json& edges = field(j, path, "edges");
  if (!edges.is_array()) throw FieldError{path + ".edges is " + std::string(edges.type_name()) + ", not an array"};
  for (std::size_t i = 0; i < edges.size(); ++i) h.edges.push_back(number(edges[i], path + ".edges[" + std::to_string(i) + "]"));
  h.p = non_negative_list(field(j, path, "p"), path + ".p");
  if (h.p.empty() || h.edges.size() != h.p.size() + 1) {
    throw FieldError{path + " has " + std::to_string(h.edges.size()) + " edges for " + std::to_string(h.p.size()) +
                     " bins (needs bins + 1, at least one bin)"};
  }
  // Equal widths to 1e-9 of the range: the edges are written with full precision, and EMD and
  // binning both assume one width.
  const double range = h.edges.back() - h.edges.front();
  const double width = range / static_cast<double>(h.p.size());
  for (std::size_t i = 1; i < h.edges.size(); ++i) {
    if (!(h.edges[i] > h.edges[i - 1])) throw FieldError{path + ".edges are not increasing at index " + std::to_string(i)};
    if (std::abs(h.edges[i] - h.edges[i - 1] - width) > 1e-9 * range) {
      throw FieldError{path + ".edges are not equally spaced at index " + std::to_string(i)};
    }
  }
  // A unit mass to 1e-4: Fissure writes p to full precision (sum off by round-off only), and a
  // file from another tool with 6-decimal p (the shared reference statistics) is off by at most
  // 36 bins × 5e-7 = 1.8e-5.
  const double total = h.total();
  if (total != 0.0 && std::abs(total - 1.0) > 1e-4) {
    throw FieldError{path + ".p sums to " + format_number(total) + ", not 1 (or 0 for an empty histogram)"};
  }
  return h;
}

}  // namespace

std::string pattern_stats_to_json(const PatternStats& s) {
  json junctions = json::array();
  for (const JunctionStat& j : s.junctions) {
    junctions.push_back({{"x", j.position.x()}, {"y", j.position.y()}, {"degree", j.degree}, {"type", to_string(j.type)},
                         {"angle_deg", j.angle_deg}, {"gaps_deg", j.gaps_deg}});
  }
  const json out{
      {"format", kPatternStatsFormat},
      {"source", s.source},
      {"total_area", s.total_area},
      {"crack_width", s.crack_width},
      {"fragments", {{"count", s.fragment_count}, {"touching_border", s.fragments_touching_border},
                     {"areas", s.fragment_areas}, {"histogram_log10_area", histogram_json(s.fragment_area_hist)}}},
      {"cracks", {{"count", s.crack_count}, {"total_length", s.total_crack_length}, {"lengths", s.crack_lengths},
                  {"histogram_log10_length", histogram_json(s.crack_length_hist)}}},
      {"junctions", {{"count", s.junction_count}, {"density", s.junction_density},
                     {"histogram_log10_1p_local_density", histogram_json(s.junction_density_hist)},
                     {"t", s.t_count}, {"y", s.y_count}, {"x", s.x_count},
                     {"mean_angle_deg", s.mean_junction_angle_deg},
                     {"histogram_gap_deg", histogram_json(s.junction_angle_hist)},
                     {"relaxation_mode", s.relaxation_mode == RelaxationMode::Directional ? "directional" : "isotropic"},
                     {"list", junctions}}},
      {"ends", {{"interior", s.end_count}, {"border", s.border_end_count}}},
  };
  return out.dump(1);
}

namespace {

PatternStats read_fields(const json& j, const std::string& source) {
  PatternStats s;
  const json& format = field(j, "", "format");
  if (!format.is_number_integer() || format.get<std::int64_t>() != kPatternStatsFormat) {
    throw FieldError{"format " + format.dump() + " is not the supported version " + std::to_string(kPatternStatsFormat)};
  }
  if (j.contains("source")) {
    if (!j["source"].is_string()) throw FieldError{"source is " + std::string(j["source"].type_name()) + ", not a string"};
    s.source = j["source"].get<std::string>();
  } else {
    s.source = source;
  }
  s.total_area = non_negative(field(j, "", "total_area"), "total_area");
  if (!(s.total_area > 0.0)) throw FieldError{"total_area is 0, not positive"};
  s.crack_width = optional_non_negative(j, "", "crack_width", 0.0);

  const json& f = field(j, "", "fragments");
  s.fragment_count = count(field(f, "fragments", "count"), "fragments.count");
  s.fragments_touching_border = optional_count(f, "fragments", "touching_border");
  s.fragment_areas = non_negative_list(field(f, "fragments", "areas"), "fragments.areas");
  if (static_cast<std::size_t>(s.fragment_count) != s.fragment_areas.size()) {
    throw FieldError{"fragments.count is " + std::to_string(s.fragment_count) + " but fragments.areas lists " +
                     std::to_string(s.fragment_areas.size())};
  }
  s.fragment_area_hist = histogram_from(f, "fragments", "histogram_log10_area");

  const json& c = field(j, "", "cracks");
  s.crack_count = count(field(c, "cracks", "count"), "cracks.count");
  s.total_crack_length = optional_non_negative(c, "cracks", "total_length", 0.0);
  s.crack_lengths = non_negative_list(field(c, "cracks", "lengths"), "cracks.lengths");
  if (static_cast<std::size_t>(s.crack_count) != s.crack_lengths.size()) {
    throw FieldError{"cracks.count is " + std::to_string(s.crack_count) + " but cracks.lengths lists " +
                     std::to_string(s.crack_lengths.size())};
  }
  s.crack_length_hist = histogram_from(c, "cracks", "histogram_log10_length");

  const json& k = field(j, "", "junctions");
  s.junction_count = count(field(k, "junctions", "count"), "junctions.count");
  s.junction_density = non_negative(field(k, "junctions", "density"), "junctions.density");
  s.junction_density_hist = histogram_from(k, "junctions", "histogram_log10_1p_local_density");
  s.t_count = optional_count(k, "junctions", "t");
  s.y_count = optional_count(k, "junctions", "y");
  s.x_count = optional_count(k, "junctions", "x");
  s.mean_junction_angle_deg = optional_non_negative(k, "junctions", "mean_angle_deg", 0.0);
  if (s.mean_junction_angle_deg > 360.0) {
    throw FieldError{"junctions.mean_angle_deg is " + format_number(s.mean_junction_angle_deg) + ", above 360"};
  }
  if (k.contains("histogram_gap_deg")) s.junction_angle_hist = histogram_from(k, "junctions", "histogram_gap_deg");
  if (k.contains("relaxation_mode")) {
    const json& mode = k["relaxation_mode"];
    if (mode != "directional" && mode != "isotropic") {
      throw FieldError{"junctions.relaxation_mode is " + mode.dump() + ", not \"directional\" or \"isotropic\""};
    }
    s.relaxation_mode = mode == "directional" ? RelaxationMode::Directional : RelaxationMode::Isotropic;
  }
  if (j.contains("ends")) {
    const json& e = j["ends"];
    s.end_count = optional_count(e, "ends", "interior");
    s.border_end_count = optional_count(e, "ends", "border");
  }
  return s;
}

}  // namespace

PatternStats pattern_stats_from_json(const std::string& text, const std::string& source) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {  // parse_error, or out_of_range for a number like 1e999
    throw IoError(source + ": not valid pattern statistics JSON: " + json_error_text(e.what()));
  }
  try {
    return read_fields(j, source);
  } catch (const FieldError& e) {
    throw IoError(source + ": not valid pattern statistics JSON: " + e.text);
  }
}

void save_pattern_stats(const std::filesystem::path& path, const PatternStats& stats) {
  write_file_atomically(path, pattern_stats_to_json(stats) + "\n");
}

PatternStats load_pattern_stats(const std::filesystem::path& path) {
  return pattern_stats_from_json(read_file(path), path.string());
}

}  // namespace fissure
