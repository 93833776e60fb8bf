// Whole scenes (issue 13): the bundled street fractured end to end, and what laziness saves.
//
// - BM_Street/slabs:S/cache:C: the street demo (S sidewalk slabs in two rows, a curb, a road; what
//   assets/scenes/street.glb holds at S = 24) read from its GLB, every slab and the curb
//   fractured with the bundled concrete at age 50 (the demo's age; at 12, ten slabs stayed whole), the road left as it
//   is, the scene exported and encoded as GLB in memory. On FISSURE_THREADS threads, bodies in
//   parallel (scripts/bench.sh: one). Counters: `per_body_s` = the time over the fractured bodies;
//   `meshing`, `preparation`, `simulation`, `fragments` = the shares of the bodies' summed
//   seconds; `export_s` = scene_export + GLB; `pieces` = fragments in all. C = 0: no tet mesh
//   cache; 1: a cold one (emptied before each iteration, so the entries' writes are paid);
//   2: a warm one (filled by a run before timing: what a second run of the same scene costs).
//   `cached` = bodies whose mesh came from the cache.
// - BM_OneBodyOf/bodies:B: a street of B bodies with one slab assigned (by node path), against
//   B = 1 (the slab alone): the rest of the scene costs only its reading and export, never a
//   mesh (target: within 10 % of the one body alone).

#include "fissure/base/thread_count.hpp"
#include "fissure/io/scene_export.hpp"
#include "fissure/io/scene_import.hpp"
#include "fissure/scene/demo_scenes.hpp"
#include "fissure/scene/scene_fracture.hpp"

#include <benchmark/benchmark.h>

#include <chrono>
#include <filesystem>

namespace {
using namespace fissure;
namespace fs = std::filesystem;

// The street with `slabs` slabs (two rows), written as a GLB and read back as a user's file is.
// `only_first`: of its bodies only the first slab, under the same path (so the same seed).
ImportedScene street(int slabs, bool curb_and_road, bool only_first = false) {
  DemoStreetOptions o;
  o.slabs_across = slabs >= 2 ? 2 : 1;
  o.slabs_along = (slabs + o.slabs_across - 1) / o.slabs_across;
  o.curb_and_road = curb_and_road;
  ExportScene scene = demo_street(o);
  if (only_first) scene.parts.resize(3);  // street, sidewalk, the first slab (demo_scenes.cpp's order)
  const fs::path file = fs::path(FISSURE_BENCH_DIR) /
                        ("bench-street-" + std::to_string(slabs) + (only_first ? "-first" : "") + ".glb");
  write_scene(file, scene);
  return import_scene(file);
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void BM_Street(benchmark::State& state) {
  const int slabs = static_cast<int>(state.range(0));
  const int cache = static_cast<int>(state.range(1));
  SceneFractureOptions options;
  options.assignments.by_material = {{"concrete", "concrete"}, {"curb", "concrete"}};
  options.age = 50.0;
  options.threads = thread_count();
  if (cache > 0) {
    options.cache_dir = fs::path(FISSURE_BENCH_DIR) / "bench-scene-cache";
    fs::remove_all(options.cache_dir);
    if (cache == 2) fracture_scene(street(slabs, true), options);
  }
  BodyFracture::Seconds shares;
  double export_s = 0.0;
  int bodies = 0, pieces = 0, cached = 0;
  for (auto _ : state) {
    if (cache == 1) {
      state.PauseTiming();
      fs::remove_all(options.cache_dir);
      state.ResumeTiming();
    }
    const ImportedScene scene = street(slabs, true);
    const SceneFracture run = fracture_scene(scene, options);
    const auto start = std::chrono::steady_clock::now();
    const std::string bytes = encode_scene(scene_export(scene, run), SceneFormat::Glb);
    export_s = seconds_since(start);
    benchmark::DoNotOptimize(bytes.data());
    shares = {};
    bodies = pieces = cached = 0;
    for (const SceneBodyReport& r : run.reports) {
      if (r.status != SceneBodyReport::Status::Fractured) continue;
      ++bodies;
      cached += r.mesh_cached ? 1 : 0;
      pieces += r.fragments;
      shares.meshing += r.seconds.meshing;
      shares.preparation += r.seconds.preparation;
      shares.simulation += r.seconds.simulation;
      shares.fragments += r.seconds.fragments;
    }
  }
  const double total = shares.meshing + shares.preparation + shares.simulation + shares.fragments;
  state.counters["per_body_s"] = benchmark::Counter(static_cast<double>(state.iterations()) * bodies, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["meshing"] = shares.meshing / total;
  state.counters["preparation"] = shares.preparation / total;
  state.counters["simulation"] = shares.simulation / total;
  state.counters["fragments"] = shares.fragments / total;
  state.counters["export_s"] = export_s;
  state.counters["pieces"] = pieces;
  state.counters["bodies"] = bodies;
  state.counters["cached"] = cached;
}
BENCHMARK(BM_Street)
    ->ArgNames({"slabs", "cache"})
    ->Args({4, 0})
    ->Args({24, 0})
    ->Args({24, 1})
    ->Args({24, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);

void BM_OneBodyOf(benchmark::State& state) {
  const int bodies = static_cast<int>(state.range(0));
  // The same slab, same path and seed, alone and among 99 others.
  const ImportedScene scene = street(100, false, bodies == 1);
  if (static_cast<int>(scene_bodies(scene).size()) != bodies) state.SkipWithError("the street has another body count");
  SceneFractureOptions options;
  options.assignments.by_path = {{scene_bodies(scene).front().path, "concrete"}};  // the first slab
  options.age = 50.0;
  options.threads = 1;
  int pieces = 0;
  for (auto _ : state) {
    const SceneFracture run = fracture_scene(scene, options);
    const std::string bytes = encode_scene(scene_export(scene, run), SceneFormat::Glb);
    benchmark::DoNotOptimize(bytes.data());
    pieces = run.reports.front().fragments;
    if (run.reports.front().status != SceneBodyReport::Status::Fractured) state.SkipWithError("the slab did not fracture");
  }
  state.counters["pieces"] = pieces;
}
BENCHMARK(BM_OneBodyOf)->ArgName("bodies")->Arg(1)->Arg(100)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);

}  // namespace

BENCHMARK_MAIN();
