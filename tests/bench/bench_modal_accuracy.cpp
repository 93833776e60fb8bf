// Time against error of the modal static solve (paper §5.1) versus the direct solve, on the
// 24K-tet 1 × 1 × 0.05 m tile with a 5 cm centre patch of 10 kN: corner supports, and a free
// body (inertia relief). For each m: the eigensolve's time (a counter, once per body), the modal
// solve + stress kernel time (the benchmark time), and the displacement, stress and peak
// max-principal errors against the direct solution.

#include "bench_support.hpp"
#include "modal_error.hpp"

#include "fissure/fem/elastic_body.hpp"
#include "fissure/fem/modal_basis.hpp"
#include "fissure/fem/static_solver.hpp"

#include <benchmark/benchmark.h>

#include <chrono>
#include <utility>

namespace {
using namespace fissure;

struct Reference {
  std::shared_ptr<const ElasticBody> body;
  std::vector<int> fixed;
  Eigen::VectorXd f, u;
  StressField stress;
  Eigen::VectorXd smax;
  double direct_ms = 0.0;
};

const Reference& reference(bool supported) {
  static std::map<bool, Reference> cache;
  Reference& r = cache[supported];
  if (!r.body) {
    const auto mesh = bench::tile(24000);
    r.body = std::make_shared<const ElasticBody>(mesh, ElasticMaterial{});
    r.fixed = supported ? bench::corner_supports(*mesh) : std::vector<int>{};
    r.f = bench::centre_patch(*mesh);
    const StaticSolver solver(r.body, r.fixed);
    const auto t0 = std::chrono::steady_clock::now();
    r.u = solver.solve(r.f).displacement;
    compute_stress_and_max_principal(*r.body, r.u, r.stress, r.smax);
    r.direct_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  }
  return r;
}

void BM_ModalVsDirect(benchmark::State& state) {
  const int m = static_cast<int>(state.range(0));
  const bool supported = state.range(1) != 0;
  const ModalPrecision precision = state.range(2) != 0 ? ModalPrecision::Single : ModalPrecision::Double;
  const Reference& ref = reference(supported);
  // The basis of the last (m, supported) is kept: precisions and repetitions run back to back,
  // and the eigensolve (seconds at m = 400) is timed once, as the counter it is.
  static std::pair<int, bool> cached_for{-1, false};
  static ModalBasis basis;
  static double eigensolve_s = 0.0;
  if (cached_for != std::make_pair(m, supported)) {
    basis = ModalBasis();
    ModalOptions options;
    options.mode_count = m;
    const auto t0 = std::chrono::steady_clock::now();
    basis = ModalBasis::compute(ref.body, ref.fixed, options);
    eigensolve_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    cached_for = {m, supported};
  }

  Eigen::VectorXd u, smax;
  StressField stress;
  for (auto _ : state) {
    u = basis.static_displacement(ref.f, precision);
    compute_stress_and_max_principal(*ref.body, u, stress, smax);
    benchmark::DoNotOptimize(smax.data());
  }
  const bench::SolutionError e =
      bench::solution_error(u, stress, smax, ref.u, ref.stress, ref.smax, ref.body->mesh().volumes());
  state.counters["modes"] = m;
  state.counters["supported"] = supported;
  state.counters["single_precision"] = state.range(2);
  state.counters["eigensolve_s"] = eigensolve_s;
  state.counters["direct_solve_and_stress_ms"] = ref.direct_ms;
  state.counters["u_err_pct"] = 100.0 * e.displacement;
  state.counters["stress_err_pct"] = 100.0 * e.stress;
  state.counters["peak_err_pct"] = 100.0 * e.peak_principal;
}
BENCHMARK(BM_ModalVsDirect)
    ->Apply([](benchmark::internal::Benchmark* b) {
      // Explicit order (ArgsProduct varies the first argument fastest): both precisions of one
      // (m, supports) run back to back and share the cached basis.
      for (int m : {20, 50, 100, 200, 400})
        for (int supported : {1, 0})
          for (int single : {0, 1}) b->Args({m, supported, single});
    })
    ->Unit(benchmark::kMillisecond)
    ->Iterations(50);

}  // namespace

BENCHMARK_MAIN();
