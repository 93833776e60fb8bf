// The visible pattern of a fractured body (issue 10): crack traces, junctions and exact fragments
// on the visible face (extract_visible_pattern), their statistics (compute_pattern_stats) and the
// 1024 px line drawing (render_pattern_image), on the CGAL tile (1 × 1 × 0.05 m) cut by a random
// hierarchical pattern of vertical plane cracks (tests/fracture/synthetic_cracks.hpp), up = +z.

#include "bench_support.hpp"
#include "synthetic_cracks.hpp"

#include "fissure/fracture/pattern_image.hpp"
#include "fissure/fracture/visible_pattern.hpp"

#include <benchmark/benchmark.h>

namespace {
using namespace fissure;

struct Case {
  std::shared_ptr<const TetMesh> mesh;
  std::vector<CrackSurface> cracks;
};

const Case& fractured_tile(int tets, int cracks) {
  static std::map<std::pair<int, int>, Case> cache;
  Case& c = cache[{tets, cracks}];
  if (!c.mesh) {
    c.mesh = bench::tile(tets);
    test::add_hierarchical_cracks(*c.mesh, c.cracks, cracks, 1, {-0.5, -0.5}, {0.5, 0.5});
  }
  return c;
}

void counters(benchmark::State& state, const Case& c, const VisiblePattern& p) {
  std::size_t cuts = 0;
  for (const CrackSurface& s : c.cracks) cuts += s.cuts.size();
  state.counters["tets"] = c.mesh->tet_count();
  state.counters["cuts"] = static_cast<double>(cuts);
  state.counters["visible_triangles"] = p.visible_triangles;
  state.counters["fragments"] = static_cast<double>(p.graph.fragments.size());
  state.counters["polylines"] = static_cast<double>(p.graph.cracks.size());
}

void BM_ExtractVisiblePattern(benchmark::State& state) {
  const Case& c = fractured_tile(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  VisiblePattern p;
  for (auto _ : state) {
    p = extract_visible_pattern(*c.mesh, c.cracks, static_cast<int>(c.cracks.size()), Eigen::Vector3d::UnitZ());
    benchmark::DoNotOptimize(p.graph.fragments.data());
  }
  counters(state, c, p);
}

// Extraction and the statistics of the exemplar module: what a fit's trial adds to a simulation.
void BM_VisiblePatternStats(benchmark::State& state) {
  const Case& c = fractured_tile(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  VisiblePattern p;
  for (auto _ : state) {
    p = extract_visible_pattern(*c.mesh, c.cracks, static_cast<int>(c.cracks.size()), Eigen::Vector3d::UnitZ());
    const PatternStats s = compute_pattern_stats(p.graph, p.stats_options);
    benchmark::DoNotOptimize(s.fragment_count);
  }
  counters(state, c, p);
}

void BM_RenderPatternImage(benchmark::State& state) {
  const Case& c = fractured_tile(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  const VisiblePattern p = extract_visible_pattern(*c.mesh, c.cracks, static_cast<int>(c.cracks.size()), Eigen::Vector3d::UnitZ());
  for (auto _ : state) {
    const PatternImage image = render_pattern_image(p);
    benchmark::DoNotOptimize(image.drawing.pixels.data());
  }
  counters(state, c, p);
}

void sizes(benchmark::internal::Benchmark* b) {
  b->Args({7000, 0});
  b->Args({7000, 5});  // the 7K-tet simulation benchmark has 4–5 cracks
  for (const int tets : {7000, 24000, 54000}) b->Args({tets, 50});
  b->Args({54000, 270});
  b->Unit(benchmark::kMillisecond);
}

BENCHMARK(BM_ExtractVisiblePattern)->Apply(sizes);
BENCHMARK(BM_VisiblePatternStats)->Apply(sizes);
BENCHMARK(BM_RenderPatternImage)->Args({24000, 50})->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
