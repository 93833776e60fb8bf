// fissure scene info SCENE [--json]: a scene's bodies (node instances of meshes), their scene
// materials, sizes and whether each can be fractured (closed or safely repaired), and the
// materials' texture references, missing ones named.
// fissure scene fracture SCENE|PROJECT [--assign NAME=MATERIAL…] [--save-project P.json] [--seed S]
//   [--age A] [--up AXIS] [--tets N] [--unit M] [--bodies K/N] [--strict] [--no-cache|--cache-dir D]
//   [--report R.json] [-o OUT]: every assigned body fractured, the scene written back with the
//   fragments as child nodes (scene/scene_fracture.hpp); a project (scene/scene_project.hpp)
//   gives the settings the other options override.
// fissure scene merge SLICE.glb… -o OUT: the slices of a --bodies K/N run joined into the file an
//   unsliced run writes (scene/scene_merge.hpp).
// fissure scene demo street|bathroom -o OUT: the demo scenes of assets/scenes/ (scene/demo_scenes.hpp).

#include "cli_common.hpp"
#include "command_table.hpp"
#include "commands.hpp"
#include "interruption.hpp"
#include "memory_estimate.hpp"
#include "option_checks.hpp"
#include "terminal_progress.hpp"

#include "fissure/base/atomic_file.hpp"
#include "fissure/base/disk_cache.hpp"
#include "fissure/base/distinct_files.hpp"
#include "fissure/base/error.hpp"
#include "fissure/base/memory.hpp"
#include "fissure/base/number_text.hpp"
#include "fissure/base/thread_count.hpp"
#include "fissure/fracture/fracture_params.hpp"
#include "fissure/fracture/fracture_scenario.hpp"
#include "fissure/io/gltf_reader.hpp"
#include "fissure/mesh/tetrahedralize.hpp"
#include "fissure/io/scene_export.hpp"
#include "fissure/io/scene_import.hpp"
#include "fissure/scene/crack_texture.hpp"
#include "fissure/scene/demo_scenes.hpp"
#include "fissure/scene/scene_body_check.hpp"
#include "fissure/scene/scene_fracture.hpp"
#include "fissure/scene/scene_merge.hpp"
#include "fissure/scene/scene_project.hpp"

#include <nlohmann/json.hpp>

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <iostream>

namespace fissure::cli {
namespace {

namespace fs = std::filesystem;

// "1 body", "2 bodies".
std::string counted(long long n, const char* one, const char* many) { return std::to_string(n) + " " + (n == 1 ? one : many); }

struct SceneInfoArgs {
  std::string scene;
  bool json = false;
  bool quiet = false;
};

// A texture reference the file gives as a path, resolved against the scene's folder; "*N" is an
// image embedded in the file. False only for a path that names no file.
bool texture_found(const fs::path& scene, const std::string& reference) {
  if (reference.empty() || reference[0] == '*') return true;
  std::error_code ec;
  const fs::path path(reference);
  return fs::is_regular_file(path.is_absolute() ? path : scene.parent_path() / path, ec);
}

// [[min x, y, z], [max x, y, z]] of world vertices: where to place a project's loads.
nlohmann::ordered_json bounds_json(const Eigen::MatrixX3d& vertices) {
  if (vertices.rows() == 0) return nullptr;
  const Eigen::Vector3d lo = vertices.colwise().minCoeff(), hi = vertices.colwise().maxCoeff();
  return {{lo.x(), lo.y(), lo.z()}, {hi.x(), hi.y(), hi.z()}};
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
  for (const std::string& w : scene.warnings) std::cerr << "fissure scene info: warning: " << w << '\n';
  // A body's meshes and their scene materials, ", "-separated (a mesh split by material is one body).
  const auto mesh_names = [&](const SceneBody& b) {
    std::string names;
    for (int m : b.meshes) names += (names.empty() ? "" : ", ") + scene.meshes[static_cast<std::size_t>(m)].name;
    return names;
  };
  const auto material_names = [&](const SceneBody& b) {
    std::string names;
    for (int m : b.meshes) {
      const int k = scene.meshes[static_cast<std::size_t>(m)].material;
      if (k < 0) continue;
      const std::string& name = scene.materials[static_cast<std::size_t>(k)].name;
      if (names.find(name) == std::string::npos) names += (names.empty() ? "" : ", ") + name;
    }
    return names;
  };
  int fracturable = 0;
  for (const SceneBodyCheck& c : checks) fracturable += c.fracturable ? 1 : 0;
  if (args.json) {
    nlohmann::ordered_json j;
    j["scene"] = scene.source;
    j["format"] = scene.format;
    j["up"] = up_axis_name(scene.up);
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
      const SceneBodyCheck& c = checks[i];
      nlohmann::ordered_json b = {{"path", bodies[i].path},
                                  {"mesh", mesh_names(bodies[i])},
                                  {"material", material_names(bodies[i])},
                                  {"triangles", c.world.faces.rows()},
                                  {"size", {c.extent.x(), c.extent.y(), c.extent.z()}},
                                  {"bounds", bounds_json(c.world.vertices)},
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
  const auto count = [](std::size_t n, const char* one, const char* many) {
    return counted(static_cast<long long>(n), one, many);
  };
  std::printf("%s: %s, up %s, %s, %s, %s, %s (%d fracturable)\n", scene.source.c_str(), scene.format.c_str(),
              up_axis_name(scene.up).c_str(), count(scene.nodes.size(), "node", "nodes").c_str(),
              count(scene.meshes.size(), "mesh", "meshes").c_str(), count(scene.materials.size(), "material", "materials").c_str(),
              count(bodies.size(), "body", "bodies").c_str(), fracturable);
  const auto f = [](double x) { return format_number(x, 3); };
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const SceneBodyCheck& c = checks[i];
    const std::string material = material_names(bodies[i]);
    std::string state = c.fracturable ? "closed" : "not fracturable: " + c.reason;
    if (c.fracturable && !c.repairs.empty()) {
      state = "repaired (";
      for (std::size_t k = 0; k < c.repairs.size(); ++k) state += (k ? "; " : "") + c.repairs[k];
      state += ")";
    }
    std::printf("  %s: mesh %s, material %s, %lld triangles, %s x %s x %s m, %s\n", bodies[i].path.c_str(),
                mesh_names(bodies[i]).c_str(), material.empty() ? "(none)" : material.c_str(),
                static_cast<long long>(c.world.faces.rows()),
                f(c.extent.x()).c_str(), f(c.extent.y()).c_str(), f(c.extent.z()).c_str(), state.c_str());
  }
  for (const SceneMaterial& m : scene.materials) {
    std::string line = "  material " + m.name;
    for (const std::string& t : m.textures) line += ", texture " + t + (texture_found(args.scene, t) ? "" : " (missing)");
    std::printf("%s\n", line.c_str());
  }
  return kExitOk;
}

struct SceneFractureArgs {
  std::string scene;                 // a scene, or a project (.json)
  std::vector<std::string> assign;
  std::uint64_t seed = 1;
  bool seed_given = false;
  std::string save_project;
  double age = -1.0;  // < 0: each material's
  std::string up;
  double tets = 0;
  double unit = 0.0;  // 0: the project's, else 1
  std::string bodies;
  bool strict = false;
  bool no_cache = false;
  std::string cache_dir;
  std::string report;
  bool allow_large = false;
  std::string crack_masks;
  double crack_mask_size = 0;  // 0: the project's, else CrackTextureOptions' default
  std::string output;
  bool quiet = false;
};

// "--assign NAME=MATERIAL": NAME is a scene material, or a node or body path when it starts with
// '/'. Split at the first '=', as KEY=VALUE is everywhere: a material file's path may hold one.
SceneAssignments parse_assignments(const std::vector<std::string>& specs) {
  SceneAssignments a;
  for (const std::string& spec : specs) {
    const std::size_t eq = spec.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == spec.size())
      throw InvalidInput("--assign " + spec + ": expected SCENE_MATERIAL=MATERIAL or /node/path=MATERIAL");
    const std::string key = spec.substr(0, eq), material = spec.substr(eq + 1);
    auto& map = key[0] == '/' ? a.by_path : a.by_material;
    if (!map.emplace(key, material).second) throw InvalidInput("--assign " + key + " is given twice");
  }
  return a;
}

std::pair<int, int> parse_slice(const std::string& text) {
  const std::size_t slash = text.find('/');
  int k = 0, n = 0;
  try {
    std::size_t used = 0;
    if (slash == std::string::npos) throw InvalidInput("");
    k = std::stoi(text.substr(0, slash), &used);
    if (used != slash) throw InvalidInput("");
    n = std::stoi(text.substr(slash + 1), &used);
    if (used != text.size() - slash - 1) throw InvalidInput("");
  } catch (const std::exception&) {
    throw InvalidInput("--bodies " + text + ": expected K/N, K from 1 to N");
  }
  if (n < 1 || k < 1 || k > n) throw InvalidInput("--bodies " + text + ": expected K/N, K from 1 to N");
  return {k, n};
}

// A malformed flag value is a command-line error (exit 2, with the help pointer), as CLI11's
// own checks are, rather than an invalid input found later (exit 3).
CLI::Validator parsed_by(std::function<void(const std::string&)> parse) {
  return CLI::Validator(
      [parse](std::string& text) -> std::string {
        try {
          parse(text);
        } catch (const InvalidInput& e) {
          std::string what = e.what();
          // The parsers name the flag themselves; CLI11 names it again.
          if (const std::size_t space = what.find(' '); what.rfind("--", 0) == 0 && space != std::string::npos) what = what.substr(space + 1);
          return what;
        }
        return {};
      },
      "");
}

nlohmann::ordered_json report_json(const SceneFracture& run, const std::string& scene, const std::string& output,
                                   std::uint64_t seed, double seconds, const std::map<std::string, std::string>& crack_masks) {
  nlohmann::ordered_json bodies = nlohmann::ordered_json::array();
  for (const SceneBodyReport& r : run.reports) {
    nlohmann::ordered_json b = {{"path", r.path}, {"status", status_name(r.status)}};
    if (!r.material.empty()) b["assignment"] = r.material;
    if (r.status == SceneBodyReport::Status::Fractured || r.status == SceneBodyReport::Status::Skipped) b["seed"] = r.seed;
    if (r.status == SceneBodyReport::Status::Skipped) b["reason"] = r.reason;
    if (!r.repairs.empty()) b["repairs"] = r.repairs;
    if (r.status == SceneBodyReport::Status::Fractured) {
      b["material"] = r.material_name;
      b["fragments"] = r.fragments;
      b["tets"] = r.tets;
      b["mesh"] = r.mesh_cached ? "cached" : "made";
      b["stress"] = r.stress_cached ? "cached" : "solved";
      b["up"] = up_axis_name(r.up);
      b["loads"] = r.loads;
      if (const auto mask = crack_masks.find(r.path); mask != crack_masks.end()) b["crack_mask"] = mask->second;
      b["seconds"] = {{"meshing", r.seconds.meshing},
                      {"preparation", r.seconds.preparation},
                      {"simulation", r.seconds.simulation},
                      {"fragments", r.seconds.fragments}};
    }
    bodies.push_back(b);
  }
  return {{"scene", scene}, {"output", output}, {"seed", seed}, {"warnings", run.warnings}, {"notes", run.notes},
          {"seconds", seconds}, {"bodies", bodies}};
}

// The run a project describes, with the command line's options over it: --assign adds to and
// overrides its assignments; --seed, --age, --up, --tets, --unit, --bodies, -o and --report
// replace its values; --strict sets its "strict".
struct SceneFractureRun {
  std::string scene;                 // the scene file to read
  SceneFractureOptions options;
  std::string output, report;
  std::string crack_masks;           // the folder of crack textures, or empty
  SceneProject project;              // what --save-project writes
};

SceneFractureRun scene_fracture_run(const SceneFractureArgs& args) {
  SceneFractureRun run;
  SceneProject& project = run.project;
  fs::path base;                     // the folder the project's paths are relative to
  if (is_scene_project_file(args.scene)) {
    project = read_scene_project(args.scene);
    base = fs::path(args.scene);
    run.scene = project_path(base, project.scene).string();
    if (!project.output.empty()) run.output = project_path(base, project.output).string();
    if (!project.report.empty()) run.report = project_path(base, project.report).string();
    if (!project.crack_masks.empty()) run.crack_masks = project_path(base, project.crack_masks).string();
  } else {
    project.scene = args.scene;
    run.scene = args.scene;
  }
  const SceneAssignments cli = parse_assignments(args.assign);
  for (const auto& [k, v] : cli.by_material) project.assignments.by_material[k] = v;
  for (const auto& [k, v] : cli.by_path) project.assignments.by_path[k] = v;
  if (args.seed_given) project.seed = args.seed;
  if (args.age >= 0.0) project.age = args.age;
  if (!args.up.empty()) project.up = args.up;
  if (args.tets > 0) project.tets = static_cast<int>(std::lround(args.tets));
  if (args.unit > 0.0) project.unit = args.unit;
  if (!args.bodies.empty()) std::tie(project.slice, project.slices) = parse_slice(args.bodies);
  if (args.strict) project.strict = true;
  if (!args.output.empty()) run.output = args.output;
  if (!args.report.empty()) run.report = args.report;
  if (!args.crack_masks.empty()) run.crack_masks = args.crack_masks;
  if (args.crack_mask_size > 0) project.crack_mask_size = static_cast<int>(std::lround(args.crack_mask_size));
  if (run.output.empty())
    throw InvalidInput("no output: give -o OUT.glb" + std::string(base.empty() ? "" : " or \"export\": {\"output\": …} in " + args.scene));
  run.options = scene_fracture_options(project, args.scene);
  if (run.options.assignments.by_material.empty() && run.options.assignments.by_path.empty())
    throw InvalidInput("nothing to fracture: give --assign SCENE_MATERIAL=MATERIAL (fissure scene info lists the scene's materials)");
  return run;
}

// The project --save-project writes: the run's, its paths made relative to the project's folder
// when they lie under it, so the folder can move as a whole.
SceneProject project_to_save(SceneProject project, const SceneFractureRun& run, const fs::path& file) {
  const fs::path folder = fs::absolute(file).parent_path();
  const auto relative = [&](const std::string& path) {
    if (path.empty()) return path;
    const fs::path r = fs::absolute(path).lexically_normal().lexically_relative(folder);
    return r.empty() || *r.begin() == ".." ? fs::absolute(path).lexically_normal().string() : r.string();
  };
  project.scene = relative(run.scene);
  project.output = relative(run.output);
  project.report = relative(run.report);
  project.crack_masks = relative(run.crack_masks);
  return project;
}

int run_scene_fracture(const SceneFractureArgs& args) {
  SceneFractureRun setup = scene_fracture_run(args);
  check_scene_output_path(setup.output);
  if (!setup.report.empty()) check_output_path(setup.report);
  if (!setup.crack_masks.empty()) {
    std::error_code ec;
    if (!fs::is_directory(setup.crack_masks, ec)) throw IoError("--crack-masks " + setup.crack_masks + ": not a directory");
    check_output_path(fs::path(setup.crack_masks) / "crack-mask.png");  // writable
  }
  {
    // No output may land on the scene or on another output; --save-project may rewrite the
    // project being run (it gains the command line's settings), nothing else.
    std::vector<RoleAndPath> outputs = output_roles("-o", scene_output_files(setup.output));
    outputs.push_back({"--report", setup.report});
    if (is_scene_project_file(args.scene)) check_distinct_files({{"the input project", args.scene}}, outputs);
    outputs.push_back({"--save-project", args.save_project});
    std::vector<RoleAndPath> inputs;
    for (const fs::path& file : scene_input_files(setup.scene))
      inputs.push_back({inputs.empty() ? "the input scene" : "the input scene's material library", file.string()});
    check_distinct_files(inputs, outputs);
  }
  // A --tets no body could be meshed with is the run's error, before any work (each body was
  // refused in turn and the run exited 0 with all of them skipped).
  setup.options.memory_limit_bytes = memory_limit(args.allow_large);
  if (setup.options.target_tets > 0) {
    require_memory(tetrahedralize_memory_estimate(setup.options.target_tets), setup.options.memory_limit_bytes,
                   "--tets " + std::to_string(setup.options.target_tets) + " per body");
  }
  if (!args.save_project.empty()) {
    if (!is_scene_project_file(args.save_project)) throw InvalidInput("--save-project " + args.save_project + ": a project file ends in .json");
    write_scene_project(args.save_project, project_to_save(setup.project, setup, args.save_project));
  }
  SceneFractureOptions& options = setup.options;
  options.threads = thread_count();
  options.strict = setup.project.strict;
  options.cancel = &interrupt_token();
  if (!args.no_cache) options.cache_dir = args.cache_dir.empty() ? default_cache_directory() : fs::path(args.cache_dir);
  // A bar on a terminal, one plain line per body otherwise (a log keeps them).
  TerminalProgress progress(args.quiet);
  const bool lines = !args.quiet && !progress.enabled();
  options.on_body_done = [&](int done, int total, const std::string& path) {
    if (lines) {
      std::fprintf(stderr, "fissure scene fracture: %d/%d %s\n", done, total, path.c_str());
    } else {
      progress.report("fracturing bodies", static_cast<double>(done) / total);
    }
  };
  const auto start = std::chrono::steady_clock::now();
  ImportedScene scene;
  SceneFracture run;
  ExportScene out;
  {
    AbandonableWork work;
    progress.stage("reading " + setup.scene);
    scene = import_scene(setup.scene);
    run = fracture_scene(scene, options);
    throw_if_interrupted();
    out = scene_export(scene, run);
  }
  throw_if_interrupted();
  progress.clear();
  int fractured = 0, whole = 0, skipped = 0, fragments = 0;
  for (const std::string& w : run.warnings) std::cerr << "fissure scene fracture: warning: " << w << '\n';
  if (!args.quiet)
    for (const std::string& n : run.notes) std::cerr << "fissure scene fracture: note: " << n << '\n';
  for (const SceneBodyReport& r : run.reports) {
    if (r.status == SceneBodyReport::Status::Fractured) {
      ++fractured;
      whole += r.fragments <= 1;
      fragments += r.fragments;
    } else if (r.status == SceneBodyReport::Status::Skipped) {
      ++skipped;
      std::cerr << "fissure scene fracture: warning: " << r.path << " skipped: " << r.reason << '\n';
    }
  }
  const auto write_report = [&](const std::map<std::string, std::string>& crack_masks) {
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!setup.report.empty()) {
      write_file_atomically(setup.report, report_json(run, setup.scene, setup.output, options.seed, seconds, crack_masks).dump(2) + "\n");
    }
  };
  if (setup.project.strict && (skipped > 0 || !run.warnings.empty())) {
    write_report({});
    throw InvalidInput("--strict: " + counted(skipped, "body", "bodies") + " skipped, " +
                       counted(static_cast<long long>(run.warnings.size()), "warning", "warnings") + " (see above); nothing written to " +
                       setup.output);
  }
  write_scene(setup.output, out);
  // Crack textures, after the scene (a failed run writes none), one body at a time.
  std::map<std::string, std::string> crack_masks;  // body path → file written
  if (!setup.crack_masks.empty()) {
    CrackTextureOptions texture;
    if (setup.project.crack_mask_size > 0) texture.size = setup.project.crack_mask_size;
    for (std::size_t b = 0; b < run.results.size(); ++b) {
      if (!run.results[b]) continue;
      const std::string& path = run.reports[b].path;
      const GreyImage image = crack_texture(run.results[b]->fracture.fragments, run.results[b]->appearance, texture);
      if (image.width == 0) {
        if (!args.quiet) std::cerr << "fissure scene fracture: note: " << path << ": no texture coordinates, so no crack mask\n";
        continue;
      }
      const fs::path file = fs::path(setup.crack_masks) / crack_texture_file_name(path);
      write_grey_png(file, image);
      crack_masks[path] = file.string();
    }
  }
  write_report(crack_masks);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!args.quiet) {
    // A body that stayed whole was simulated but did not break: said apart, as its note says.
    const std::string stayed = whole == 0 ? "" : " (" + std::to_string(whole) + " stayed whole)";
    std::printf("%s: %s fractured into %s%s, %d skipped, %zu untouched; wrote %s in %s s\n", setup.scene.c_str(),
                counted(fractured, "body", "bodies").c_str(), counted(fragments, "fragment", "fragments").c_str(), stayed.c_str(),
                skipped, run.reports.size() - fractured - skipped, setup.output.c_str(), format_number(seconds, 3).c_str());
  }
  return kExitOk;
}

struct SceneMergeArgs {
  std::vector<std::string> slices;
  std::string output;
};

int run_scene_merge(const SceneMergeArgs& args) {
  check_scene_output_path(args.output);
  std::vector<RoleAndPath> inputs;
  for (const std::string& s : args.slices) inputs.push_back({"the input slice", s});
  check_distinct_files(inputs, output_roles("-o", scene_output_files(args.output)));
  std::vector<ExportScene> slices;
  for (const std::string& s : args.slices) slices.push_back(read_fissure_gltf(s));
  write_scene(args.output, merge_scene_slices(slices, args.slices));
  return kExitOk;
}

struct SceneDemoArgs {
  std::string which;
  std::string output;
  int slabs_along = DemoStreetOptions{}.slabs_along;
  int slabs_across = DemoStreetOptions{}.slabs_across;
  bool street_shape_given = false;  ///< --slabs or --rows given (the bathroom takes neither)
};

int run_scene_demo(const SceneDemoArgs& args) {
  ExportScene scene;
  if (args.which == "street") {
    DemoStreetOptions o;
    o.slabs_along = args.slabs_along;
    o.slabs_across = args.slabs_across;
    scene = demo_street(o);
  } else if (args.which == "bathroom") {
    if (args.street_shape_given) throw InvalidInput("scene demo bathroom: --slabs and --rows shape the street; the bathroom takes neither");
    scene = demo_bathroom();
  } else {
    throw InvalidInput("scene demo " + args.which + ": the demos are street and bathroom");
  }
  write_scene(args.output, scene);
  return kExitOk;
}

}  // namespace

void register_scene(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand("scene", std::string(command_info("scene").summary));
  cmd->require_subcommand(1);
  auto args = std::make_shared<SceneInfoArgs>();
  auto* info = cmd->add_subcommand("info", "List a scene's bodies, materials, sizes and which bodies can be fractured");
  add_threads_option(*info);
  info->add_option("SCENE", args->scene, "Scene file (glTF, GLB, FBX, DAE, OBJ, PLY, STL, OFF)")->required();
  info->add_flag("--json", args->json, "Print the result as JSON");
  info->add_flag("-q,--quiet", args->quiet, "No progress on stderr");
  info->callback([&action, args] { action = [args] { return run_scene_info(*args); }; });

  auto fr = std::make_shared<SceneFractureArgs>();
  auto* fracture = cmd->add_subcommand("fracture", "Fracture every body of the assigned materials and write the scene with its fragments");
  add_threads_option(*fracture);
  fracture->add_option("SCENE", fr->scene,
                       "Scene file (glTF, GLB, FBX, DAE, OBJ, PLY, STL, OFF), or a project (.json, docs/scenes.md) whose "
                       "settings the other options override")->required();
  fracture->add_option("--assign", fr->assign,
                       "SCENE_MATERIAL=MATERIAL or /node/path=MATERIAL (repeatable): a fracture material file or a "
                       "library name for every body of that scene material, or for one node (overrides)")
      ->check(parsed_by([](const std::string& text) { parse_assignments({text}); }));
  auto* seed = fracture->add_option("--seed", fr->seed, "Project seed; each body's own seed derives from it and its path (default 1)")->check(seed_value());
  // The age's range is the parameter table's, as `fissure fracture --age` has it: an age past it
  // would be refused by every body, one at a time.
  const ParameterInfo& age = fracture_parameter_info("age");
  fracture->add_option("--age", fr->age, "Age to simulate to (default: each material's)")->check(finite_in(age.min, age.max));
  fracture->add_option("--up", fr->up, "Up axis (+x, -y, …); default: the format's (+y for glTF)");
  fracture->add_option("--tets", fr->tets, "Tetrahedra per body (default: a fitted material's, else 6000)")
      ->type_name("N")->check(count_in(10, 5e7));
  fracture->add_option("--unit", fr->unit, "Metres per scene unit (0.01 for a scene in centimetres; default 1: the format's metres)")
      ->check(finite_in(1e-9, 1e9));
  fracture->add_option("--bodies", fr->bodies, "K/N: fracture slice K of N of the assigned bodies, leave the rest as they are")
      ->check(parsed_by([](const std::string& text) { parse_slice(text); }));
  fracture->add_flag("--strict", fr->strict, "Fail (and write nothing) when a body is skipped or an assignment matches nothing");
  fracture->add_flag("--no-cache", fr->no_cache, "Make every tet mesh afresh and cache none");
  fracture->add_option("--cache-dir", fr->cache_dir,
                       "Where tet meshes are cached by content (default: $FISSURE_CACHE_DIR, else $XDG_CACHE_HOME/fissure, "
                       "else ~/.cache/fissure; capped at $FISSURE_CACHE_MAX_MB, default 4096)");
  fracture->add_option("--report", fr->report, "Write a per-body report (JSON): fractured or skipped and why, seed, timings");
  fracture->add_flag("--allow-large", fr->allow_large, "Try bodies whose estimated memory exceeds this machine's");
  fracture->add_option("--crack-masks", fr->crack_masks,
                       "Also draw each fractured body's cracks in its texture (UV) space, for decals: DIR/<body path>.png, "
                       "white on black");
  fracture->add_option("--crack-mask-size", fr->crack_mask_size, "The crack masks' side in pixels (default 1024)")
      ->type_name("N")->check(count_in(16, 16384));
  fracture->add_option("--save-project", fr->save_project,
                       "Write the run's settings as a project (.json) before running: fissure scene fracture PROJECT "
                       "repeats the run (the project being run may be named: it is updated with this run's options)");
  fracture->add_option("-o,--output", fr->output,
                       "The scene with its fragments: .glb, .gltf, .obj (+ .mtl) or .ply (required unless a project gives it)");
  fracture->add_flag("-q,--quiet", fr->quiet, "Print nothing on success, no progress");
  fracture->callback([&action, fr, seed] {
    fr->seed_given = seed->count() > 0;
    action = [fr] { return run_scene_fracture(*fr); };
  });

  auto merge_args = std::make_shared<SceneMergeArgs>();
  auto* merge = cmd->add_subcommand("merge", "Join the slices of a fissure scene fracture --bodies K/N run into the file an unsliced run writes");
  merge->add_option("SLICES", merge_args->slices, "The slices' .glb or .gltf files, in any order")->required();
  merge->add_option("-o,--output", merge_args->output, "The merged scene: .glb, .gltf, .obj or .ply")->required();
  merge->callback([&action, merge_args] { action = [merge_args] { return run_scene_merge(*merge_args); }; });

  auto demo_args = std::make_shared<SceneDemoArgs>();
  auto* demo = cmd->add_subcommand("demo", "Write a demo scene (street or bathroom), as in assets/scenes/");
  demo->add_option("WHICH", demo_args->which, "street or bathroom")->required();
  demo->add_option("--slabs", demo_args->slabs_along, "Street: slabs along the kerb")->check(CLI::Range(1, 1000));
  demo->add_option("--rows", demo_args->slabs_across, "Street: rows of slabs")->check(CLI::Range(1, 100));
  demo->add_option("-o,--output", demo_args->output, "Output: .glb, .gltf, .obj or .ply")->required();
  demo->callback([&action, demo, demo_args] {
    demo_args->street_shape_given = demo->count("--slabs") + demo->count("--rows") > 0;
    action = [demo_args] { return run_scene_demo(*demo_args); };
  });
}

}  // namespace fissure::cli
