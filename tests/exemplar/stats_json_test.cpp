// pattern_stats_from_json refuses what it cannot use, naming the file and the JSON key path.

#include "fissure/base/error.hpp"
#include "fissure/exemplar/exemplar_analysis.hpp"
#include "fissure/exemplar/similarity.hpp"
#include "fissure/exemplar/stats_json.hpp"

#include "drawings.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

namespace fissure {
namespace {

nlohmann::json valid_stats() {
  static const std::string text = pattern_stats_to_json(
      analyze_crack_mask(crack_mask_from_grey(test::to_grey_image(test::brick_drawing(240, 40, 2)), {}, "bricks")).stats);
  return nlohmann::json::parse(text);
}

std::string io_error_of(const std::string& text) {
  try {
    pattern_stats_from_json(text, "stats.json");
  } catch (const IoError& e) {
    return e.what();
  }
  return "accepted";
}

// Used to be accepted: negative histogram values made the fragment EMD 1.25, outside its
// documented [0, 1).
TEST(StatsJson, NegativeHistogramIsRefused) {
  nlohmann::json j = valid_stats();
  auto& p = j["fragments"]["histogram_log10_area"]["p"];
  for (auto& v : p) v = 0.0;
  p[0] = -0.25;
  p[23] = 1.25;
  EXPECT_EQ(io_error_of(j.dump()),
            "stats.json: not valid pattern statistics JSON: fragments.histogram_log10_area.p[0] is -0.25, negative");
}

TEST(StatsJson, EveryFieldIsChecked) {
  struct Case {
    const char* expected;
    void (*spoil)(nlohmann::json&);
  };
  const Case cases[] = {
      {"missing key total_area", [](nlohmann::json& j) { j.erase("total_area"); }},
      {"total_area is 0, not positive", [](nlohmann::json& j) { j["total_area"] = 0; }},
      {"total_area is string, not a number", [](nlohmann::json& j) { j["total_area"] = "big"; }},
      {"fragments.count is 2.5, not an integer", [](nlohmann::json& j) { j["fragments"]["count"] = 2.5; }},
      {"fragments.count is -1, not a count", [](nlohmann::json& j) { j["fragments"]["count"] = -1; }},
      {"fragments.count is 3 but fragments.areas lists", [](nlohmann::json& j) { j["fragments"]["count"] = 3; }},
      {"fragments.areas[1] is -0.5, negative", [](nlohmann::json& j) { j["fragments"]["areas"][1] = -0.5; }},
      {"cracks.histogram_log10_length.p sums to 2, not 1",
       [](nlohmann::json& j) { j["cracks"]["histogram_log10_length"]["p"][0] = 1.0 + j["cracks"]["histogram_log10_length"]["p"][0].get<double>(); }},
      {"cracks.histogram_log10_length.edges are not increasing at index 1",
       [](nlohmann::json& j) { j["cracks"]["histogram_log10_length"]["edges"][1] = -5.0; }},
      {"cracks.histogram_log10_length.edges are not equally spaced at index 2",
       [](nlohmann::json& j) { j["cracks"]["histogram_log10_length"]["edges"][2] = -3.4; }},
      {"cracks.histogram_log10_length has 16 edges for 16 bins",
       [](nlohmann::json& j) { j["cracks"]["histogram_log10_length"]["edges"].erase(0); }},
      {"junctions.density is -3, negative", [](nlohmann::json& j) { j["junctions"]["density"] = -3; }},
      {"missing key junctions.histogram_log10_1p_local_density",
       [](nlohmann::json& j) { j["junctions"].erase("histogram_log10_1p_local_density"); }},
      {"junctions.t is -2, not a count", [](nlohmann::json& j) { j["junctions"]["t"] = -2; }},
      {"junctions.mean_angle_deg is 400, above 360", [](nlohmann::json& j) { j["junctions"]["mean_angle_deg"] = 400; }},
      {"junctions.relaxation_mode is \"sideways\"", [](nlohmann::json& j) { j["junctions"]["relaxation_mode"] = "sideways"; }},
      {"ends.border is 1.5, not an integer", [](nlohmann::json& j) { j["ends"]["border"] = 1.5; }},
      {"format 2 is not the supported version 1", [](nlohmann::json& j) { j["format"] = 2; }},
      {"format \"1\" is not the supported version 1", [](nlohmann::json& j) { j["format"] = "1"; }},
      {"fragments is not an object", [](nlohmann::json& j) { j["fragments"] = 5; }},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.expected);
    nlohmann::json j = valid_stats();
    c.spoil(j);
    const std::string message = io_error_of(j.dump());
    EXPECT_EQ(message.rfind("stats.json: not valid pattern statistics JSON: ", 0), 0u) << message;
    EXPECT_NE(message.find(c.expected), std::string::npos) << message;
  }
  // NaN cannot be written in JSON; a huge exponent is how an infinity arrives (refused by the
  // parser as an overflow, one line).
  std::string text = valid_stats().dump();
  const std::string key = "\"total_area\":";
  const std::size_t at = text.find(key) + key.size();
  text.replace(at, text.find(',', at) - at, "1e999");
  EXPECT_NE(io_error_of(text).find("stats.json: not valid pattern statistics JSON: number overflow parsing '1e999'"),
            std::string::npos)
      << io_error_of(text);
  // What was valid still is, and compares as zero with itself.
  const PatternStats s = pattern_stats_from_json(valid_stats().dump(), "stats.json");
  EXPECT_EQ(pattern_similarity(s, s).total, 0.0);
}

// Used to pass nlohmann's text through: "[json.exception.parse_error.101] parse error at line 1,
// column 1: syntax error while parsing value - invalid literal; last read: 'n'".
TEST(StatsJson, SyntaxErrorIsOneClearLine) {
  const std::string message = io_error_of("{\n  \"format\": 1,\n  \"total_area\": nope\n}");
  EXPECT_EQ(message.find("json.exception"), std::string::npos) << message;
  EXPECT_NE(message.find("stats.json: not valid pattern statistics JSON: syntax error at line 3, column"), std::string::npos)
      << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  EXPECT_NE(io_error_of("").find("stats.json: not valid pattern statistics JSON: syntax error"), std::string::npos);
}

}  // namespace
}  // namespace fissure
