// Tetrahedralisation of the 1 × 1 × 0.05 m tile (CGAL Mesh_3, perturb + exude) at the paper's
// three resolutions. Target (issue 3): 24K tets ≤ 1 s on one core.

#include "bench_support.hpp"

#include <benchmark/benchmark.h>

namespace {

void BM_Tetrahedralize(benchmark::State& state) {
  using namespace fissure;
  TetrahedralizeOptions options;
  options.target_tets = static_cast<int>(state.range(0));
  const SurfaceMesh surface = make_tile_surface({1.0, 1.0, 0.05});
  TetrahedralizeReport report;
  int tets = 0;
  for (auto _ : state) {
    const TetMesh mesh = tetrahedralize(surface, options, &report);
    tets = mesh.tet_count();
    benchmark::DoNotOptimize(tets);
  }
  state.counters["tets"] = tets;
  state.counters["min_dihedral_deg"] = report.quality.min_dihedral_deg;
  state.counters["attempts"] = report.attempts;
}
BENCHMARK(BM_Tetrahedralize)->Arg(7000)->Arg(24000)->Arg(54000)->Unit(benchmark::kMillisecond)->Iterations(1);

// The same with a cancel token that is never raised, as the CLI calls it: sliver removal then
// runs through Fissure's watched CGAL passes instead of the free functions (same mesh, tested
// in tetrahedralize_test); the difference is the cost of watching.
void BM_TetrahedralizeWatched(benchmark::State& state) {
  using namespace fissure;
  TetrahedralizeOptions options;
  options.target_tets = static_cast<int>(state.range(0));
  const SurfaceMesh surface = make_tile_surface({1.0, 1.0, 0.05});
  const CancelToken never;
  TetrahedralizeReport report;
  int tets = 0;
  for (auto _ : state) {
    const TetMesh mesh = tetrahedralize(surface, options, &report, nullptr, &never);
    tets = mesh.tet_count();
    benchmark::DoNotOptimize(tets);
  }
  state.counters["tets"] = tets;
  state.counters["min_dihedral_deg"] = report.quality.min_dihedral_deg;
  state.counters["attempts"] = report.attempts;
}
BENCHMARK(BM_TetrahedralizeWatched)->Arg(24000)->Arg(54000)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
