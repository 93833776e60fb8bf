#pragma once
// Reading hand-edited JSON files (materials, projects) with messages that name the key: shared by
// the modules' sources, never by a public header (which may not mention the JSON library).
// FieldError is "<key path> <what is wrong>"; a reader turns it into one error naming its file.

#include <nlohmann/json.hpp>

#include <algorithm>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace fissure::json_fields {

using nlohmann::json;

// A structural failure: "<key path> <what is wrong>", turned into one IoError naming the file.
struct FieldError {
  std::string text;
};

inline std::string type_of(const json& value) { return value.type_name(); }

inline const json& required(const json& object, const std::string& parent, const std::string& key) {
  const auto it = object.find(key);
  if (it == object.end()) throw FieldError{"missing key " + parent + key};
  return *it;
}

inline std::string string_field(const json& value, const std::string& path) {
  if (!value.is_string()) throw FieldError{path + " is " + type_of(value) + ", not a string"};
  return value.get<std::string>();
}

// Levenshtein distance, for "did you mean": keys are short, so the O(|a|·|b|) table is nothing.
inline std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// Refuses the first key of `object` not in `known`, suggesting the nearest known key when it is
// at most 3 edits away (a typo, not another word).
inline void refuse_unknown_keys(const json& object, const std::string& parent, const std::vector<std::string>& known) {
  for (const auto& [key, value] : object.items()) {
    if (std::find(known.begin(), known.end(), key) != known.end()) continue;
    std::string text = "unknown key " + parent + json(key).dump();
    std::size_t best = 4;
    std::string nearest;
    for (const std::string& k : known) {
      const std::size_t d = edit_distance(key, k);
      if (d < best) {
        best = d;
        nearest = k;
      }
    }
    if (!nearest.empty()) text += " (did you mean " + parent + nearest + "?)";
    throw FieldError{text};
  }
}

// json::parse keeps the last of repeated keys without a word; these files are edited by hand,
// so a repeated key is refused. The callback sees every key as it is read.
class RepeatedKeyCheck {
public:
  bool operator()(int /*depth*/, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start: m_frames.push_back({true, {}, {}}); break;
      case json::parse_event_t::array_start: m_frames.push_back({false, {}, {}}); break;
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        if (!m_frames.empty()) m_frames.pop_back();
        break;
      case json::parse_event_t::key: {
        Frame& top = m_frames.back();
        std::string key = parsed.get<std::string>();
        if (!top.keys.insert(key).second) throw FieldError{"key " + path() + key + " appears twice"};
        top.last_key = std::move(key);
        break;
      }
      case json::parse_event_t::value: break;
    }
    return true;
  }

private:
  struct Frame {
    bool object;
    std::set<std::string> keys;
    std::string last_key;
  };
  // "parameters." for a key inside "parameters" (the open objects' keys, outermost first).
  std::string path() const {
    std::string p;
    for (std::size_t i = 0; i + 1 < m_frames.size(); ++i)
      if (m_frames[i].object) p += m_frames[i].last_key + ".";
    return p;
  }
  std::vector<Frame> m_frames;
};

}  // namespace fissure::json_fields
