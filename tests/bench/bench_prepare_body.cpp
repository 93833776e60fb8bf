// Per-body preparation (issue 9): what a body costs before its first simulation, on one core.
// Tetrahedralise (CGAL Mesh_3 with sliver removal) + assemble K (gradients, pattern, values and
// the lumped mass: the ElasticBody) + the static operator (supports eliminated, CHOLMOD
// factorisation: the StaticSolver). Targets: ≤ 1 s at 7K tets, ≤ 1.7 s at 24K. Bodies: the
// 1 × 1 × 0.05 m tile, a unit sphere (bulky, curved, no sharp features) and the tile bent to a
// 1 m radius (thin, curved, sharp rim), tests/mesh/curved_shapes.hpp.

#include "bench_support.hpp"
#include "curved_shapes.hpp"

#include "fissure/fem/elastic_body.hpp"
#include "fissure/fem/static_solver.hpp"
#include "fissure/fem/supports.hpp"

#include <benchmark/benchmark.h>

#include <time.h>

namespace {
using namespace fissure;

enum Body { kTile = 0, kSphere = 1, kShell = 2 };

SurfaceMesh body_surface(int body) {
  if (body == kSphere) return test::icosphere(3);
  if (body == kShell) return test::curved_shell();
  return make_tile_surface({1.0, 1.0, 0.05});
}

// Supports that hold every body still: the tile's four bottom corners (bench_support.hpp), the
// sphere's nodes below z = −0.9 (a polar cap), the shell's nodes within 2 cm of its straight ends.
std::vector<int> body_supports(int body, const TetMesh& mesh) {
  if (body == kTile) return bench::corner_supports(mesh);
  std::vector<int> nodes;
  const double end = mesh.nodes().col(0).cwiseAbs().maxCoeff();
  for (int v = 0; v < mesh.node_count(); ++v) {
    const bool held = body == kSphere ? mesh.nodes()(v, 2) < -0.9 : std::abs(mesh.nodes()(v, 0)) > end - 0.02;
    if (held) nodes.push_back(v);
  }
  return dofs_of_nodes(nodes);
}

// CPU seconds of the whole process (CHOLMOD's OpenMP threads included): on the one pinned core
// bench.sh gives a benchmark this is its wall time, and on a shared machine it is not inflated
// by other processes' turns on that core.
double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

void BM_PrepareBody(benchmark::State& state) {
  const int body = static_cast<int>(state.range(0));
  TetrahedralizeOptions options;
  options.target_tets = static_cast<int>(state.range(1));
  const SurfaceMesh surface = body_surface(body);
  TetrahedralizeReport report;
  double mesh_s = 0.0, stiffness_s = 0.0, factor_s = 0.0;
  int tets = 0;
  for (auto _ : state) {
    double start = cpu_seconds();
    auto mesh = std::make_shared<const TetMesh>(tetrahedralize(surface, options, &report));
    mesh_s = cpu_seconds() - start;
    start = cpu_seconds();
    auto elastic = std::make_shared<const ElasticBody>(mesh, ElasticMaterial{});
    stiffness_s = cpu_seconds() - start;
    const std::vector<int> fixed = body_supports(body, *mesh);
    start = cpu_seconds();
    const StaticSolver solver(elastic, fixed);
    factor_s = cpu_seconds() - start;
    tets = mesh->tet_count();
    benchmark::DoNotOptimize(solver.factorization().factor_nonzeros());
  }
  state.SetLabel(surface.source_name);
  state.counters["tets"] = tets;
  state.counters["attempts"] = report.attempts;
  state.counters["min_dihedral_deg"] = report.quality.min_dihedral_deg;
  state.counters["tetrahedralize_s"] = mesh_s;
  state.counters["stiffness_s"] = stiffness_s;
  state.counters["factor_s"] = factor_s;
  state.counters["prepare_s"] = mesh_s + stiffness_s + factor_s;
}
BENCHMARK(BM_PrepareBody)
    ->ArgNames({"body", "tets"})
    ->Args({kTile, 7000})
    ->Args({kTile, 24000})
    ->Args({kTile, 54000})
    ->Args({kSphere, 7000})
    ->Args({kSphere, 24000})
    ->Args({kShell, 7000})
    ->Args({kShell, 24000})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
