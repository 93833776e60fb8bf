// Exemplar analysis (tracing → crack graph → statistics) on synthetic masks of 1024² and 4096²
// px, one core. Targets (issue 4): 1024² ≤ 50 ms, 4096² ≤ 1 s, peak memory on 4096² ≤ 300 MB.
// The mask: a hierarchical network of orthogonal cracks (each rectangle split across its longer
// side at a random position), pen width scaled with the image, ~12 % crack pixels, written as a
// PNG so the timing includes decoding as `fissure analyze` does.

#include "child_peak_memory.hpp"
#include "drawings.hpp"

#include "fissure/base/rng.hpp"
#include "fissure/exemplar/exemplar_analysis.hpp"

#include <benchmark/benchmark.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <filesystem>

namespace {
using namespace fissure;

// The stress case: the tests' oblique grid, 24 px pitch, 3 px strokes (≈ 1.7 crossings per
// 1000 px², thousands of close junction pairs to contract).
std::filesystem::path make_dense_mask(int size) {
  const auto path = std::filesystem::temp_directory_path() / ("fissure-bench-dense-" + std::to_string(size) + ".png");
  if (!std::filesystem::exists(path)) cv::imwrite(path.string(), test::oblique_grid_drawing(size, 24, 3));
  return path;
}

std::filesystem::path make_mask(int size, bool dense = false) {
  if (dense) return make_dense_mask(size);
  const auto path = std::filesystem::temp_directory_path() / ("fissure-bench-mask-" + std::to_string(size) + ".png");
  if (std::filesystem::exists(path)) return path;
  cv::Mat mask(size, size, CV_8U, cv::Scalar(0));
  const int pen = std::max(2, size / 300);
  Rng rng(42);
  struct Box { int x0, y0, x1, y1; };
  std::vector<Box> stack{{0, 0, size - 1, size - 1}};
  const int smallest = size / 28;
  while (!stack.empty()) {
    const Box b = stack.back();
    stack.pop_back();
    const int w = b.x1 - b.x0, h = b.y1 - b.y0;
    if (std::max(w, h) <= 2 * smallest) continue;
    if (w >= h) {
      const int x = b.x0 + smallest + static_cast<int>(rng.uniform_index(static_cast<std::uint64_t>(w - 2 * smallest)));
      cv::line(mask, {x, b.y0}, {x, b.y1}, cv::Scalar(255), pen);
      stack.push_back({b.x0, b.y0, x, b.y1});
      stack.push_back({x, b.y0, b.x1, b.y1});
    } else {
      const int y = b.y0 + smallest + static_cast<int>(rng.uniform_index(static_cast<std::uint64_t>(h - 2 * smallest)));
      cv::line(mask, {b.x0, y}, {b.x1, y}, cv::Scalar(255), pen);
      stack.push_back({b.x0, b.y0, b.x1, y});
      stack.push_back({b.x0, y, b.x1, b.y1});
    }
  }
  cv::imwrite(path.string(), mask);
  return path;
}

// Arguments: image size, then 0 = the hierarchical network above (the targets), 1 = the
// dense oblique grid.
void BM_AnalyzeExemplar(benchmark::State& state) {
  const int size = static_cast<int>(state.range(0));
  const auto path = make_mask(size, state.range(1) != 0);
  ExemplarAnalysis a;
  for (auto _ : state) {
    a = analyze_exemplar(path);
    benchmark::DoNotOptimize(a.stats.fragment_count);
  }
  state.counters["megapixels"] = size * static_cast<double>(size) / 1e6;
  state.counters["crack_fraction"] = static_cast<double>(a.diagnostics.crack_pixels) / (static_cast<double>(size) * size);
  state.counters["fragments"] = a.stats.fragment_count;
  state.counters["junctions"] = a.stats.junction_count;
  state.counters["cracks"] = a.stats.crack_count;
}
BENCHMARK(BM_AnalyzeExemplar)->Args({1024, 0})->Args({4096, 0})->Args({2048, 1})->Args({4096, 1})->Unit(benchmark::kMillisecond);

// Peak resident memory of `fissure analyze` on the mask, measured on a child process
// (child_peak_memory.hpp), so nothing this benchmark allocated counts; and the part of it above
// the CLI's start-up baseline (`fissure --help`), which is the analysis itself.
void BM_AnalyzeExemplarPeakMemory(benchmark::State& state) {
  const int size = static_cast<int>(state.range(0));
  const auto path = make_mask(size, state.range(1) != 0);
  double peak = 0.0;
  for (auto _ : state) peak = bench::child_peak_rss_mb({FISSURE_BINARY_DIR "/bin/fissure", "analyze", path.string()});
  if (peak < 0) state.SkipWithError("fissure analyze failed");
  // What the process holds before any work: the shared libraries `fissure` loads at start.
  const double baseline = bench::child_peak_rss_mb({FISSURE_BINARY_DIR "/bin/fissure", "analyze", "--help"});
  state.counters["peak_rss_mb"] = peak;
  state.counters["cli_baseline_mb"] = baseline;
  state.counters["analysis_mb"] = peak - baseline;
  state.counters["megapixels"] = size * static_cast<double>(size) / 1e6;
}
BENCHMARK(BM_AnalyzeExemplarPeakMemory)->Args({1024, 0})->Args({4096, 0})->Args({4096, 1})->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
