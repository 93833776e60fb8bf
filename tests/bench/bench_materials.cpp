// The per-trial set-up the fracture parameters cost: drawing the resistance field (one per
// trial, paper §5.1) and reading a material file (once per command). Sizes are the paper's
// 7K / 24K / 54K tets; `spread` is R_cvar as a percentage of R_cm (15: the default tile, where
// truncation never triggers; 100: Table 3's largest, where 17 % of the draws are resampled).

#include "fissure/base/atomic_file.hpp"
#include "fissure/fracture/material_file.hpp"
#include "fissure/fracture/resistance_field.hpp"

#include <benchmark/benchmark.h>

namespace {

void BM_DrawResistance(benchmark::State& state) {
  const auto tets = static_cast<std::size_t>(state.range(0));
  const double mean = 4.5e7, stddev = mean * static_cast<double>(state.range(1)) / 100.0;
  std::uint64_t seed = 1;
  for (auto _ : state) {
    Eigen::VectorXd r = fissure::draw_resistance(tets, mean, stddev, seed++);
    benchmark::DoNotOptimize(r.data());
  }
}
BENCHMARK(BM_DrawResistance)->ArgsProduct({{7000, 24000, 54000}, {15, 100}})->ArgNames({"tets", "spread"})
    ->Unit(benchmark::kMicrosecond);

// Parse + validate of the bundled default material, from text already in memory.
void BM_ReadMaterial(benchmark::State& state) {
  const std::string text = fissure::read_file(fissure::find_material(fissure::kDefaultMaterialName));
  for (auto _ : state) {
    fissure::FractureMaterial m = fissure::material_from_json(text, "ceramic-tile.json");
    benchmark::DoNotOptimize(m.params.age);
  }
}
BENCHMARK(BM_ReadMaterial)->Unit(benchmark::kMicrosecond);

}  // namespace
BENCHMARK_MAIN();
