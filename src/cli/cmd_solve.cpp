// fissure solve MESH --E .. --nu .. [--rho ..] --fix SEL… --load SPEC… [--modes m] -o result.msh

#include "cli_common.hpp"
#include "fem_options.hpp"
#include "command_table.hpp"
#include "commands.hpp"
#include "interruption.hpp"
#include "memory_estimate.hpp"
#include "option_checks.hpp"
#include "terminal_progress.hpp"

#include "fissure/base/error.hpp"
#include "fissure/base/distinct_files.hpp"
#include "fissure/base/thread_count.hpp"
#include "fissure/base/number_text.hpp"
#include "fissure/fem/load.hpp"
#include "fissure/base/memory.hpp"
#include "fissure/fem/modal_basis.hpp"
#include "fissure/fem/nodal_vectors.hpp"
#include "fissure/fem/static_solver.hpp"
#include "fissure/fem/stress.hpp"
#include "fissure/io/msh.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>

namespace fissure::cli {
namespace {

struct SolveArgs {
  std::string mesh;
  std::string output;
  ElasticMaterial material;
  std::vector<std::string> fix;
  std::vector<std::string> load;
  std::string gravity;
  int modes = 0;
  std::string mass = "lumped";
  std::string cache_dir;
  bool no_cache = false;
  bool binary = false;
  bool quiet = false;
  bool allow_large = false;
};

int run_solve(const SolveArgs& args) {
  validate_material_flags(args.material);
  check_msh_output_path(args.output);
  check_distinct_files({{"the input mesh", args.mesh}}, {{"-o", args.output}});
  if (args.load.empty() && args.gravity.empty()) throw InvalidInput("give at least one --load or --gravity");
  TerminalProgress progress(args.quiet);
  Stopwatch clock;
  std::shared_ptr<const TetMesh> mesh;
  std::vector<int> fixed;
  Eigen::VectorXd u;
  std::string method;
  double residual = 0.0;
  StressField stress;
  Eigen::VectorXd max_principal;
  std::shared_ptr<const ElasticBody> body;
  {
    AbandonableWork work;
    progress.stage("reading " + args.mesh);
    mesh = std::make_shared<const TetMesh>(read_msh(args.mesh));
    // The modal path is checked by ModalBasis::compute against options.memory_limit_bytes.
    if (args.modes == 0) {
      require_memory(static_solve_bytes(mesh->tet_count()), memory_limit(args.allow_large), "solving " + args.mesh);
    }

    // Loads and supports are checked before any expensive work.
    Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(mesh->node_count()));
    for (const std::string& spec : args.load) f += assemble_load(*mesh, parse_load(spec));
    if (!args.gravity.empty()) {
      const auto g = parse_number_list(args.gravity, "--gravity", 3, "gx,gy,gz (m/s^2)");
      f += gravity_load(*mesh, args.material.density, Eigen::Vector3d(g[0], g[1], g[2]));
    }
    std::vector<SupportSpec> supports;
    for (const std::string& spec : args.fix) supports.push_back(parse_support(spec));
    fixed = resolve_supports(*mesh, supports);
    check_supports_for_mechanisms(*mesh, fixed);
    const MassKind mass = mass_kind(args.mass);

    progress.stage("assembling");
    body = std::make_shared<const ElasticBody>(mesh, args.material, thread_count());
    throw_if_interrupted();
    if (args.modes > 0) {
      ModalOptions options;
      options.mode_count = args.modes;
      options.memory_limit_bytes = memory_limit(args.allow_large);
      options.mass = mass;
      bool loaded = false;
      const ModalBasis basis =
          modal_basis_for(body, fixed, options, args.no_cache, args.cache_dir, loaded, progress, &interrupt_token());
      u = basis.static_displacement(f);
      method = "modal, " + std::to_string(args.modes) + " modes" + (loaded ? " (cached basis)" : "");
    } else {
      progress.stage("solving");
      StaticSolverOptions options;
      options.mass = mass;
      const StaticSolver solver(body, fixed, options);
      throw_if_interrupted();
      const StaticSolution solution = solver.solve(f);
      u = solution.displacement;
      residual = solution.relative_residual;
      method = "direct";
    }
    throw_if_interrupted();
    progress.stage("computing stress");
    compute_stress_and_max_principal(*body, u, stress, max_principal);
  }
  throw_if_interrupted();

  Eigen::MatrixXd displacement(mesh->node_count(), 3);
  for (int v = 0; v < mesh->node_count(); ++v) displacement.row(v) = u.segment<3>(3 * v).transpose();
  progress.stage("writing " + args.output);
  write_msh(args.output, *mesh,
            {{"displacement", MshView::Kind::NodeData, displacement},
             {"stress", MshView::Kind::ElementData, voigt_rows_to_tensor_rows(stress)},
             {"max_principal_stress", MshView::Kind::ElementData, max_principal}},
            MshWriteOptions{args.binary});
  progress.clear();
  if (!args.quiet) {
    std::FILE* out = summary_stream(args.output);
    if (fixed.empty()) std::fprintf(out, "no --fix: free body, solved by inertia relief\n");
    const std::string residual_text = args.modes == 0 ? ", residual " + format_number(residual, 2) : std::string();
    Eigen::Index peak_tet = 0;
    const double peak = max_principal.maxCoeff(&peak_tet);
    std::fprintf(out, "%s: %d tets, %s%s, max |u| %s m, peak max principal stress %s Pa (%s), %lld ms -> %s\n",
                 args.mesh.c_str(), mesh->tet_count(), method.c_str(), residual_text.c_str(),
                 format_number(max_nodal_magnitude(u).magnitude, 4).c_str(), format_number(peak, 4).c_str(),
                 mesh->tet_label(static_cast<int>(peak_tet)).c_str(), std::llround(clock.milliseconds()),
                 args.output.c_str());
  }
  return kExitOk;
}

}  // namespace

void register_solve(CLI::App& app, Action& action) {
  auto args = std::make_shared<SolveArgs>();
  auto* cmd = app.add_subcommand("solve", std::string(command_info("solve").summary));
  add_threads_option(*cmd);
  cmd->add_option("MESH", args->mesh, "Tet mesh, gmsh .msh (2.2 or 4.1)")->required();
  add_material_options(*cmd, args->material, false);
  cmd->add_option("--fix", args->fix,
                  "Support: box:x0,x1,y0,y1,z0,z1 | ball:x,y,z,r | PHYSICAL_GROUP, optionally @x, @yz... to fix only "
                  "those components (repeatable). None: free body, inertia relief")
      ->allow_extra_args(false);
  cmd->add_option("--load", args->load, "Load SEL=fx,fy,fz: total force in N spread area-weighted over the selection's "
                                        "boundary faces (repeatable)")
      ->allow_extra_args(false);
  cmd->add_option("--gravity", args->gravity, "Gravity gx,gy,gz in m/s^2, e.g. 0,0,-9.81");
  cmd->add_option("--modes", args->modes, "Solve by modal superposition with this many modes (default: direct solve)")
      ->check(CLI::Range(1, 5000));
  cmd->add_option("--mass", args->mass, "Mass matrix for modes and inertia relief")
      ->check(CLI::IsMember({"lumped", "consistent"}))
      ->default_val("lumped");
  cmd->add_option("--cache-dir", args->cache_dir, "Where modal bases are cached (default $FISSURE_CACHE_DIR or ~/.cache/fissure)");
  cmd->add_flag("--no-cache", args->no_cache, "Compute the modal basis without reading or writing the cache");
  cmd->add_option("-o,--output", args->output, "Result file, gmsh MSH 4.1 with views: a .msh file, or - for stdout")
      ->required();
  cmd->add_flag("--binary", args->binary, "Write binary MSH instead of ASCII");
  cmd->add_flag("--allow-large", args->allow_large,
                "Try a solve whose estimated memory exceeds this machine's (refused by default)");
  cmd->add_flag("-q,--quiet", args->quiet, "Print nothing on success, no progress");
  cmd->callback([&action, args] { action = [args] { return run_solve(*args); }; });
}

}  // namespace fissure::cli
