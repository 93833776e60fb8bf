// fissure mesh INPUT --tets N -o out.msh

#include "cli_common.hpp"
#include "command_table.hpp"
#include "commands.hpp"
#include "interruption.hpp"
#include "memory_estimate.hpp"
#include "option_checks.hpp"
#include "terminal_progress.hpp"

#include "fissure/base/number_text.hpp"
#include "fissure/base/distinct_files.hpp"
#include "fissure/io/msh.hpp"
#include "fissure/io/surface_import.hpp"
#include "fissure/mesh/tetrahedralize.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>

namespace fissure::cli {
namespace {

struct MeshArgs {
  std::string input;
  std::string output;
  double tets = 24000;  // a double so that "2e6" parses; count_in() keeps it whole
  unsigned seed = 0;
  bool binary = false;
  bool quiet = false;
  bool allow_large = false;
};

int run_mesh(const MeshArgs& args) {
  check_msh_output_path(args.output);
  check_distinct_files({{"the input", args.input}}, {{"-o", args.output}});
  const int tets = static_cast<int>(std::lround(args.tets));
  TerminalProgress progress(args.quiet);
  Stopwatch clock;
  SurfaceRepairReport repairs;
  TetrahedralizeReport report;
  TetMesh mesh;
  {
    AbandonableWork work;
    progress.stage("reading " + args.input);
    const SurfaceMesh surface = load_surface_input(args.input, repairs);
    TetrahedralizeOptions options;
    options.target_tets = tets;
    options.seed = args.seed;
    options.memory_limit_bytes = memory_limit(args.allow_large);
    mesh = tetrahedralize(surface, options, &report, &progress, &interrupt_token());
  }
  throw_if_interrupted();
  const double mesh_ms = clock.milliseconds();
  progress.stage("writing " + args.output);
  write_msh(args.output, mesh, {}, MshWriteOptions{args.binary});
  progress.clear();
  for (const std::string& action : repairs.actions) std::cerr << "fissure mesh: repaired " << args.input << ": " << action << '\n';
  for (const std::string& warning : report.warnings) std::cerr << "fissure mesh: warning: " << warning << '\n';
  if (!args.quiet) {
    std::fprintf(summary_stream(args.output),
                 "%s: %d tets, %d nodes, volume %s m^3, min dihedral %s deg, %d attempt(s), %lld ms -> %s\n",
                 args.input.c_str(), mesh.tet_count(), mesh.node_count(), format_number(mesh.total_volume()).c_str(),
                 format_number(report.quality.min_dihedral_deg, 3).c_str(), report.attempts, std::llround(mesh_ms),
                 args.output.c_str());
  }
  return kExitOk;
}

}  // namespace

void register_mesh(CLI::App& app, Action& action) {
  auto args = std::make_shared<MeshArgs>();
  auto* cmd = app.add_subcommand("mesh", std::string(command_info("mesh").summary));
  add_threads_option(*cmd);
  cmd->add_option("INPUT", args->input,
                  "Surface file (OBJ, PLY, STL, glTF/GLB, FBX, OFF) or tile:W,H,T (metres; x, y centred, z from 0 to T)")
      ->required();
  cmd->add_option("--tets", args->tets, "Target number of tetrahedra (the result lands within +-25 %)")
      ->default_val(24000)
      ->type_name("N")->check(count_in(10, 5e7));
  cmd->add_option("-o,--output", args->output, "Output mesh, gmsh MSH 4.1: a .msh file, or - for stdout")->required();
  cmd->add_option("--seed", args->seed, "Seed of the mesher's random generator (same seed, same mesh)")->check(seed_value())->default_val(0);
  cmd->add_flag("--binary", args->binary, "Write binary MSH instead of ASCII");
  cmd->add_flag("--allow-large", args->allow_large,
                "Try a mesh whose estimated memory exceeds this machine's (refused by default)");
  cmd->add_flag("-q,--quiet", args->quiet, "Print nothing on success, no progress");
  cmd->callback([&action, args] { action = [args] { return run_mesh(*args); }; });
}

}  // namespace fissure::cli
