// What a user pays before any work: wall time from exec to exit, peak resident memory, and the
// shared libraries the dynamic loader initialises, for `fissure --version` and each command's
// `--help` (the command's own executable started and its options parsed, nothing computed).
// Iterations are sized by wall time (UseRealTime): the benchmark thread itself only waits.
// Issue 9's targets: --version ≤ 50 ms and ≤ 30 MB with ≤ 60 libraries, and no command loading a
// library it does not use (src/cli/CMakeLists.txt, docs/architecture.md "Start-up").

#include "child_peak_memory.hpp"

#include <benchmark/benchmark.h>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <set>
#include <sstream>
#include <string>
#include <vector>

extern char** environ;

namespace {

std::vector<std::string> command_line(const char* args) {
  std::vector<std::string> argv{FISSURE_BINARY_DIR "/bin/fissure"};
  std::istringstream words(args);
  for (std::string word; words >> word;) argv.push_back(word);
  return argv;
}

// One run with stdout and stderr to /dev/null; false when it could not start or failed.
bool run_once(const std::vector<std::string>& argv) {
  std::vector<char*> raw;
  for (const std::string& a : argv) raw.push_back(const_cast<char*>(a.c_str()));
  raw.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, raw[0], &actions, nullptr, raw.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) return false;
  int status = 0;
  if (waitpid(pid, &status, 0) != pid) return false;
  return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

// Distinct libraries the loader initialises over the whole run (the dispatcher's few are a subset
// of the command's, so the union is what the command process holds). −1 when the run failed.
double shared_libraries(const std::vector<std::string>& argv) {
  std::string command = "LD_DEBUG=libs";
  for (const std::string& a : argv) command += " '" + a + "'";
  command += " 2>&1 >/dev/null";
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return -1;
  std::set<std::string> initialised;
  char line[4096];
  while (std::fgets(line, sizeof line, pipe)) {
    if (const char* at = std::strstr(line, "calling init: ")) initialised.insert(at + std::strlen("calling init: "));
  }
  const int status = pclose(pipe);
  if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) return -1;
  return static_cast<double>(initialised.size());
}

void BM_Startup(benchmark::State& state, const char* args) {
  const auto argv = command_line(args);
  for (auto _ : state) {
    if (!run_once(argv)) {
      state.SkipWithError(("fissure " + std::string(args) + " failed").c_str());
      return;
    }
  }
  state.counters["peak_rss_mb"] = fissure::bench::child_peak_rss_mb(argv);
  state.counters["shared_libs"] = shared_libraries(argv);
}
BENCHMARK_CAPTURE(BM_Startup, version, "--version")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_Startup, mesh, "mesh --help")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_Startup, solve, "solve --help")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_Startup, modes, "modes --help")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_Startup, analyze, "analyze --help")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_Startup, compare, "compare --help")->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
