// The FEM kernels on the CGAL tile at ~7K / 24K / 54K tets, one core. Targets at 24K (issue 3):
// assemble K ≤ 50 ms, factor ≤ 100 ms, direct solve ≤ 3 ms, 50 modes ≤ 0.6 s, modal solve
// (m = 50) ≤ 0.1 ms, stress + max principal for all tets ≤ 0.5 ms. Issue 8: stress + λ_max +
// its direction for all tets ≤ 1 ms, the same with patch recovery ≤ 2.5 ms.

#include "bench_support.hpp"

#include "fissure/fem/elastic_body.hpp"
#include "fissure/fem/modal_basis.hpp"
#include "fissure/fem/static_solver.hpp"
#include "fissure/fem/stress.hpp"
#include "fissure/fem/stress_recovery.hpp"

#include <benchmark/benchmark.h>

#include <filesystem>
#include <map>

namespace {
using namespace fissure;

void set_size_counters(benchmark::State& state, const TetMesh& mesh) {
  state.counters["tets"] = mesh.tet_count();
  state.counters["dofs"] = 3.0 * mesh.node_count();
}

void BM_AssembleStiffness(benchmark::State& state) {
  const auto mesh = bench::tile(static_cast<int>(state.range(0)));
  const TetGradients gradients = compute_tet_gradients(*mesh);
  const StiffnessPattern pattern(*mesh);
  const ElasticMaterial material;
  for (auto _ : state) {
    SparseMatrixD k = assemble_stiffness(*mesh, gradients, material, pattern);
    benchmark::DoNotOptimize(k.valuePtr());
  }
  set_size_counters(state, *mesh);
}

// Pattern + gradients + values: the whole cost of building K for a new mesh.
void BM_AssembleStiffnessFromScratch(benchmark::State& state) {
  const auto mesh = bench::tile(static_cast<int>(state.range(0)));
  const ElasticMaterial material;
  for (auto _ : state) {
    const TetGradients gradients = compute_tet_gradients(*mesh);
    const StiffnessPattern pattern(*mesh);
    SparseMatrixD k = assemble_stiffness(*mesh, gradients, material, pattern);
    benchmark::DoNotOptimize(k.valuePtr());
  }
  set_size_counters(state, *mesh);
}

void BM_Factorize(benchmark::State& state) {
  const auto mesh = bench::tile(static_cast<int>(state.range(0)));
  auto body = std::make_shared<const ElasticBody>(mesh, ElasticMaterial{});
  const DofMap dofs(body->stiffness().rows(), bench::corner_supports(*mesh));
  const Eigen::SparseMatrix<double> k = dofs.restrict_matrix(body->stiffness());
  SparseCholesky chol;
  for (auto _ : state) chol.factorize(k);
  set_size_counters(state, *mesh);
  state.counters["nnz_L"] = static_cast<double>(chol.factor_nonzeros());
  // The threads the process has after factorising (OpenMP and OpenBLAS keep their workers):
  // 1 when the run is single-threaded, as bench.sh's FISSURE_THREADS=1 says (issue 9).
  int tasks = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator("/proc/self/task")) ++tasks;
  state.counters["threads"] = tasks;
}

void BM_DirectSolve(benchmark::State& state) {
  const auto mesh = bench::tile(static_cast<int>(state.range(0)));
  auto body = std::make_shared<const ElasticBody>(mesh, ElasticMaterial{});
  const StaticSolver solver(body, bench::corner_supports(*mesh));
  const Eigen::VectorXd f = bench::centre_patch(*mesh);
  double residual = 0.0;
  for (auto _ : state) {
    const StaticSolution s = solver.solve(f);
    residual = s.relative_residual;
    benchmark::DoNotOptimize(s.displacement.data());
  }
  set_size_counters(state, *mesh);
  state.counters["residual"] = residual;
}

// Second argument: right-hand sides per call. One goes through CHOLMOD's supernodal solve, blocks
// through Fissure's (supernodal_solve.hpp): the block eigensolver's 8 at a time.
void BM_BlockSolve(benchmark::State& state) {
  const auto mesh = bench::tile(static_cast<int>(state.range(0)));
  auto body = std::make_shared<const ElasticBody>(mesh, ElasticMaterial{});
  const DofMap dofs(body->stiffness().rows(), bench::corner_supports(*mesh));
  const Eigen::SparseMatrix<double> k = dofs.restrict_matrix(body->stiffness());
  SparseCholesky chol;
  chol.factorize(k);
  const Eigen::MatrixXd b = Eigen::MatrixXd::Ones(k.rows(), state.range(1));
  for (auto _ : state) {
    const Eigen::MatrixXd x = chol.solve(b);
    benchmark::DoNotOptimize(x.data());
  }
  set_size_counters(state, *mesh);
  // Microseconds per right-hand side: rhs·10⁻⁶ per iteration, as a rate, inverted.
  state.counters["us_per_rhs"] = benchmark::Counter(1e-6 * static_cast<double>(state.range(1)),
                                                    benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_Eigensolve50(benchmark::State& state) {
  const auto mesh = bench::tile(static_cast<int>(state.range(0)));
  auto body = std::make_shared<const ElasticBody>(mesh, ElasticMaterial{});
  const auto fixed = state.range(1) ? bench::corner_supports(*mesh) : std::vector<int>{};
  ModalOptions options;
  options.mode_count = 50;
  double f1 = 0.0;
  for (auto _ : state) {
    const ModalBasis basis = ModalBasis::compute(body, fixed, options);
    f1 = basis.frequencies_hz()[0];
  }
  set_size_counters(state, *mesh);
  state.counters["f1_hz"] = f1;
  state.counters["supported"] = static_cast<double>(state.range(1));
}

// Few modes (second argument), corner supports: the case where blocks of 8 had been slower than
// the single-vector Lanczos they replaced (issue 9).
void BM_EigensolveFewModes(benchmark::State& state) {
  const auto mesh = bench::tile(static_cast<int>(state.range(0)));
  auto body = std::make_shared<const ElasticBody>(mesh, ElasticMaterial{});
  const auto fixed = bench::corner_supports(*mesh);
  ModalOptions options;
  options.mode_count = static_cast<int>(state.range(1));
  double f1 = 0.0;
  for (auto _ : state) f1 = ModalBasis::compute(body, fixed, options).frequencies_hz()[0];
  set_size_counters(state, *mesh);
  state.counters["f1_hz"] = f1;
  state.counters["modes"] = static_cast<double>(state.range(1));
}

// Second argument: 0 = double precision, 1 = the float copy of Φ (ModalPrecision::Single).
void BM_ModalSolve50(benchmark::State& state) {
  const auto mesh = bench::tile(static_cast<int>(state.range(0)));
  const ModalPrecision precision = state.range(1) != 0 ? ModalPrecision::Single : ModalPrecision::Double;
  // One basis per mesh size: the eigensolve is not what this measures (and repetitions rerun it).
  static std::map<int, ModalBasis> bases;
  auto found = bases.find(static_cast<int>(state.range(0)));
  if (found == bases.end()) {
    auto body = std::make_shared<const ElasticBody>(mesh, ElasticMaterial{});
    ModalOptions options;
    options.mode_count = 50;
    found = bases.emplace(static_cast<int>(state.range(0)),
                          ModalBasis::compute(body, bench::corner_supports(*mesh), options)).first;
  }
  const ModalBasis& basis = found->second;
  const Eigen::VectorXd f = bench::centre_patch(*mesh);
  for (auto _ : state) {
    Eigen::VectorXd u = basis.static_displacement(f, precision);
    benchmark::DoNotOptimize(u.data());
  }
  state.counters["single_precision"] = state.range(1);
  state.counters["phi_MB"] = static_cast<double>(basis.modes().size()) * (precision == ModalPrecision::Single ? 4 : 8) / 1e6;
  set_size_counters(state, *mesh);
}

void BM_CacheReload50(benchmark::State& state) {
  const auto mesh = bench::tile(static_cast<int>(state.range(0)));
  auto body = std::make_shared<const ElasticBody>(mesh, ElasticMaterial{});
  ModalOptions options;
  options.mode_count = 50;
  const auto fixed = bench::corner_supports(*mesh);
  const auto dir = std::filesystem::temp_directory_path() / "fissure-bench-cache";
  std::filesystem::create_directories(dir);
  cached_modal_basis(body, fixed, options, dir);  // fill
  bool loaded = false;
  for (auto _ : state) {
    const ModalBasis basis = cached_modal_basis(body, fixed, options, dir, &loaded);
    benchmark::DoNotOptimize(basis.modes().data());
  }
  set_size_counters(state, *mesh);
  state.counters["loaded"] = loaded;
}

void BM_StressAndMaxPrincipal(benchmark::State& state) {
  const auto mesh = bench::tile(static_cast<int>(state.range(0)));
  auto body = std::make_shared<const ElasticBody>(mesh, ElasticMaterial{});
  const Eigen::VectorXd u = bench::centre_patch_displacement(body);
  StressField stress;
  Eigen::VectorXd smax;
  for (auto _ : state) {
    compute_stress_and_max_principal(*body, u, stress, smax);
    benchmark::DoNotOptimize(smax.data());
  }
  set_size_counters(state, *mesh);
}

// Building the patch-recovery operator (once per mesh) and applying it to a stress field (once per
// stress-map step): the sparse product nodal = W · σ_tets, then the per-tet mean of the nodes.
void BM_StressRecoveryBuild(benchmark::State& state) {
  const auto mesh = bench::tile(static_cast<int>(state.range(0)));
  std::int64_t nonzeros = 0;
  for (auto _ : state) {
    const StressRecovery recovery(*mesh);
    nonzeros = recovery.weights().nonZeros();
    benchmark::DoNotOptimize(nonzeros);
  }
  state.counters["weights_per_node"] = static_cast<double>(nonzeros) / mesh->node_count();
  set_size_counters(state, *mesh);
}

void BM_StressRecoveryApply(benchmark::State& state) {
  const auto mesh = bench::tile(static_cast<int>(state.range(0)));
  auto body = std::make_shared<const ElasticBody>(mesh, ElasticMaterial{});
  const Eigen::VectorXd u = bench::centre_patch_displacement(body);
  const StressField stress = compute_stress(*body, u);
  const StressRecovery recovery(*mesh);
  for (auto _ : state) {
    StressField smoothed = recovery.smoothed_tets(stress);
    benchmark::DoNotOptimize(smoothed.data());
  }
  set_size_counters(state, *mesh);
}

// The fracture stage's seam (issue 8): stress, λ_max and its unit direction of every tet from a
// displacement, raw (the fused kernel) or patch-recovered (raw stress, smoothed_tets, then the
// closed forms on the smoothed field).
void BM_PrincipalStressWithDirection(benchmark::State& state) {
  const auto mesh = bench::tile(static_cast<int>(state.range(0)));
  auto body = std::make_shared<const ElasticBody>(mesh, ElasticMaterial{});
  const Eigen::VectorXd u = bench::centre_patch_displacement(body);
  PrincipalStressField field;
  for (auto _ : state) {
    compute_principal_stress(*body, u, field);
    benchmark::DoNotOptimize(field.max_direction.data());
  }
  set_size_counters(state, *mesh);
}

void BM_RecoveredPrincipalStressWithDirection(benchmark::State& state) {
  const auto mesh = bench::tile(static_cast<int>(state.range(0)));
  auto body = std::make_shared<const ElasticBody>(mesh, ElasticMaterial{});
  const Eigen::VectorXd u = bench::centre_patch_displacement(body);
  const StressRecovery recovery(*mesh);
  PrincipalStressField field;
  for (auto _ : state) {
    compute_principal_stress(*body, u, recovery, field);
    benchmark::DoNotOptimize(field.max_direction.data());
  }
  set_size_counters(state, *mesh);
}

// What the direction kernel replaces: Eigen's solver per element for λ_max and its direction.
void BM_PrincipalDirectionEigenPerElement(benchmark::State& state) {
  const auto mesh = bench::tile(static_cast<int>(state.range(0)));
  auto body = std::make_shared<const ElasticBody>(mesh, ElasticMaterial{});
  const Eigen::VectorXd u = bench::centre_patch_displacement(body);
  Eigen::VectorXd smax(mesh->tet_count());
  Eigen::MatrixX3d direction(mesh->tet_count(), 3);
  for (auto _ : state) {
    const StressField stress = compute_stress(*body, u);
    for (int t = 0; t < mesh->tet_count(); ++t) {
      const PrincipalStresses p = principal_stresses(stress.row(t).transpose());
      smax[t] = p.values[0];
      direction.row(t) = p.directions.col(0).transpose();
    }
    benchmark::DoNotOptimize(direction.data());
  }
  set_size_counters(state, *mesh);
}

// The straightforward alternative the fused kernel replaces: Eigen's solver per element.
void BM_StressEigenPerElement(benchmark::State& state) {
  const auto mesh = bench::tile(static_cast<int>(state.range(0)));
  auto body = std::make_shared<const ElasticBody>(mesh, ElasticMaterial{});
  const Eigen::VectorXd u = bench::centre_patch_displacement(body);
  const StressField stress = compute_stress(*body, u);
  Eigen::VectorXd smax(mesh->tet_count());
  for (auto _ : state) {
    for (int t = 0; t < mesh->tet_count(); ++t) smax[t] = principal_stresses(stress.row(t).transpose()).values[0];
    benchmark::DoNotOptimize(smax.data());
  }
  set_size_counters(state, *mesh);
}

#define FISSURE_SIZES ->Arg(7000)->Arg(24000)->Arg(54000)
BENCHMARK(BM_AssembleStiffness) FISSURE_SIZES->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AssembleStiffnessFromScratch) FISSURE_SIZES->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Factorize) FISSURE_SIZES->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DirectSolve) FISSURE_SIZES->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BlockSolve)->ArgsProduct({{7000, 24000, 54000}, {1, 8, 16}})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Eigensolve50)->Args({7000, 1})->Args({24000, 1})->Args({54000, 1})->Args({24000, 0})
    ->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_EigensolveFewModes)->ArgsProduct({{7000, 24000}, {10, 20}})->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_ModalSolve50)->ArgsProduct({{7000, 24000, 54000}, {0, 1}})->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CacheReload50) FISSURE_SIZES->Unit(benchmark::kMillisecond);
BENCHMARK(BM_StressAndMaxPrincipal) FISSURE_SIZES->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_StressRecoveryBuild) FISSURE_SIZES->Unit(benchmark::kMillisecond);
BENCHMARK(BM_StressRecoveryApply) FISSURE_SIZES->Unit(benchmark::kMillisecond);
BENCHMARK(BM_StressEigenPerElement)->Arg(24000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PrincipalStressWithDirection)->Arg(7000)->Arg(24000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_RecoveredPrincipalStressWithDirection)->Arg(7000)->Arg(24000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PrincipalDirectionEigenPerElement)->Arg(24000)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
