#include "fissure/scene/scene_project.hpp"

#include "fissure/base/atomic_file.hpp"
#include "fissure/base/error.hpp"
#include "fissure/base/json_error_text.hpp"
#include "fissure/base/number_text.hpp"
#include "fissure/fracture/fracture_params.hpp"
#include "fissure/fracture/fracture_scenario.hpp"

#include "json_fields.hpp"

#include <cmath>
#include <limits>
#include <system_error>

namespace fissure {
namespace {

namespace fs = std::filesystem;
using namespace json_fields;

double finite_number(const json& value, const std::string& path) {
  if (!value.is_number()) throw FieldError{path + " is " + type_of(value) + ", not a number"};
  const double v = value.get<double>();
  if (!std::isfinite(v)) throw FieldError{path + " is not finite"};
  return v;
}

double positive_number(const json& value, const std::string& path) {
  const double v = finite_number(value, path);
  if (!(v > 0.0)) throw FieldError{path + " is " + format_number(v) + ", not positive"};
  return v;
}

Eigen::Vector3d vector3(const json& value, const std::string& path) {
  if (!value.is_array() || value.size() != 3) throw FieldError{path + " is " + value.dump() + ", not [x, y, z]"};
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) v[i] = finite_number(value[static_cast<std::size_t>(i)], path + "[" + std::to_string(i) + "]");
  return v;
}

std::map<std::string, std::string> string_map(const json& value, const std::string& path) {
  if (!value.is_object()) throw FieldError{path + " is " + type_of(value) + ", not an object"};
  std::map<std::string, std::string> out;
  for (const auto& [key, v] : value.items()) {
    const std::string s = string_field(v, path + "." + key);
    if (key.empty() || s.empty()) throw FieldError{path + " has an empty name or material"};
    out[key] = s;
  }
  return out;
}

PatchLoad read_load(const json& value, const std::string& path) {
  if (!value.is_object()) throw FieldError{path + " is " + type_of(value) + ", not an object"};
  refuse_unknown_keys(value, path + ".", {"position", "normal", "magnitude", "radius"});
  PatchLoad load;
  load.position = vector3(required(value, path + ".", "position"), path + ".position");
  const Eigen::Vector3d normal = vector3(required(value, path + ".", "normal"), path + ".normal");
  if (!(normal.norm() > 0.0)) throw FieldError{path + ".normal is zero"};
  load.normal = normal.normalized();
  load.magnitude = positive_number(required(value, path + ".", "magnitude"), path + ".magnitude");
  load.radius = positive_number(required(value, path + ".", "radius"), path + ".radius");
  return load;
}

SceneBodySetupEntry read_body(const json& value, const std::string& path) {
  if (!value.is_object()) throw FieldError{path + " is " + type_of(value) + ", not an object"};
  refuse_unknown_keys(value, path + ".", {"loads", "supports", "free", "up"});
  SceneBodySetupEntry body;
  if (value.contains("loads")) {
    const json& loads = value["loads"];
    if (!loads.is_array()) throw FieldError{path + ".loads is " + type_of(loads) + ", not an array"};
    for (std::size_t i = 0; i < loads.size(); ++i) body.loads.push_back(read_load(loads[i], path + ".loads[" + std::to_string(i) + "]"));
  }
  if (value.contains("supports")) {
    const json& supports = value["supports"];
    if (!supports.is_array()) throw FieldError{path + ".supports is " + type_of(supports) + ", not an array"};
    for (std::size_t i = 0; i < supports.size(); ++i) {
      const std::string at = path + ".supports[" + std::to_string(i) + "]";
      body.supports.push_back(string_field(supports[i], at));
      try {
        parse_support(body.supports.back());
      } catch (const InvalidInput& e) {
        throw FieldError{at + ": " + e.what()};
      }
    }
  }
  if (value.contains("free")) {
    if (!value["free"].is_boolean()) throw FieldError{path + ".free is " + type_of(value["free"]) + ", not true or false"};
    body.free_body = value["free"].get<bool>();
  }
  if (body.free_body && !body.supports.empty()) throw FieldError{path + " is free and has supports: give one or the other"};
  if (value.contains("up")) {
    body.up = string_field(value["up"], path + ".up");
    try {
      parse_up_axis(*body.up);
    } catch (const InvalidInput& e) {
      throw FieldError{path + ".up: " + e.what()};
    }
  }
  return body;
}

SceneProject read_fields(const json& j) {
  if (!j.is_object()) throw FieldError{"the document is " + type_of(j) + ", not an object"};
  const json& version = required(j, "", "fissure_project");
  if (!version.is_number_integer() || version.get<std::int64_t>() < 1)
    throw FieldError{"fissure_project is " + version.dump() + ", not a version number"};
  if (version.get<std::int64_t>() > kSceneProjectVersion) {
    throw FieldError{"fissure_project " + version.dump() + " is from a newer Fissure (this one reads up to version " +
                     std::to_string(kSceneProjectVersion) + ")"};
  }
  refuse_unknown_keys(j, "", {"fissure_project", "scene", "seed", "age", "up", "tets", "unit", "slice", "strict", "assign",
                          "bodies", "export"});
  SceneProject p;
  p.scene = string_field(required(j, "", "scene"), "scene");
  if (p.scene.empty()) throw FieldError{"scene is empty"};
  if (j.contains("seed")) {
    const json& seed = j["seed"];
    if (!seed.is_number_unsigned()) throw FieldError{"seed is " + seed.dump() + ", not a whole number ≥ 0"};
    p.seed = seed.get<std::uint64_t>();
  }
  if (j.contains("age")) {
    const double age = finite_number(j["age"], "age");
    // The parameter table's range (a larger age would be refused by every body, one by one).
    const ParameterInfo& row = fracture_parameter_info("age");
    if (age < row.min || age > row.max) {
      throw FieldError{"age is " + format_number(age) + ", not in " + format_number(row.min) + ".." + format_number(row.max)};
    }
    p.age = age;
  }
  if (j.contains("up")) {
    p.up = string_field(j["up"], "up");
    try {
      parse_up_axis(*p.up);
    } catch (const InvalidInput& e) {
      throw FieldError{std::string("up: ") + e.what()};
    }
  }
  if (j.contains("tets")) {
    const json& tets = j["tets"];
    if (!tets.is_number_unsigned() || (tets.get<std::uint64_t>() != 0 && (tets.get<std::uint64_t>() < 10 || tets.get<std::uint64_t>() > 50000000)))
      throw FieldError{"tets is " + tets.dump() + ", not 0 (the default) or a count in 10..5e7"};
    p.tets = static_cast<int>(tets.get<std::uint64_t>());
  }
  if (j.contains("unit")) {
    p.unit = positive_number(j["unit"], "unit");
    if (p.unit < 1e-9 || p.unit > 1e9) throw FieldError{"unit is " + format_number(p.unit) + ", not in 1e-9..1e9 metres per scene unit"};
  }
  if (j.contains("slice")) {
    const json& slice = j["slice"];
    const auto count = [](const json& v) { return v.is_number_unsigned() && v.get<std::uint64_t>() >= 1 && v.get<std::uint64_t>() <= 1000000; };
    if (!slice.is_array() || slice.size() != 2 || !count(slice[0]) || !count(slice[1]) || slice[0].get<std::uint64_t>() > slice[1].get<std::uint64_t>())
      throw FieldError{"slice is " + slice.dump() + ", not [K, N] with K from 1 to N (--bodies K/N)"};
    p.slice = slice[0].get<int>();
    p.slices = slice[1].get<int>();
  }
  if (j.contains("strict")) {
    if (!j["strict"].is_boolean()) throw FieldError{"strict is " + j["strict"].dump() + ", not true or false"};
    p.strict = j["strict"].get<bool>();
  }
  if (j.contains("assign")) {
    const json& assign = j["assign"];
    if (!assign.is_object()) throw FieldError{"assign is " + type_of(assign) + ", not an object"};
    refuse_unknown_keys(assign, "assign.", {"materials", "nodes"});
    if (assign.contains("materials")) p.assignments.by_material = string_map(assign["materials"], "assign.materials");
    if (assign.contains("nodes")) p.assignments.by_path = string_map(assign["nodes"], "assign.nodes");
    for (const auto& [path, material] : p.assignments.by_path)
      if (path[0] != '/') throw FieldError{"assign.nodes." + path + ": a node path starts with /"};
  }
  if (j.contains("bodies")) {
    const json& bodies = j["bodies"];
    if (!bodies.is_object()) throw FieldError{"bodies is " + type_of(bodies) + ", not an object"};
    for (const auto& [path, body] : bodies.items()) {
      if (path.empty() || path[0] != '/') throw FieldError{"bodies." + path + ": a body path starts with /"};
      p.bodies[path] = read_body(body, "bodies." + path);
    }
  }
  if (j.contains("export")) {
    const json& e = j["export"];
    if (!e.is_object()) throw FieldError{"export is " + type_of(e) + ", not an object"};
    refuse_unknown_keys(e, "export.", {"output", "report", "crack_masks", "crack_mask_size"});
    if (e.contains("output")) p.output = string_field(e["output"], "export.output");
    if (e.contains("report")) p.report = string_field(e["report"], "export.report");
    if (e.contains("crack_masks")) p.crack_masks = string_field(e["crack_masks"], "export.crack_masks");
    if (e.contains("crack_mask_size")) {
      const json& size = e["crack_mask_size"];
      if (!size.is_number_unsigned() || size.get<std::uint64_t>() < 16 || size.get<std::uint64_t>() > 16384)
        throw FieldError{"export.crack_mask_size is " + size.dump() + ", not a count of pixels in 16..16384"};
      p.crack_mask_size = static_cast<int>(size.get<std::uint64_t>());
    }
  }
  return p;
}

nlohmann::ordered_json vector_json(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace

fs::path project_path(const fs::path& project_file, const std::string& written) {
  const fs::path p(written);
  // A project in the working folder keeps its paths as written: "s.glb", not "./s.glb", in
  // every message and summary that names them.
  if (p.is_absolute() || !project_file.has_parent_path()) return p;
  return project_file.parent_path() / p;
}

bool is_scene_project_file(const fs::path& file) { return file.extension() == ".json"; }

SceneProject read_scene_project(const fs::path& file) {
  const std::string text = read_file(file);
  const std::string bad = file.string() + ": not a valid Fissure project: ";
  SceneProject project;
  try {
    project = read_fields(json::parse(text, RepeatedKeyCheck{}));
  } catch (const json::exception& e) {
    throw IoError(bad + json_error_text(e.what()));
  } catch (const FieldError& e) {
    throw IoError(bad + e.text);
  }
  const fs::path scene = project_path(file, project.scene);
  std::error_code ec;
  if (!fs::is_regular_file(scene, ec)) {
    throw IoError(file.string() + ": its scene " + project.scene + " is not at " + fs::absolute(scene, ec).string() +
                       ": was it moved? Put the scene back or edit \"scene\" in " + file.filename().string());
  }
  return project;
}

std::string scene_project_to_json(const SceneProject& p) {
  nlohmann::ordered_json j;
  j["fissure_project"] = kSceneProjectVersion;
  j["scene"] = p.scene;
  j["seed"] = p.seed;
  if (p.age) j["age"] = *p.age;
  if (p.up) j["up"] = *p.up;
  if (p.tets > 0) j["tets"] = p.tets;
  if (p.unit != 1.0) j["unit"] = p.unit;
  if (p.slices > 1) j["slice"] = {p.slice, p.slices};
  if (p.strict) j["strict"] = true;
  nlohmann::ordered_json assign = nlohmann::ordered_json::object();
  if (!p.assignments.by_material.empty()) assign["materials"] = p.assignments.by_material;
  if (!p.assignments.by_path.empty()) assign["nodes"] = p.assignments.by_path;
  j["assign"] = assign;
  nlohmann::ordered_json bodies = nlohmann::ordered_json::object();
  for (const auto& [path, body] : p.bodies) {
    nlohmann::ordered_json b = nlohmann::ordered_json::object();
    if (!body.loads.empty()) {
      nlohmann::ordered_json loads = nlohmann::ordered_json::array();
      for (const PatchLoad& l : body.loads)
        loads.push_back({{"position", vector_json(l.position)}, {"normal", vector_json(l.normal)},
                         {"magnitude", l.magnitude}, {"radius", l.radius}});
      b["loads"] = loads;
    }
    if (!body.supports.empty()) b["supports"] = body.supports;
    if (body.free_body) b["free"] = true;
    if (body.up) b["up"] = *body.up;
    bodies[path] = b;
  }
  if (!bodies.empty()) j["bodies"] = bodies;
  nlohmann::ordered_json e = nlohmann::ordered_json::object();
  if (!p.output.empty()) e["output"] = p.output;
  if (!p.report.empty()) e["report"] = p.report;
  if (!p.crack_masks.empty()) e["crack_masks"] = p.crack_masks;
  if (p.crack_mask_size > 0) e["crack_mask_size"] = p.crack_mask_size;
  if (!e.empty()) j["export"] = e;
  // nlohmann writes doubles in their shortest round-trip form: reading gives the same bits.
  return j.dump(2) + "\n";
}

void write_scene_project(const fs::path& file, const SceneProject& project) {
  write_file_atomically(file, scene_project_to_json(project));
}

SceneFractureOptions scene_fracture_options(const SceneProject& project, const std::string& source) {
  SceneFractureOptions o;
  o.assignments = project.assignments;
  o.seed = project.seed;
  o.age = project.age;
  if (project.up) o.up = parse_up_axis(*project.up);
  o.target_tets = project.tets;
  o.unit = project.unit;
  o.slice = project.slice;
  o.slices = project.slices;
  for (const auto& [path, body] : project.bodies) {
    SceneBodySetup setup;
    setup.free_body = body.free_body;
    setup.loads = body.loads;
    if (body.up) setup.up = parse_up_axis(*body.up);
    try {
      for (const std::string& s : body.supports) setup.supports.push_back(parse_support(s));
    } catch (const InvalidInput& e) {
      throw InvalidInput(source + ": bodies." + path + ": " + e.what());
    }
    o.body_setups[path] = std::move(setup);
  }
  return o;
}

}  // namespace fissure
