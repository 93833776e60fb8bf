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

}  // namespace

BENCHMARK_MAIN();
