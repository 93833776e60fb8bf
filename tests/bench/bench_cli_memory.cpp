// Peak resident memory of the `fissure solve` process with 50 modes on the 54K-tet tile
// (target ≤ 400 MB, issue 3), measured on a child process (child_peak_memory.hpp), so the
// benchmark's own allocations do not count. Also the whole command's wall time, cache off.

#include "bench_support.hpp"
#include "child_peak_memory.hpp"

#include "fissure/io/msh.hpp"

#include <benchmark/benchmark.h>

#include <filesystem>

namespace {
using namespace fissure;

void BM_SolveCommandPeakMemory(benchmark::State& state) {
  const int target = static_cast<int>(state.range(0));
  const int modes = static_cast<int>(state.range(1));
  const auto dir = std::filesystem::temp_directory_path() / "fissure-bench-memory";
  std::filesystem::create_directories(dir);
  const auto mesh_file = dir / ("tile" + std::to_string(target) + ".msh");
  const auto mesh = bench::tile(target);
  write_msh(mesh_file, *mesh);
  std::vector<std::string> argv{FISSURE_BINARY_DIR "/bin/fissure", "solve", mesh_file.string(), "--E", "3e10", "--nu", "0.2",
                                "--load", "ball:0,0,0.05,0.05=0,0,-1e4", "--no-cache", "-q", "-o", (dir / "result.msh").string()};
  for (const char* s : {"box:-0.5,-0.45,-0.5,-0.45,0,0", "box:0.45,0.5,-0.5,-0.45,0,0", "box:-0.5,-0.45,0.45,0.5,0,0",
                        "box:0.45,0.5,0.45,0.5,0,0"}) {
    argv.push_back("--fix");
    argv.push_back(s);
  }
  if (modes > 0) {
    argv.push_back("--modes");
    argv.push_back(std::to_string(modes));
  }
  double peak = 0.0;
  for (auto _ : state) peak = bench::child_peak_rss_mb(argv);
  if (peak < 0) state.SkipWithError("fissure solve failed");
  state.counters["tets"] = mesh->tet_count();
  state.counters["modes"] = modes;
  state.counters["peak_rss_mb"] = peak;
}
BENCHMARK(BM_SolveCommandPeakMemory)
    ->Args({54000, 50})
    ->Args({54000, 0})
    ->Args({24000, 50})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
