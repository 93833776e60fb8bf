// What the machine itself can do, run beside the FEM benchmarks so their figures can be read
// against it: read bandwidth by working-set size (the modal solve and the stress kernel are
// memory-bound) and double-precision FMA throughput (assembly and factorisation are not).
// Shared virtual machines vary from day to day; this section tells a slow day from a regression.

#include <Eigen/Core>
#include <benchmark/benchmark.h>

namespace {

// Sums a working set of state.range(0) KiB of doubles, over and over: once it exceeds a cache
// level, GB_per_s (10⁹ bytes/s) is that level's (or memory's) streaming read bandwidth on one core.
void BM_ReadBandwidth(benchmark::State& state) {
  const Eigen::Index n = state.range(0) * 1024 / static_cast<Eigen::Index>(sizeof(double));
  const Eigen::VectorXd data = Eigen::VectorXd::LinSpaced(n, 0.0, 1.0);
  for (auto _ : state) {
    double sum = data.sum();
    benchmark::DoNotOptimize(sum);
  }
  state.counters["GB_per_s"] = benchmark::Counter(static_cast<double>(n * sizeof(double)) * static_cast<double>(state.iterations()) / 1e9,
                                                  benchmark::Counter::kIsRate);
  state.counters["working_set_MB"] = static_cast<double>(n * sizeof(double)) / 1e6;
}
BENCHMARK(BM_ReadBandwidth)->Arg(256)->Arg(1536)->Arg(3 * 1024)->Arg(7 * 1024)->Arg(16 * 1024)->Arg(256 * 1024);

// y ← a·y + b on a 32 KiB array (in L1): two flops per element, vectorised by Eigen.
void BM_FmaThroughput(benchmark::State& state) {
  Eigen::ArrayXd y = Eigen::ArrayXd::LinSpaced(4096, 0.0, 1.0);
  const double a = 0.999999, b = 1e-7;
  for (auto _ : state) {
    for (int repeat = 0; repeat < 64; ++repeat) y = a * y + b;
    benchmark::DoNotOptimize(y.data());
  }
  state.counters["GFLOPs"] = benchmark::Counter(2.0 * 4096 * 64 * static_cast<double>(state.iterations()) / 1e9,
                                                benchmark::Counter::kIsRate);
}
BENCHMARK(BM_FmaThroughput);

}  // namespace

BENCHMARK_MAIN();
