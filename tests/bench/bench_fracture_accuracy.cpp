// Time against error of the simulation's approximations (issue 10): mesh resolution, the modal
// basis's m, single-precision modal expansion, and stress recovery on or off, each measured by
// what it does to the visible pattern, the Eq. 5 distance (pattern_similarity) to the most exact
// setting for the same seed, averaged over kSeeds seeds. The resistance field is a function of
// position (draw_resistance on the centroids), so one seed is one body at every resolution.
//
// Setting: the bundled ceramic-tile material on the CGAL 1 × 1 × 0.05 m tile, the default
// scenario (rim rollers, the default patch load), σ⁰ = the static stress of the load, the visible
// pattern's PatternStats as the fit measures it. References:
//  - mesh rows: the 54K mesh, direct solve, double, recovered stress (the most exact setting);
//  - modal rows: the direct solve at 24K, recovered (the modal basis changes only σ⁰ on one mesh,
//    so its error is told apart from the mesh's);
//  - recovery rows: the same mesh's recovered stress.
// `seed_spread` is the noise floor: the mean Eq. 5 distance between the reference's patterns of
// two different seeds (all pairs). An approximation whose `eq5` is well below it changes the
// pattern less than re-rolling the seed does.
// `sigma0_err_pct`: the field error, ‖λ_max − λ_max,ref‖ / ‖λ_max,ref‖ over the tets, volume
// weighted (max principal stress of σ⁰; defined only on the reference's own mesh, so the mesh
// rows leave it out).
// Times (one core): mesh rows time the simulation of one trial (`prepare_s`, the one-off
// PreparedBody, and `mesh_s`, the CGAL meshing, beside it); the σ⁰ rows time the σ⁰ computation
// of one trial (the simulation that follows costs the same as the reference's, the mesh row's).
// The eigensolve is a one-off per body, `eigensolve_s`.

#include "fissure/exemplar/similarity.hpp"
#include "fissure/fem/modal_basis.hpp"
#include "fissure/fem/stress_recovery.hpp"
#include "fissure/fracture/material_file.hpp"
#include "fissure/fracture/prepared_body.hpp"
#include "fissure/fracture/resistance_field.hpp"
#include "fissure/fracture/simulation.hpp"
#include "fissure/fracture/visible_pattern.hpp"
#include "fissure/mesh/tetrahedralize.hpp"
#include "fissure/mesh/tile.hpp"

#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <vector>

namespace {
using namespace fissure;

constexpr int kSeeds = 5;
constexpr int kFinest = 54000;   // the reference resolution
constexpr int kModalMesh = 24000;  // where the modal and single-precision rows run

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

const FractureParams& params() {
  static const FractureParams p = load_material(find_material(kDefaultMaterialName)).params;
  return p;
}

// One resolution of the tile, prepared, with the resistance of every seed and the reference
// (direct, recovered) σ⁰ and patterns.
struct Level {
  std::shared_ptr<const TetMesh> mesh;
  std::unique_ptr<PreparedBody> body;
  double mesh_s = 0.0, prepare_s = 0.0;
  std::vector<Eigen::VectorXd> resistance;  // per seed
  StressField reference_stress;             // direct, recovered
  Eigen::VectorXd reference_smax;
  std::vector<PatternStats> reference_patterns;  // per seed
  double seed_spread = 0.0;
};

std::uint64_t seed_of(int k) { return static_cast<std::uint64_t>(k + 1); }

PatternStats pattern_of(const Level& level, const StressField& sigma0, int k) {
  const FractureResult r =
      simulate_fracture(level.body->fracture_body(), params(), sigma0, level.resistance[k], seed_of(k));
  const VisiblePattern v =
      extract_visible_pattern(*level.mesh, r.cracks, static_cast<int>(r.cracks.size()), Eigen::Vector3d::UnitZ());
  return compute_pattern_stats(v.graph, v.stats_options);
}

std::vector<PatternStats> patterns_of(const Level& level, const StressField& sigma0) {
  std::vector<PatternStats> out;
  for (int k = 0; k < kSeeds; ++k) out.push_back(pattern_of(level, sigma0, k));
  return out;
}

Eigen::VectorXd max_principal(const StressField& stress) {
  Eigen::VectorXd smax;
  max_principal_of(stress, smax);
  return smax;
}

const Level& level(int target) {
  static std::map<int, Level> levels;
  auto it = levels.find(target);
  if (it != levels.end()) return it->second;
  Level l;
  auto t0 = std::chrono::steady_clock::now();
  TetrahedralizeOptions options;
  options.target_tets = target;
  l.mesh = std::make_shared<const TetMesh>(tetrahedralize(make_tile_surface({1.0, 1.0, 0.05}), options));
  l.mesh_s = seconds_since(t0);
  t0 = std::chrono::steady_clock::now();
  l.body = std::make_unique<PreparedBody>(l.mesh, params().elastic(), FractureScenario{});
  l.prepare_s = seconds_since(t0);
  for (int k = 0; k < kSeeds; ++k) l.resistance.push_back(draw_resistance(l.mesh->centroids(), params(), seed_of(k)));
  l.reference_stress = l.body->initial_stress(params(), true);
  l.reference_smax = max_principal(l.reference_stress);
  l.reference_patterns = patterns_of(l, l.reference_stress);
  int pairs = 0;
  for (int a = 0; a < kSeeds; ++a)
    for (int b = a + 1; b < kSeeds; ++b, ++pairs)
      l.seed_spread += pattern_similarity(l.reference_patterns[a], l.reference_patterns[b]).total;
  l.seed_spread /= pairs;
  return levels.emplace(target, std::move(l)).first->second;
}

// Mean over seeds of the Eq. 5 distance between `patterns` and `reference` of the same seed, and
// the mean visible fragment count of `patterns`.
struct PatternError {
  double eq5 = 0.0;
  double fragments = 0.0;
};

PatternError pattern_error(const std::vector<PatternStats>& patterns, const std::vector<PatternStats>& reference) {
  PatternError e;
  for (int k = 0; k < kSeeds; ++k) {
    e.eq5 += pattern_similarity(patterns[k], reference[k]).total / kSeeds;
    e.fragments += static_cast<double>(patterns[k].fragment_count) / kSeeds;
  }
  return e;
}

// Volume-weighted relative L2 of the max principal stress over the tets.
double field_error(const Level& l, const Eigen::VectorXd& smax) {
  const Eigen::VectorXd& v = l.mesh->volumes();
  const Eigen::VectorXd d = smax - l.reference_smax;
  return std::sqrt(v.dot(d.cwiseProduct(d)) / v.dot(l.reference_smax.cwiseProduct(l.reference_smax)));
}

void set_pattern_counters(benchmark::State& state, const Level& reference, const PatternError& e) {
  state.counters["reference_tets"] = reference.mesh->tet_count();
  state.counters["eq5"] = e.eq5;
  state.counters["seed_spread"] = reference.seed_spread;
  state.counters["eq5_over_spread"] = e.eq5 / reference.seed_spread;
  state.counters["fragments"] = e.fragments;
}

// Mesh resolution: the same seeds on the target mesh, against the finest. Time: one trial's
// simulation, the seeds in turn.
void BM_MeshResolution(benchmark::State& state) {
  const Level& l = level(static_cast<int>(state.range(0)));
  const Level& ref = level(kFinest);
  int k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        simulate_fracture(l.body->fracture_body(), params(), l.reference_stress, l.resistance[k], seed_of(k)));
    k = (k + 1) % kSeeds;
  }
  state.counters["tets"] = l.mesh->tet_count();
  state.counters["mesh_s"] = l.mesh_s;
  state.counters["prepare_s"] = l.prepare_s;
  set_pattern_counters(state, ref, pattern_error(l.reference_patterns, ref.reference_patterns));
}
BENCHMARK(BM_MeshResolution)
    ->ArgName("tets")
    ->Arg(7000)
    ->Arg(24000)
    ->Arg(kFinest)
    ->Iterations(kSeeds)
    ->Unit(benchmark::kMillisecond);

// σ⁰ by the direct solve, recovered (1, the reference) or raw tet stress (0), on one mesh,
// against that mesh's recovered σ⁰. Time: one σ⁰ (load vector, triangular solves, stress).
void BM_DirectStress(benchmark::State& state) {
  const Level& l = level(static_cast<int>(state.range(0)));
  const bool recovered = state.range(1) != 0;
  StressField sigma0;
  for (auto _ : state) {
    sigma0 = l.body->initial_stress(params(), recovered);
    benchmark::DoNotOptimize(sigma0.data());
  }
  static std::map<std::pair<int, bool>, PatternError> errors;
  const auto key = std::make_pair(l.mesh->tet_count(), recovered);
  if (errors.find(key) == errors.end())
    errors[key] = recovered ? pattern_error(l.reference_patterns, l.reference_patterns)
                            : pattern_error(patterns_of(l, sigma0), l.reference_patterns);
  state.counters["tets"] = l.mesh->tet_count();
  state.counters["recovered"] = recovered;
  state.counters["sigma0_err_pct"] = 100.0 * field_error(l, max_principal(sigma0));
  set_pattern_counters(state, l, errors[key]);
}
BENCHMARK(BM_DirectStress)
    ->ArgNames({"tets", "recovered"})
    ->Args({kModalMesh, 1})
    ->Args({kModalMesh, 0})
    ->Args({kFinest, 1})
    ->Args({kFinest, 0})
    ->Unit(benchmark::kMillisecond);

// σ⁰ by the modal static solve with m modes (ModalBasis on the prepared body's supports), then
// stress recovery as PreparedBody::initial_stress does, at 24K, against the direct solve there.
// Time: one σ⁰ (modal solve in the given precision, stress, recovery).
void BM_ModalStress(benchmark::State& state) {
  const Level& l = level(kModalMesh);
  const int m = static_cast<int>(state.range(0));
  const ModalPrecision precision = state.range(1) != 0 ? ModalPrecision::Single : ModalPrecision::Double;
  struct Basis {
    ModalBasis basis;
    double eigensolve_s = 0.0;
  };
  static std::map<int, Basis> bases;
  static const StressRecovery recovery(*l.mesh);  // what PreparedBody builds (PatchFit)
  if (bases.find(m) == bases.end()) {
    // The prepared body owns its ElasticBody; the aliasing pointer lends it without owning.
    const std::shared_ptr<const ElasticBody> elastic(std::shared_ptr<const void>(), &l.body->elastic_body());
    ModalOptions options;
    options.mode_count = m;
    const auto t0 = std::chrono::steady_clock::now();
    Basis b;
    b.basis = ModalBasis::compute(elastic, l.body->fixed_dofs(), options);
    b.eigensolve_s = seconds_since(t0);
    bases.emplace(m, std::move(b));
  }
  const Basis& b = bases.at(m);
  PrincipalStressField field;
  for (auto _ : state) {
    const Eigen::VectorXd u = b.basis.static_displacement(l.body->load_vector(params()), precision);
    compute_principal_stress(l.body->elastic_body(), u, recovery, field);
    benchmark::DoNotOptimize(field.stress.data());
  }
  // Patterns per (m, single); the double rows run first, so a single row finds its double twin.
  static std::map<std::pair<int, bool>, std::vector<PatternStats>> patterns;
  const bool single = precision == ModalPrecision::Single;
  const auto key = std::make_pair(m, single);
  if (patterns.find(key) == patterns.end()) patterns[key] = patterns_of(l, field.stress);
  const PatternError e = pattern_error(patterns[key], l.reference_patterns);
  // Single precision moves σ⁰ by ~1e-6 relative: its distance to the double twin is what a
  // perturbation far below any modelling error does to the pattern (the sensitivity floor).
  const auto twin = patterns.find(std::make_pair(m, false));
  if (single && twin != patterns.end())
    state.counters["eq5_to_double"] = pattern_error(patterns[key], twin->second).eq5;
  state.counters["tets"] = l.mesh->tet_count();
  state.counters["modes"] = m;
  state.counters["single_precision"] = single;
  state.counters["eigensolve_s"] = b.eigensolve_s;
  state.counters["sigma0_err_pct"] = 100.0 * field_error(l, field.max_principal);
  set_pattern_counters(state, l, e);
}
BENCHMARK(BM_ModalStress)
    ->ArgNames({"modes", "single"})
    ->Args({10, 0})
    ->Args({10, 1})
    ->Args({20, 0})
    ->Args({20, 1})
    ->Args({50, 0})
    ->Args({50, 1})
    ->Args({100, 0})
    ->Args({100, 1})
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
