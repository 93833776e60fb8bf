// fissure fracture INPUT [--material M] [parameter flags] [--fix SEL…] [--load SPEC…] [--up A]
//   [--free] [--fragments N] [--seed S] [--tets N] [-o fragments.glb|gltf|obj|ply] [--pattern p.png]
//   [--stats s.json] [--msh out.msh]

#include "cli_common.hpp"
#include "command_table.hpp"
#include "commands.hpp"
#include "interruption.hpp"
#include "memory_estimate.hpp"
#include "option_checks.hpp"
#include "terminal_progress.hpp"

#include "fissure/base/atomic_file.hpp"
#include "fissure/base/distinct_files.hpp"
#include "fissure/base/error.hpp"
#include "fissure/base/memory.hpp"
#include "fissure/base/number_text.hpp"
#include "fissure/base/thread_count.hpp"
#include "fissure/exemplar/stats_json.hpp"
#include "fissure/fracture/fitted_transfer.hpp"
#include "fissure/fracture/fragment_mesh.hpp"
#include "fissure/fracture/fragment_target.hpp"
#include "fissure/fracture/material_file.hpp"
#include "fissure/fracture/overload.hpp"
#include "fissure/fracture/pattern_image.hpp"
#include "fissure/fracture/prepared_body.hpp"
#include "fissure/fracture/resistance_field.hpp"
#include "fissure/fracture/visible_pattern.hpp"
#include "fissure/io/msh.hpp"
#include "fissure/io/scene_export.hpp"
#include "fissure/io/surface_import.hpp"
#include "fissure/mesh/tetrahedralize.hpp"
#include "fissure/mesh/tile.hpp"
#include "fissure/scene/fragment_export.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <optional>
#include <cstdio>
#include <iostream>
#include <map>

namespace fissure::cli {
namespace {

struct FractureArgs {
  std::string input;
  bool tets_given = false;  // --tets on the command line (else a fitted material's body count)
  bool posterior = false;   // draw the five fitted parameters from a fitted material's posterior
  std::string material = kDefaultMaterialName;
  std::map<std::size_t, double> overrides;  // table row → value given on the command line
  std::string relaxation;
  std::vector<std::string> fix;
  std::vector<std::string> load;
  std::string up;
  std::string view;
  bool free_body = false;
  double fragments = 0;
  std::uint64_t seed = 1;
  double tets = 24000;
  std::string output;
  std::string pattern;
  double pattern_size = 1024;
  std::string stats;
  std::string msh;
  bool raw_stress = false;
  bool quiet = false;
  bool allow_large = false;
};

// The up axis of the input's own convention: glTF, FBX, COLLADA and OBJ (as Blender writes it,
// and as `fissure scene` reads it) are +Y up, the rest (tile:, .msh, STL, PLY, OFF) +Z.
Eigen::Vector3d default_up(const std::string& input) {
  const std::string ext = is_tile_spec(input) ? std::string() : lower_extension(input);
  if (ext == ".gltf" || ext == ".glb" || ext == ".fbx" || ext == ".dae" || ext == ".obj") return Eigen::Vector3d::UnitY();
  return Eigen::Vector3d::UnitZ();
}

Eigen::Vector3d parse_direction(const std::string& text, const std::string& flag) {
  if (text.find(',') == std::string::npos) {
    try {
      return parse_up_axis(text);
    } catch (const InvalidInput&) {
      throw InvalidInput(flag + " " + text + " is not an axis (+x, -y, …) nor a direction x,y,z");
    }
  }
  const auto v = parse_number_list(text, flag, 3, "x,y,z");
  const Eigen::Vector3d d(v[0], v[1], v[2]);
  if (!(d.norm() > 0.0)) throw InvalidInput(flag + " " + text + " is the zero vector");
  return d.normalized();
}

FractureParams params_from(const FractureArgs& args, std::string& material_name, std::optional<MaterialFit>& fit) {
  const FractureMaterial material = load_material(find_material(args.material));
  material_name = material.name;
  fit = material.fit;
  FractureParams p = material.params;
  for (const auto& [row, value] : args.overrides) parameter_value(p, row) = value;
  if (!args.relaxation.empty()) {
    const auto choice = parse_relaxation_choice(args.relaxation);
    if (!choice) throw InvalidInput("--relaxation " + args.relaxation + " is not one of " + relaxation_choice_names());
    p.relaxation = *choice;
  }
  const std::vector<std::string> problems = p.problems(true);
  if (!problems.empty()) {
    std::string text;
    for (const std::string& s : problems) text += (text.empty() ? "" : "; ") + s;
    throw InvalidInput(text);
  }
  return p;
}

// The tet mesh of the input; `appearance` receives the input surface's materials and UVs (none
// for a .msh or a tile).
std::shared_ptr<const TetMesh> mesh_from(const FractureArgs& args, TerminalProgress& progress, SurfaceAppearance& appearance) {
  progress.stage("reading " + args.input);
  if (!is_tile_spec(args.input) && lower_extension(args.input) == ".msh") {
    return std::make_shared<const TetMesh>(read_msh(args.input));
  }
  SurfaceRepairReport repairs;
  SurfaceMesh surface = load_surface_input(args.input, repairs);
  appearance = std::move(surface.appearance);
  for (const std::string& action : repairs.actions) std::cerr << "fissure fracture: repaired " << args.input << ": " << action << '\n';
  TetrahedralizeOptions options;
  options.target_tets = static_cast<int>(std::lround(args.tets));
  options.memory_limit_bytes = memory_limit(args.allow_large);
  TetrahedralizeReport report;
  auto mesh = std::make_shared<const TetMesh>(tetrahedralize(surface, options, &report, &progress, &interrupt_token()));
  for (const std::string& warning : report.warnings) std::cerr << "fissure fracture: warning: " << warning << '\n';
  return mesh;
}

// The first crack time of every tet, −1 for a tet no crack cuts (a gmsh view value).
Eigen::VectorXd crack_onset(const TetMesh& mesh, const FractureResult& r) {
  Eigen::VectorXd onset = Eigen::VectorXd::Constant(mesh.tet_count(), -1.0);
  for (const CrackSurface& c : r.cracks) {
    for (const CrackCut& cut : c.cuts) {
      if (onset(cut.tet) < 0.0) onset(cut.tet) = c.time;
    }
  }
  return onset;
}

int run_fracture(const FractureArgs& given) {
  std::string material_name;
  std::optional<MaterialFit> fit;
  FractureParams params = params_from(given, material_name, fit);
  FractureArgs args = given;
  if (args.posterior) {
    if (!fit) throw InvalidInput("--posterior needs a fitted material (written by fissure fit); " + material_name + " has no fit");
    params = draw_from_posterior(*fit, params, args.seed);
    // Parameters given on the command line still win over the draw.
    for (const auto& [row, value] : args.overrides) parameter_value(params, row) = value;
  }
  // A fitted material reproduces its fit on a tile: the fit body's resolution and the fit's load
  // rule (a patch at a drawn cell of the top face's grid), unless --tets or --load say otherwise.
  if (fit && !args.tets_given) args.tets = fit->body_tets;
  const bool fitted_load_rule = fit && args.load.empty() && !args.free_body && is_tile_spec(args.input);
  for (const std::string* path : {&args.pattern, &args.stats}) {
    if (!path->empty()) check_output_path(*path);
  }
  if (!args.msh.empty()) check_msh_output_path(args.msh);
  if (args.pattern == "-" || args.msh == "-" || args.output == "-")
    throw InvalidInput("--pattern, --msh and -o write files; only --stats may be -");
  if (!args.output.empty()) check_scene_output_path(args.output);
  {
    std::vector<RoleAndPath> outputs = output_roles("-o", scene_output_files(args.output));  // "" is ignored
    for (const RoleAndPath& o : std::vector<RoleAndPath>{{"--pattern", args.pattern}, {"--stats", args.stats}, {"--msh", args.msh}})
      outputs.push_back(o);
    check_distinct_files({{"the input", args.input}, {"--material", args.material}}, outputs);
  }
  FractureScenario scenario;
  scenario.up = args.up.empty() ? default_up(args.input) : parse_direction(args.up, "--up");
  scenario.free_body = args.free_body;
  for (const std::string& spec : args.fix) scenario.supports.push_back(parse_support(spec));
  for (const std::string& spec : args.load) scenario.loads.push_back(parse_load(spec));
  const Eigen::Vector3d view = args.view.empty() ? scenario.up : parse_direction(args.view, "--view");

  TerminalProgress progress(args.quiet);
  Stopwatch clock;
  std::shared_ptr<const TetMesh> mesh;
  SurfaceAppearance appearance;
  std::unique_ptr<PreparedBody> prepared;
  StressField initial;
  Eigen::VectorXd resistance;
  FragmentTargetResult target;
  double preparation_s = 0.0, simulation_s = 0.0;
  double length_scale = 1.0, fitted_force = 0.0;
  {
    AbandonableWork work;
    mesh = mesh_from(args, progress, appearance);
    require_memory(static_solve_bytes(mesh->tet_count()), memory_limit(args.allow_large), "fracturing " + args.input);
    if (fit) {
      // A fitted material's lengths follow the body's visible face (fitted_transfer.hpp); the
      // values given on the command line are the user's own and stay as given.
      params = fitted_params_on(*fit, params, *mesh, view, &length_scale);
      for (const auto& [row, value] : args.overrides) parameter_value(params, row) = value;
    }
    // The fitted load rule's patch pushes with 1 N until the body is prepared: its force keeps the
    // fit's stress, which takes the prepared body to measure.
    if (fitted_load_rule) scenario.loads = {fitted_load(*mesh, scenario.up, fit->load_grid, fit->load_inset, 1.0, args.seed)};
    progress.stage("preparing the body");
    prepared = std::make_unique<PreparedBody>(mesh, params.elastic(), scenario, thread_count());
    throw_if_interrupted();
    initial = prepared->initial_stress(params, !args.raw_stress);
    if (fitted_load_rule) {
      fitted_force = fitted_load_force(*fit, params, *prepared);
      initial *= fitted_force;
    }
    if (const auto overload = overload_note(initial, params)) std::cerr << "fissure fracture: warning: " << *overload << '\n';
    resistance = draw_resistance(mesh->centroids(), params, args.seed, thread_count());
    preparation_s = clock.milliseconds() / 1e3;
    progress.stage("simulating");
    SimulationOptions options;
    options.progress = &progress;
    options.cancel = &interrupt_token();
    if (args.fragments > 0 && !args.output.empty()) {
      // The meshes are what is written: their count is the one aimed at.
      target = simulate_to_fragment_mesh_count(prepared->fracture_body(), params, initial, resistance, args.seed,
                                               static_cast<int>(std::lround(args.fragments)), thread_count(), options);
    } else if (args.fragments > 0) {
      target = simulate_to_fragment_count(prepared->fracture_body(), params, initial, resistance, args.seed,
                                          static_cast<int>(std::lround(args.fragments)), options);
    } else {
      target.result = simulate_fracture(prepared->fracture_body(), params, initial, resistance, args.seed, options);
      target.age = target.result.simulated_age;
      target.reached = true;
    }
    simulation_s = clock.milliseconds() / 1e3 - preparation_s - target.meshing_seconds;
  }
  throw_if_interrupted();
  const FractureResult& result = target.result;

  progress.stage("measuring the visible pattern");
  VisiblePatternOptions pattern_options;
  pattern_options.reference_long_side_px = static_cast<int>(std::lround(args.pattern_size));
  const VisiblePattern visible =
      extract_visible_pattern(*mesh, result.cracks, static_cast<int>(result.cracks.size()), view, pattern_options);
  PatternStats stats;
  if (visible.has_visible_face) stats = compute_pattern_stats(visible.graph, visible.stats_options);

  // The fragments as closed meshes, only when they are written.
  double meshing_s = 0.0, export_s = 0.0;
  std::size_t fragment_meshes = 0;
  if (!args.output.empty()) {
    progress.stage("meshing the fragments");
    Stopwatch meshing;
    const std::vector<FragmentMesh> fragments =
        target.meshings > 0 ? std::move(target.meshes)
                            : mesh_fragments(*mesh, result.cracks, static_cast<int>(result.cracks.size()), thread_count());
    meshing_s = target.meshings > 0 ? target.meshing_seconds : meshing.milliseconds() / 1e3;
    fragment_meshes = fragments.size();
    progress.stage("writing " + args.output);
    Stopwatch exporting;
    ExportScene scene = fragment_scene(fragments, result.cracks, params.density, appearance);
    // The fragments are in the input's frame; the writer turns them to the format's up.
    scene.up = scenario.up;
    scene.frame_name = is_tile_spec(args.input) ? "tile" : std::filesystem::path(args.input).stem().string();
    write_scene(args.output, scene);
    export_s = exporting.milliseconds() / 1e3;
  }

  nlohmann::ordered_json fracture = {
      {"material", material_name},
      {"seed", args.seed},
      {"age", target.age},
      {"tets", mesh->tet_count()},
      {"fragments", result.fragments.count},
      {"cracks", result.cracks.size()},
      {"partial_cracks", result.partial_cracks.size()},
      {"crack_limit_reached", result.crack_limit_reached},
      {"seconds", {{"preparation", preparation_s}, {"simulation", simulation_s}, {"fragment_meshing", meshing_s}, {"export", export_s}}}};
  if (args.fragments > 0) fracture["fragments_requested"] = std::lround(args.fragments);
  if (fitted_load_rule) {
    fracture["fitted_load"] = fitted_load(*mesh, scenario.up, fit->load_grid, fit->load_inset, fitted_force, args.seed).spec;
  }
  if (fit) fracture["fitted_length_scale"] = length_scale;
  if (args.posterior) {
    nlohmann::ordered_json drawn = nlohmann::ordered_json::object();
    for (const FitPrior& prior : table3_priors()) {
      drawn[prior.name] = parameter_value(params, static_cast<std::size_t>(find_fracture_parameter(prior.name)));
    }
    fracture["posterior_draw"] = drawn;
  }
  // The closed meshes' own count: exact where the labeller probes seven points per face.
  if (!args.output.empty()) fracture["fragment_meshes"] = fragment_meshes;
  if (target.meshings > 0) fracture["fragment_meshings"] = target.meshings;  // --fragments counted meshes

  progress.stage("writing");
  if (!args.stats.empty()) {
    nlohmann::ordered_json out;
    if (visible.has_visible_face) {
      out = nlohmann::ordered_json::parse(pattern_stats_to_json(stats));
    } else {
      out["pattern"] = "empty";
      out["reason"] = visible.empty_reason;
    }
    out["fracture"] = fracture;
    const std::string text = out.dump(2) + "\n";
    if (args.stats == "-") {
      std::fwrite(text.data(), 1, text.size(), stdout);
    } else {
      write_file_atomically(args.stats, text);
    }
  }
  if (!args.pattern.empty()) {
    if (!visible.has_visible_face) throw InvalidInput("--pattern " + args.pattern + ": " + visible.empty_reason);
    PatternImageOptions image_options;
    image_options.long_side_px = pattern_options.reference_long_side_px;
    image_options.line_width_px = pattern_options.line_width_px;
    write_pattern_image(args.pattern, render_pattern_image(visible, image_options));
  }
  if (!args.msh.empty()) {
    Eigen::VectorXd labels(mesh->tet_count());
    std::vector<NamedSet> groups;
    for (int k = 0; k < result.fragments.count; ++k)
      groups.push_back({fragment_name(k, result.fragments.count), 3, {}, {}, {}});
    for (int t = 0; t < mesh->tet_count(); ++t) {
      const int k = result.fragments.fragment_of_tet[static_cast<std::size_t>(t)];
      labels(t) = k;
      groups[static_cast<std::size_t>(k)].tets.push_back(t);
    }
    write_msh(args.msh, *mesh,
              {{"fragment", MshView::Kind::ElementData, labels},
               {"crack_onset_time", MshView::Kind::ElementData, crack_onset(*mesh, result)},
               {"resistance", MshView::Kind::ElementData, resistance}},
              {}, groups);
  }
  progress.clear();
  if (!target.reached) std::cerr << "fissure fracture: warning: --fragments: " << target.reason << '\n';
  if (!args.quiet) {
    std::FILE* out = args.stats == "-" ? stderr : stdout;
    std::string pattern_text = visible.has_visible_face
                                   ? std::to_string(stats.fragment_count) + " fragments, " +
                                         std::to_string(stats.junction_count) + " junctions on the visible face"
                                   : "no visible face (" + visible.empty_reason + ")";
    // With -o the count is the meshes written (what the artist opens); the labeller's count, which
    // can run ahead of it on dense patterns (fragment_target.hpp), only without.
    const std::string fragment_text = args.output.empty()
                                          ? std::to_string(result.fragments.count) + " fragments"
                                          : std::to_string(fragment_meshes) + " fragments written to " + args.output;
    std::fprintf(out, "%s: %d tets, %s, age %s: %zu cracks (%zu partial), %s; %s; %s s preparation, %s s simulation\n",
                 args.input.c_str(), mesh->tet_count(), material_name.c_str(), format_number(target.age, 4).c_str(),
                 result.cracks.size(), result.partial_cracks.size(), fragment_text.c_str(), pattern_text.c_str(),
                 format_number(preparation_s, 3).c_str(), format_number(simulation_s, 3).c_str());
  }
  return kExitOk;
}

}  // namespace

void register_fracture(CLI::App& app, Action& action) {
  auto args = std::make_shared<FractureArgs>();
  auto* cmd = app.add_subcommand("fracture", std::string(command_info("fracture").summary));
  add_threads_option(*cmd);
  cmd->add_option("INPUT", args->input,
                  "Closed surface (OBJ, PLY, STL, glTF/GLB, FBX, OFF), a tet mesh (.msh) or tile:W,H,T (metres)")
      ->required();
  cmd->add_option("--material", args->material,
                  "Fracture material: a bundled name (" + [] {
                    std::string names;
                    for (const std::string& n : bundled_material_names()) names += (names.empty() ? "" : ", ") + n;
                    return names;
                  }() + ") or a .json file")
      ->default_val(kDefaultMaterialName);
  const auto& table = fracture_parameter_table();
  for (std::size_t row = 0; row < table.size(); ++row) {
    const ParameterInfo& info = table[row];
    // The unit is in the range the check shows ("NUM:in (0, 100] m").
    std::string help = std::string(info.help) + " (overrides the material's)";
    cmd->add_option_function<double>(
           info.flag, [args, row](double value) { args->overrides[row] = value; }, help)
        ->type_name("NUM")
        ->check(parameter_range(info));
  }
  cmd->add_option("--relaxation", args->relaxation, "Stress relaxation: directional (Eq. 3), isotropic (Eq. 4)");
  cmd->add_option("--fix", args->fix,
                  "Support SEL or SEL@xyz (repeatable); default: rollers on the rim of the lowest face");
  cmd->add_option("--load", args->load,
                  "Load SEL[^nx,ny,nz]=fx,fy,fz in N (repeatable); default: a patch at the centre of the top face "
                  "pushing down with load_factor x body weight");
  cmd->add_flag("--free", args->free_body, "Hold nothing: the load is balanced by inertia (inertia relief)");
  cmd->add_option("--up", args->up, "Up axis (+x, -y, … or x,y,z); default: +y for glTF/FBX/DAE/OBJ, else +z");
  cmd->add_option("--view", args->view, "Direction the visible face looks along (default: up)");
  cmd->add_option("--fragments", args->fragments, "Reach about N fragments (+-20 %) by choosing the age; with -o, N closed meshes")
      ->type_name("N")->check(count_in(1, 1e6));
  cmd->add_option("--seed", args->seed, "Seed of the resistance field and the crack noise")->check(seed_value())->default_val(1);
  cmd->add_flag("--posterior", args->posterior,
                "Draw the five fitted parameters from a fitted material's posterior (per seed: similar, not identical)");
  cmd->add_option("--tets", args->tets, "Target number of tetrahedra for a surface input (a fitted material: its fit body's)")
      ->default_val(24000)
      ->type_name("N")->check(count_in(10, 5e7));
  cmd->add_option("-o,--output", args->output,
                  "Write the fragments as closed meshes, one object each: .glb, .gltf, .obj (+ .mtl) or .ply");
  cmd->add_option("--pattern", args->pattern, "Write the visible crack pattern as a line drawing (PNG)")->check(png_path());
  cmd->add_option("--pattern-size", args->pattern_size, "Long side of the pattern drawing, pixels")
      ->default_val(1024)
      ->type_name("N")->check(count_in(64, 16384));
  cmd->add_option("--stats", args->stats,
                  "Write the visible pattern's statistics (the schema of fissure analyze --json, plus \"fracture\"); - for stdout");
  cmd->add_option("--msh", args->msh, "Write the tet mesh with fragment labels and crack-onset times as gmsh views");
  cmd->add_flag("--raw-stress", args->raw_stress, "Use the raw per-tet stress instead of the recovered one");
  cmd->add_flag("--allow-large", args->allow_large, "Try a body whose estimated memory exceeds this machine's");
  cmd->add_flag("-q,--quiet", args->quiet, "Print nothing on success, no progress");
  cmd->callback([&action, args, cmd] {
    args->tets_given = cmd->count("--tets") > 0;
    action = [args] { return run_fracture(*args); };
  });
}

}  // namespace fissure::cli
