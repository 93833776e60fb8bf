#include "fissure/exemplar/stats_json.hpp"

#include "fissure/base/atomic_file.hpp"
#include "fissure/base/error.hpp"

#include <nlohmann/json.hpp>

namespace fissure {
namespace {

using nlohmann::json;

json histogram_json(const Histogram& h) { return json{{"edges", h.edges}, {"p", h.p}}; }

Histogram histogram_from(const json& j) {
  Histogram h;
  h.edges = j.at("edges").get<std::vector<double>>();
  h.p = j.at("p").get<std::vector<double>>();
  if (h.edges.size() != h.p.size() + 1 || h.p.empty()) throw std::runtime_error("histogram edges and p disagree");
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

PatternStats pattern_stats_from_json(const std::string& text, const std::string& source) {
  PatternStats s;
  try {
    const json j = json::parse(text);
    const int format = j.at("format").get<int>();
    if (format != kPatternStatsFormat) {
      throw IoError(source + ": pattern statistics format " + std::to_string(format) + ", expected " +
                    std::to_string(kPatternStatsFormat));
    }
    s.source = j.value("source", source);
    s.total_area = j.at("total_area").get<double>();
    s.crack_width = j.value("crack_width", 0.0);
    const json& f = j.at("fragments");
    s.fragment_count = f.at("count").get<int>();
    s.fragments_touching_border = f.value("touching_border", 0);
    s.fragment_areas = f.at("areas").get<std::vector<double>>();
    s.fragment_area_hist = histogram_from(f.at("histogram_log10_area"));
    const json& c = j.at("cracks");
    s.crack_count = c.at("count").get<int>();
    s.total_crack_length = c.value("total_length", 0.0);
    s.crack_lengths = c.at("lengths").get<std::vector<double>>();
    s.crack_length_hist = histogram_from(c.at("histogram_log10_length"));
    const json& k = j.at("junctions");
    s.junction_count = k.at("count").get<int>();
    s.junction_density = k.at("density").get<double>();
    s.junction_density_hist = histogram_from(k.at("histogram_log10_1p_local_density"));
    s.t_count = k.value("t", 0);
    s.y_count = k.value("y", 0);
    s.x_count = k.value("x", 0);
    s.mean_junction_angle_deg = k.value("mean_angle_deg", 0.0);
    if (k.contains("histogram_gap_deg")) s.junction_angle_hist = histogram_from(k.at("histogram_gap_deg"));
    s.relaxation_mode = k.value("relaxation_mode", std::string("isotropic")) == "directional" ? RelaxationMode::Directional
                                                                                            : RelaxationMode::Isotropic;
    if (j.contains("ends")) {
      s.end_count = j["ends"].value("interior", 0);
      s.border_end_count = j["ends"].value("border", 0);
    }
  } catch (const IoError&) {
    throw;
  } catch (const std::exception& e) {
    throw IoError(source + ": not valid pattern statistics JSON: " + e.what());
  }
  return s;
}

void save_pattern_stats(const std::filesystem::path& path, const PatternStats& stats) {
  write_file_atomically(path, pattern_stats_to_json(stats) + "\n");
}

PatternStats load_pattern_stats(const std::filesystem::path& path) {
  return pattern_stats_from_json(read_file(path), path.string());
}

}  // namespace fissure
