// Time against error of the mesh resolution: the tile of bench_fem (1 × 1 × 0.05 m, corner
// supports, 10 kN on a 5 cm centre patch) solved directly at increasing tet counts and compared
// with a 200K-tet reference. Meshes differ, so the errors compare quantities every mesh defines:
//   compliance fᵀu (twice the strain energy; converges from below, the global measure),
//   the volume mean of the max principal stress over the bottom half under the centre
//   (|x|, |y| ≤ 0.1 m, z ≤ T/2: where the tile cracks first),
//   the peak max principal stress in that region, and over the whole tile (the corner supports
//   are 5 cm patches whose edges concentrate stress: that peak is not expected to converge).
// The time is meshing + assembly + factorisation + solve + stress: what a body costs the first
// time it fractures at that resolution.

#include "bench_support.hpp"

#include "fissure/fem/elastic_body.hpp"
#include "fissure/fem/static_solver.hpp"
#include "fissure/fem/stress.hpp"

#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>

namespace {
using namespace fissure;

struct Measures {
  double compliance = 0.0;
  double centre_mean_stress = 0.0;
  double centre_peak_stress = 0.0;
  double global_peak_stress = 0.0;
  int tets = 0;
};

Measures solve_tile(const std::shared_ptr<const TetMesh>& mesh) {
  auto body = std::make_shared<const ElasticBody>(mesh, ElasticMaterial{});
  const StaticSolver solver(body, bench::corner_supports(*mesh));
  const Eigen::VectorXd f = bench::centre_patch(*mesh);
  const Eigen::VectorXd u = solver.solve(f).displacement;
  StressField stress;
  Eigen::VectorXd smax;
  compute_stress_and_max_principal(*mesh, body->gradients(), body->material(), u, stress, smax);
  Measures m;
  m.tets = mesh->tet_count();
  m.compliance = f.dot(u);
  m.global_peak_stress = smax.maxCoeff();
  double volume = 0.0, integral = 0.0;
  for (int t = 0; t < mesh->tet_count(); ++t) {
    const Eigen::Vector3d c = mesh->centroid(t);
    if (std::abs(c.x()) > 0.1 || std::abs(c.y()) > 0.1 || c.z() > 0.025) continue;
    volume += mesh->volumes()[t];
    integral += mesh->volumes()[t] * smax[t];
    m.centre_peak_stress = std::max(m.centre_peak_stress, smax[t]);
  }
  m.centre_mean_stress = integral / volume;
  return m;
}

const Measures& reference() {
  static const Measures r = [] {
    TetrahedralizeOptions options;
    options.target_tets = 200000;
    return solve_tile(std::make_shared<const TetMesh>(tetrahedralize(make_tile_surface({1.0, 1.0, 0.05}), options)));
  }();
  return r;
}

double percent(double value, double reference_value) { return 100.0 * (value - reference_value) / reference_value; }

void BM_MeshResolutionVsReference(benchmark::State& state) {
  const Measures& ref = reference();
  Measures m;
  for (auto _ : state) {
    TetrahedralizeOptions options;
    options.target_tets = static_cast<int>(state.range(0));
    m = solve_tile(std::make_shared<const TetMesh>(tetrahedralize(make_tile_surface({1.0, 1.0, 0.05}), options)));
  }
  state.counters["tets"] = m.tets;
  state.counters["reference_tets"] = ref.tets;
  state.counters["compliance_err_pct"] = percent(m.compliance, ref.compliance);
  state.counters["centre_mean_err_pct"] = percent(m.centre_mean_stress, ref.centre_mean_stress);
  state.counters["centre_peak_err_pct"] = percent(m.centre_peak_stress, ref.centre_peak_stress);
  state.counters["global_peak_err_pct"] = percent(m.global_peak_stress, ref.global_peak_stress);
  state.counters["centre_mean_MPa"] = m.centre_mean_stress / 1e6;
  state.counters["global_peak_MPa"] = m.global_peak_stress / 1e6;
}
BENCHMARK(BM_MeshResolutionVsReference)
    ->Arg(7000)->Arg(14000)->Arg(24000)->Arg(54000)->Arg(100000)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
