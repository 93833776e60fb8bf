#include "test_support.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdio>
#include <fstream>
#include <cstdlib>
#include <sys/wait.h>
#include <unistd.h>

namespace fissure::test {
namespace fs = std::filesystem;

fs::path source_dir() { return FISSURE_SOURCE_DIR; }
fs::path binary_dir() { return FISSURE_BINARY_DIR; }

fs::path shared_dir() {
  if (const char* env = std::getenv("FISSURE_SHARED_DIR"); env && *env) return env;
  return fs::weakly_canonical(source_dir() / ".." / "shared");
}

fs::path fresh_temp_dir(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("fissure-test-" + std::to_string(::getpid()) + "-" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

CommandResult run_command(const std::string& command) {
  CommandResult result;
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buffer{};
  std::size_t n;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) {
    result.output.append(buffer.data(), n);
  }
  const int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

fs::path fissure_executable() { return binary_dir() / "bin" / "fissure"; }

std::size_t peak_rss_bytes() {
  static std::atomic<std::size_t> highest{0};
  std::size_t now = 0;
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);) {
    if (line.rfind("VmHWM:", 0) == 0) now = std::stoull(line.substr(6)) * 1024;
  }
  std::size_t seen = highest.load();
  while (now > seen && !highest.compare_exchange_weak(seen, now)) {
  }
  return std::max(now, seen);
}

std::size_t peak_rss_growth(std::size_t before) {
  const std::size_t now = peak_rss_bytes();
  return now > before ? now - before : 0;
}

}  // namespace fissure::test
