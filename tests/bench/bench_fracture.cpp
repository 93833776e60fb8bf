// The fracture simulation alone (issue 10): the body prepared and σ⁰ computed once, then
// simulate_fracture per iteration, and the same plus the visible pattern and its statistics.
// Targets (one core): 7K-tet tile with 4–5 cracks ≤ 2 ms; 54K-tet 1 × 1 × 0.1 m slab with about
// 270 cracks at r_relax = 5 cm ≤ 50 ms (the paper on 2008 hardware: 16 and 264 ms).
// Bodies: structured (6 tets per cell) so the tet counts are exact: a 1 × 1 × 0.02 m tile of
// 24 × 24 × 2 cells (6,912 tets) and the slab of 30 × 30 × 10 cells (54,000). The crack count is
// set by SimulationOptions::max_cracks on a run whose age would open more, so each row times
// exactly the number of cracks it names (the counter `cracks` says so).

#include "fissure/fracture/prepared_body.hpp"
#include "fissure/fracture/resistance_field.hpp"
#include "fissure/fracture/simulation.hpp"
#include "fissure/fracture/visible_pattern.hpp"
#include "fissure/mesh/structured_box.hpp"

#include <benchmark/benchmark.h>

#include <map>
#include <memory>

namespace {
using namespace fissure;

struct Case {
  std::unique_ptr<PreparedBody> body;
  FractureParams params;
  StressField initial;
  Eigen::VectorXd resistance;
};

// body 0: the 7K tile, 1: the 54K slab.
const Case& prepared(int body) {
  static std::map<int, Case> cases;
  auto it = cases.find(body);
  if (it != cases.end()) return it->second;
  Case c;
  const bool slab = body == 1;
  auto mesh = std::make_shared<const TetMesh>(make_structured_box(
      Eigen::Vector3d(-0.5, -0.5, 0.0), Eigen::Vector3d(1.0, 1.0, slab ? 0.1 : 0.02), slab ? 30 : 24, slab ? 30 : 24,
      slab ? 10 : 2));
  c.params = FractureParams{};  // ceramic-tile
  c.params.age = 40.0;          // more cracks than any row asks for
  if (slab) c.params.relax_radius = 0.05;
  c.body = std::make_unique<PreparedBody>(mesh, c.params.elastic(), FractureScenario{});
  c.initial = c.body->initial_stress(c.params);
  c.resistance = draw_resistance(mesh->centroids(), c.params, 1);
  return cases.emplace(body, std::move(c)).first->second;
}

void BM_Simulate(benchmark::State& state) {
  const Case& c = prepared(static_cast<int>(state.range(0)));
  SimulationOptions options;
  options.max_cracks = static_cast<int>(state.range(1));
  const bool with_pattern = state.range(2) != 0;
  FractureResult r;
  for (auto _ : state) {
    r = simulate_fracture(c.body->fracture_body(), c.params, c.initial, c.resistance, 7, options);
    if (with_pattern) {
      const VisiblePattern v = extract_visible_pattern(c.body->mesh(), r.cracks, static_cast<int>(r.cracks.size()),
                                                       Eigen::Vector3d::UnitZ());
      benchmark::DoNotOptimize(compute_pattern_stats(v.graph, v.stats_options));
    }
  }
  state.counters["tets"] = c.body->mesh().tet_count();
  state.counters["cracks"] = static_cast<double>(r.cracks.size());
  state.counters["fragments"] = r.fragments.count;
}
// (body, max cracks, with pattern statistics)
BENCHMARK(BM_Simulate)
    ->Args({0, 5, 0})
    ->Args({0, 5, 1})
    ->Args({1, 270, 0})
    ->Args({1, 270, 1})
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
