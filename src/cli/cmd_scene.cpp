// fissure scene info SCENE [--json]: a scene's bodies (node instances of meshes), their scene
// materials, sizes and whether each can be fractured (closed or safely repaired), and the
// materials' texture references, missing ones named. Issue 13's `scene fracture` and `scene
// merge` join it here.

#include "cli_common.hpp"
#include "command_table.hpp"
#include "commands.hpp"
#include "interruption.hpp"
#include "terminal_progress.hpp"

#include "fissure/base/number_text.hpp"
#include "fissure/io/scene_import.hpp"
#include "fissure/scene/scene_body_check.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>

namespace fissure::cli {
namespace {

namespace fs = std::filesystem;

struct SceneInfoArgs {
  std::string scene;
  bool json = false;
  bool quiet = false;
};

std::string axis_name(const Eigen::Vector3d& up) {
  for (int a = 0; a < 3; ++a) {
    if (up[a] != 0.0) return std::string(up[a] > 0.0 ? "+" : "-") + "xyz"[a];
  }
  return "?";
}

// A texture reference the file gives as a path, resolved against the scene's folder; "*N" is an
// image embedded in the file. False only for a path that names no file.
bool texture_found(const fs::path& scene, const std::string& reference) {
  if (reference.empty() || reference[0] == '*') return true;
  std::error_code ec;
  const fs::path path(reference);
  return fs::is_regular_file(path.is_absolute() ? path : scene.parent_path() / path, ec);
}

int run_scene_info(const SceneInfoArgs& args) {
  TerminalProgress progress(args.quiet);
  ImportedScene scene;
  std::vector<SceneBody> bodies;
  std::vector<SceneBodyCheck> checks;
  {
    AbandonableWork work;
    progress.stage("reading " + args.scene);
    scene = import_scene(args.scene);
    bodies = scene_bodies(scene);
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      progress.report("checking bodies", static_cast<double>(i) / static_cast<double>(bodies.size()));
      throw_if_interrupted();
      checks.push_back(check_scene_body(scene, bodies[i]));
    }
  }
  throw_if_interrupted();
  progress.clear();
  const auto material_name = [&](int m) { return m < 0 ? std::string() : scene.materials[static_cast<std::size_t>(m)].name; };
  int fracturable = 0;
  for (const SceneBodyCheck& c : checks) fracturable += c.fracturable ? 1 : 0;
  if (args.json) {
    nlohmann::ordered_json j;
    j["scene"] = scene.source;
    j["format"] = scene.format;
    j["up"] = axis_name(scene.up);
    j["nodes"] = scene.nodes.size();
    j["meshes"] = scene.meshes.size();
    nlohmann::ordered_json materials = nlohmann::ordered_json::array();
    for (const SceneMaterial& m : scene.materials) {
      nlohmann::ordered_json textures = nlohmann::ordered_json::array();
      for (const std::string& t : m.textures) textures.push_back({{"reference", t}, {"found", texture_found(args.scene, t)}});
      materials.push_back({{"name", m.name}, {"textures", textures}});
    }
    j["materials"] = materials;
    nlohmann::ordered_json list = nlohmann::ordered_json::array();
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      const SceneMesh& mesh = scene.meshes[static_cast<std::size_t>(bodies[i].mesh)];
      const SceneBodyCheck& c = checks[i];
      nlohmann::ordered_json b = {{"path", bodies[i].path},
                                  {"mesh", mesh.name},
                                  {"material", material_name(mesh.material)},
                                  {"triangles", mesh.triangles.rows()},
                                  {"size", {c.extent.x(), c.extent.y(), c.extent.z()}},
                                  {"fracturable", c.fracturable}};
      if (c.fracturable) {
        b["volume"] = c.volume;
        b["repairs"] = c.repairs;
      } else {
        b["reason"] = c.reason;
      }
      list.push_back(b);
    }
    j["bodies"] = list;
    std::printf("%s\n", j.dump(2).c_str());
    return kExitOk;
  }
  std::printf("%s: %s, up %s, %zu nodes, %zu meshes, %zu materials, %zu bodies (%d fracturable)\n", scene.source.c_str(),
              scene.format.c_str(), axis_name(scene.up).c_str(), scene.nodes.size(), scene.meshes.size(),
              scene.materials.size(), bodies.size(), fracturable);
  const auto f = [](double x) { return format_number(x, 3); };
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const SceneMesh& mesh = scene.meshes[static_cast<std::size_t>(bodies[i].mesh)];
    const SceneBodyCheck& c = checks[i];
    const std::string material = material_name(mesh.material);
    std::string state = c.fracturable ? "closed" : "not fracturable: " + c.reason;
    if (c.fracturable && !c.repairs.empty()) {
      state = "repaired (";
      for (std::size_t k = 0; k < c.repairs.size(); ++k) state += (k ? "; " : "") + c.repairs[k];
      state += ")";
    }
    std::printf("  %s: mesh %s, material %s, %lld triangles, %s x %s x %s m, %s\n", bodies[i].path.c_str(), mesh.name.c_str(),
                material.empty() ? "(none)" : material.c_str(), static_cast<long long>(mesh.triangles.rows()),
                f(c.extent.x()).c_str(), f(c.extent.y()).c_str(), f(c.extent.z()).c_str(), state.c_str());
  }
  for (const SceneMaterial& m : scene.materials) {
    std::string line = "  material " + m.name;
    for (const std::string& t : m.textures) line += ", texture " + t + (texture_found(args.scene, t) ? "" : " (missing)");
    std::printf("%s\n", line.c_str());
  }
  return kExitOk;
}

}  // namespace

void register_scene(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand("scene", std::string(command_info("scene").summary));
  cmd->require_subcommand(1);
  auto args = std::make_shared<SceneInfoArgs>();
  auto* info = cmd->add_subcommand("info", "List a scene's bodies, materials, sizes and which bodies can be fractured");
  add_threads_option(*info);
  info->add_option("SCENE", args->scene, "Scene file (glTF, GLB, FBX, OBJ, PLY, STL, OFF)")->required();
  info->add_flag("--json", args->json, "Print the result as JSON");
  info->add_flag("-q,--quiet", args->quiet, "No progress on stderr");
  info->callback([&action, args] { action = [args] { return run_scene_info(*args); }; });
}

}  // namespace fissure::cli
