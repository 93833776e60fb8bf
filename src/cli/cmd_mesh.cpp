// fissure mesh INPUT --tets N -o out.msh

#include "cli_common.hpp"
#include "commands.hpp"

#include "fissure/base/atomic_file.hpp"

#include "fissure/io/msh.hpp"
#include "fissure/io/surface_import.hpp"
#include "fissure/mesh/tetrahedralize.hpp"

#include <cstdio>
#include <iostream>

namespace fissure::cli {
namespace {

struct MeshArgs {
  std::string input;
  std::string output;
  int tets = 24000;
  unsigned seed = 0;
  bool binary = false;
  bool quiet = false;
};

int run_mesh(const MeshArgs& args) {
  check_output_path(args.output);
  Stopwatch clock;
  SurfaceRepairReport repairs;
  const SurfaceMesh surface = load_surface_input(args.input, repairs);
  for (const std::string& action : repairs.actions) std::cerr << "fissure mesh: repaired " << args.input << ": " << action << '\n';
  TetrahedralizeOptions options;
  options.target_tets = args.tets;
  options.seed = args.seed;
  TetrahedralizeReport report;
  const TetMesh mesh = tetrahedralize(surface, options, &report);
  const double mesh_ms = clock.milliseconds();
  for (const std::string& warning : report.warnings) std::cerr << "fissure mesh: warning: " << warning << '\n';
  write_msh(args.output, mesh, {}, MshWriteOptions{args.binary});
  if (!args.quiet) {
    std::printf("%s: %d tets, %d nodes, volume %.6g m^3, min dihedral %.1f deg, %d attempt(s), %.0f ms -> %s\n",
                args.input.c_str(), mesh.tet_count(), mesh.node_count(), mesh.total_volume(),
                report.quality.min_dihedral_deg, report.attempts, mesh_ms, args.output.c_str());
  }
  return kExitOk;
}

}  // namespace

void register_mesh(CLI::App& app, Action& action) {
  auto args = std::make_shared<MeshArgs>();
  auto* cmd = app.add_subcommand("mesh", "Tetrahedralise a closed surface (or a procedural tile) into a gmsh .msh file");
  cmd->add_option("INPUT", args->input,
                  "Surface file (OBJ, PLY, STL, glTF/GLB, FBX, OFF) or tile:W,H,T (metres; x, y centred, z from 0 to T)")
      ->required();
  cmd->add_option("--tets", args->tets, "Target number of tetrahedra (the result lands within +-25 %)")
      ->default_val(24000)
      ->check(CLI::Range(10, 50'000'000));
  cmd->add_option("-o,--output", args->output, "Output mesh, gmsh MSH 4.1")->required();
  cmd->add_option("--seed", args->seed, "Seed of the mesher's random generator (same seed, same mesh)")->default_val(0);
  cmd->add_flag("--binary", args->binary, "Write binary MSH instead of ASCII");
  cmd->add_flag("-q,--quiet", args->quiet, "Print nothing on success");
  cmd->callback([&action, args] { action = [args] { return run_mesh(*args); }; });
}

}  // namespace fissure::cli
