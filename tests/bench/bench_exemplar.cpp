// Exemplar analysis (tracing → crack graph → statistics) on synthetic masks of 1024² and 4096²
// px, one core. Targets (issue 4): 1024² ≤ 50 ms, 4096² ≤ 1 s, peak memory on 4096² ≤ 300 MB.
// The mask: a hierarchical network of orthogonal cracks (each rectangle split across its longer
// side at a random position), pen width scaled with the image, ~12 % crack pixels, written as a
// PNG so the timing includes decoding as `fissure analyze` does.

#include "fissure/base/rng.hpp"
#include "fissure/exemplar/exemplar_analysis.hpp"

#include <benchmark/benchmark.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>

namespace {
using namespace fissure;

std::filesystem::path make_mask(int size) {
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

void BM_AnalyzeExemplar(benchmark::State& state) {
  const int size = static_cast<int>(state.range(0));
  const auto path = make_mask(size);
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
BENCHMARK(BM_AnalyzeExemplar)->Arg(1024)->Arg(4096)->Unit(benchmark::kMillisecond);

// Peak resident memory of a whole analysis in a fresh child process (wait4), so nothing this
// benchmark allocated before counts.
void BM_AnalyzeExemplarPeakMemory(benchmark::State& state) {
  const int size = static_cast<int>(state.range(0));
  const auto path = make_mask(size);
  double peak = 0.0;
  for (auto _ : state) {
    const pid_t pid = fork();
    if (pid == 0) {
      try {
        analyze_exemplar(path);
      } catch (...) {
        _exit(1);
      }
      _exit(0);
    }
    int status = 0;
    rusage usage{};
    wait4(pid, &status, 0, &usage);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) state.SkipWithError("analysis failed");
    peak = static_cast<double>(usage.ru_maxrss) / 1024.0;
  }
  state.counters["peak_rss_mb"] = peak;
  state.counters["megapixels"] = size * static_cast<double>(size) / 1e6;
}
BENCHMARK(BM_AnalyzeExemplarPeakMemory)->Arg(1024)->Arg(4096)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
