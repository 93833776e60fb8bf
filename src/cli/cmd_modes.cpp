// fissure modes MESH --E .. --nu .. --rho .. --count k [--fix SEL…] [--mass lumped|consistent]

#include "cli_common.hpp"
#include "fem_options.hpp"
#include "command_table.hpp"
#include "commands.hpp"
#include "interruption.hpp"
#include "memory_estimate.hpp"
#include "terminal_progress.hpp"

#include "fissure/fem/modal_basis.hpp"
#include "fissure/fem/supports.hpp"
#include "fissure/io/msh.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <iostream>

namespace fissure::cli {
namespace {

struct ModesArgs {
  std::string mesh;
  ElasticMaterial material;
  int count = 10;
  std::vector<std::string> fix;
  std::string mass = "lumped";
  std::string cache_dir;
  bool no_cache = false;
  bool quiet = false;
  bool allow_large = false;
};

int run_modes(const ModesArgs& args) {
  validate_material_flags(args.material);
  TerminalProgress progress(args.quiet);
  Stopwatch clock;
  std::shared_ptr<const TetMesh> mesh;
  ModalBasis basis;
  bool loaded = false;
  {
    AbandonableWork work;
    progress.stage("reading " + args.mesh);
    mesh = std::make_shared<const TetMesh>(read_msh(args.mesh));
    std::vector<SupportSpec> supports;
    for (const std::string& spec : args.fix) supports.push_back(parse_support(spec));
    const std::vector<int> fixed = resolve_supports(*mesh, supports);
    progress.stage("assembling");
    auto body = std::make_shared<const ElasticBody>(mesh, args.material);
    throw_if_interrupted();
    ModalOptions options;
    options.mode_count = args.count;
    options.mass = mass_kind(args.mass);
    options.memory_limit_bytes = memory_limit(args.allow_large);
    basis = modal_basis_for(body, fixed, options, args.no_cache, args.cache_dir, loaded, progress, &interrupt_token());
  }
  throw_if_interrupted();
  progress.clear();
  nlohmann::json out;
  out["mesh"] = args.mesh;
  out["tets"] = mesh->tet_count();
  out["free_body"] = basis.free_body();
  out["mass"] = args.mass;
  out["rigid_modes"] = basis.rigid_modes().cols();
  const Eigen::VectorXd hz = basis.frequencies_hz();
  std::vector<double> frequencies(hz.data(), hz.data() + hz.size());
  out["frequencies_hz"] = frequencies;
  out["cached"] = loaded;
  out["milliseconds"] = std::llround(clock.milliseconds());
  std::cout << out.dump(2) << '\n';
  return kExitOk;
}

}  // namespace

void register_modes(CLI::App& app, Action& action) {
  auto args = std::make_shared<ModesArgs>();
  auto* cmd = app.add_subcommand("modes", std::string(command_info("modes").summary));
  add_threads_option(*cmd);
  cmd->add_option("MESH", args->mesh, "Tet mesh, gmsh .msh (2.2 or 4.1)")->required();
  add_material_options(*cmd, args->material, true);
  cmd->add_option("--count", args->count, "Number of flexible modes")->required()->check(CLI::Range(1, 5000));
  cmd->add_option("--fix", args->fix, "Support selection, as for solve (repeatable). None: free body (6 rigid modes "
                                      "per part are excluded)")
      ->allow_extra_args(false);
  cmd->add_option("--mass", args->mass, "Mass matrix")->check(CLI::IsMember({"lumped", "consistent"}))->default_val("lumped");
  cmd->add_option("--cache-dir", args->cache_dir, "Where modal bases are cached");
  cmd->add_flag("--no-cache", args->no_cache, "Do not read or write the cache");
  cmd->add_flag("--allow-large", args->allow_large,
                "Try an analysis whose estimated memory exceeds this machine's (refused by default)");
  cmd->add_flag("-q,--quiet", args->quiet, "No progress on stderr");
  cmd->callback([&action, args] { action = [args] { return run_modes(*args); }; });
}

}  // namespace fissure::cli
