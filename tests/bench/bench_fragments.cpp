// Closed fragment meshes and their export (issue 11), and Fissure's side of the race against
// Blender's Cell Fracture (scripts/race-cell-fracture.sh runs the other side and this binary's
// BM_Race rows on the same machine, in one run).
//
// Bodies: the CGAL 1 × 1 × 0.05 m tile at the requested tet count, the bundled default material,
// its default scenario (the load on the top face's centre, rollers on the bottom rim), seed 1.
// - BM_MeshFragments/tets:N: mesh_fragments on one thread (the cracks of the default age).
// - BM_FragmentScene/tets:N: the export scene (UV charts, per-fragment values).
// - BM_EncodeScene/tets:N/format:F: its bytes, F = 0 GLB, 1 glTF, 2 OBJ, 3 PLY (no disk).
// - BM_Race/pieces:P/tets:N: body prepared (tet mesh, K factored, σ⁰, resistance), the crack
//   count that gives about P closed meshes found once beforehand; timed: the simulation of those
//   cracks plus the closed meshes, on thread_count() threads (FISSURE_THREADS). Counters: `pieces` = closed meshes,
//   `closed` = those whose every directed edge has its reverse once (watertight, consistently
//   wound), `volume_err` = |Σ fragment volumes − tet-mesh volume| / tet-mesh volume,
//   `search_s` = the one-off search that chose the crack count.

#include "fissure/base/thread_count.hpp"
#include "fissure/fracture/fragment_mesh.hpp"
#include "fissure/fracture/fragment_target.hpp"
#include "fissure/fracture/material_file.hpp"
#include "fissure/fracture/prepared_body.hpp"
#include "fissure/fracture/resistance_field.hpp"
#include "fissure/fracture/simulation.hpp"
#include "fissure/io/scene_export.hpp"
#include "fissure/mesh/tetrahedralize.hpp"
#include "fissure/mesh/tile.hpp"
#include "fissure/scene/fragment_export.hpp"

#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <utility>

namespace {
using namespace fissure;

const FractureParams& params() {
  static const FractureParams p = load_material(find_material(kDefaultMaterialName)).params;
  return p;
}

struct Body {
  std::shared_ptr<const TetMesh> mesh;
  std::unique_ptr<PreparedBody> prepared;
  StressField initial;
  Eigen::VectorXd resistance;
  FractureResult cracked;  // at the material's default age
};

const Body& body(int target_tets) {
  static std::map<int, Body> bodies;
  auto it = bodies.find(target_tets);
  if (it != bodies.end()) return it->second;
  Body b;
  TetrahedralizeOptions options;
  options.target_tets = target_tets;
  b.mesh = std::make_shared<const TetMesh>(tetrahedralize(make_tile_surface({1.0, 1.0, 0.05}), options));
  b.prepared = std::make_unique<PreparedBody>(b.mesh, params().elastic(), FractureScenario{});
  b.initial = b.prepared->initial_stress(params(), true);
  b.resistance = draw_resistance(b.mesh->centroids(), params(), 1);
  b.cracked = simulate_fracture(b.prepared->fracture_body(), params(), b.initial, b.resistance, 1);
  return bodies.emplace(target_tets, std::move(b)).first->second;
}

int crack_count(const FractureResult& r) { return static_cast<int>(r.cracks.size()); }

void BM_MeshFragments(benchmark::State& state) {
  const Body& b = body(static_cast<int>(state.range(0)));
  std::vector<FragmentMesh> fragments;
  for (auto _ : state) fragments = mesh_fragments(*b.mesh, b.cracked.cracks, crack_count(b.cracked), 1);
  std::size_t triangles = 0;
  for (const auto& f : fragments) triangles += static_cast<std::size_t>(f.triangles.rows());
  state.counters["tets"] = b.mesh->tet_count();
  state.counters["cracks"] = crack_count(b.cracked);
  state.counters["pieces"] = static_cast<double>(fragments.size());
  state.counters["triangles"] = static_cast<double>(triangles);
}
BENCHMARK(BM_MeshFragments)->ArgName("tets")->Arg(7000)->Arg(54000)->Unit(benchmark::kMillisecond);

const std::vector<FragmentMesh>& fragments_of(int target_tets) {
  static std::map<int, std::vector<FragmentMesh>> cache;
  auto it = cache.find(target_tets);
  if (it != cache.end()) return it->second;
  const Body& b = body(target_tets);
  return cache.emplace(target_tets, mesh_fragments(*b.mesh, b.cracked.cracks, crack_count(b.cracked), 1)).first->second;
}

void BM_FragmentScene(benchmark::State& state) {
  const int tets = static_cast<int>(state.range(0));
  const auto& fragments = fragments_of(tets);
  for (auto _ : state) benchmark::DoNotOptimize(fragment_scene(fragments, body(tets).cracked.cracks, params().density));
  state.counters["pieces"] = static_cast<double>(fragments.size());
}
BENCHMARK(BM_FragmentScene)->ArgName("tets")->Arg(7000)->Arg(54000)->Unit(benchmark::kMillisecond);

void BM_EncodeScene(benchmark::State& state) {
  const int tets = static_cast<int>(state.range(0));
  const ExportScene scene = fragment_scene(fragments_of(tets), body(tets).cracked.cracks, params().density);
  const auto format = static_cast<SceneFormat>(state.range(1));
  std::size_t bytes = 0;
  for (auto _ : state) {
    const std::string out = encode_scene(scene, format, "fragments.mtl");
    bytes = out.size();
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["MB"] = static_cast<double>(bytes) / 1e6;
}
BENCHMARK(BM_EncodeScene)
    ->ArgNames({"tets", "format"})
    ->ArgsProduct({{7000, 54000}, {0, 1, 2, 3}})
    ->Unit(benchmark::kMillisecond);

// The crack count that gives about `pieces` closed meshes on the body of `tets`, found once (not
// timed) by simulate_to_fragment_mesh_count, which aims at the meshes' own count (the labeller's
// runs ahead of it on dense patterns, docs/fragments.md).
struct RaceCase {
  int cracks = 0;
  double search_s = 0.0;
};

const RaceCase& race_case(int pieces, int tets) {
  static std::map<std::pair<int, int>, RaceCase> cases;
  auto it = cases.find({pieces, tets});
  if (it != cases.end()) return it->second;
  const Body& b = body(tets);
  const auto t0 = std::chrono::steady_clock::now();
  // Tolerance 0: the nearest count its search meets (Cell Fracture makes exactly N).
  const FragmentTargetResult r = simulate_to_fragment_mesh_count(b.prepared->fracture_body(), params(), b.initial,
                                                                 b.resistance, 1, pieces, thread_count(), {}, 0.0);
  RaceCase c;
  c.cracks = crack_count(r.result);
  c.search_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return cases.emplace(std::make_pair(pieces, tets), c).first->second;
}

// Watertight and consistently wound: every directed edge has its reverse exactly once.
bool closed(const FragmentMesh& f) {
  std::map<std::pair<int, int>, int> directed;
  for (Eigen::Index t = 0; t < f.triangles.rows(); ++t)
    for (int i = 0; i < 3; ++i) ++directed[{f.triangles(t, i), f.triangles(t, (i + 1) % 3)}];
  for (const auto& [e, count] : directed) {
    const auto back = directed.find({e.second, e.first});
    if (count != 1 || back == directed.end() || back->second != 1) return false;
  }
  return f.triangles.rows() >= 4 && f.volume > 0.0;
}

void BM_Race(benchmark::State& state) {
  const int pieces = static_cast<int>(state.range(0)), tets = static_cast<int>(state.range(1));
  const Body& b = body(tets);
  const RaceCase& c = race_case(pieces, tets);
  FractureParams p = params();
  p.age = fracture_parameter_table()[static_cast<std::size_t>(find_fracture_parameter("age"))].max;
  SimulationOptions options;
  options.max_cracks = c.cracks;
  const int threads = thread_count();
  std::vector<FragmentMesh> fragments;
  double simulation_s = 0.0, meshing_s = 0.0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    const FractureResult r = simulate_fracture(b.prepared->fracture_body(), p, b.initial, b.resistance, 1, options);
    const auto t1 = std::chrono::steady_clock::now();
    fragments = mesh_fragments(*b.mesh, r.cracks, crack_count(r), threads);
    simulation_s += std::chrono::duration<double>(t1 - t0).count();
    meshing_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
  }
  state.counters["simulation_ms"] = 1e3 * simulation_s / static_cast<double>(state.iterations());
  state.counters["meshing_ms"] = 1e3 * meshing_s / static_cast<double>(state.iterations());
  double volume = 0.0;
  int closed_count = 0;
  for (const auto& f : fragments) {
    volume += f.volume;
    closed_count += closed(f) ? 1 : 0;
  }
  const double body_volume = b.mesh->total_volume();
  state.counters["tets"] = b.mesh->tet_count();
  state.counters["fissure_threads"] = threads;
  state.counters["pieces"] = static_cast<double>(fragments.size());
  state.counters["closed"] = closed_count;
  state.counters["volume_err"] = std::abs(volume - body_volume) / body_volume;
  state.counters["cracks"] = c.cracks;
  state.counters["search_s"] = c.search_s;
}
BENCHMARK(BM_Race)
    ->ArgNames({"pieces", "tets"})
    ->Args({50, 7000})
    ->Args({200, 24000})
    ->Args({1000, 54000})
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
