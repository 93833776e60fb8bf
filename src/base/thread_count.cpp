#include "fissure/base/thread_count.hpp"

#include "fissure/base/error.hpp"
#include "fissure/base/number_text.hpp"
#include "fissure/base/parallel.hpp"

#include <atomic>
#include <cstdlib>
#include <string>

namespace fissure {

namespace {

constexpr int kMaxThreads = 1024;

// FISSURE_THREADS, or 0 when unset or not a count: an environment variable is a hint, so a bad
// value falls back to the default instead of failing every command.
int environment_threads() {
  const char* text = std::getenv("FISSURE_THREADS");
  if (!text || !*text) return 0;
  char* end = nullptr;
  const long n = std::strtol(text, &end, 10);
  return (*end == '\0' && n >= 1 && n <= kMaxThreads) ? static_cast<int>(n) : 0;
}

// 0 until set_thread_count is called.
std::atomic<int> g_thread_count{0};

}  // namespace

void set_thread_count(int n) {
  if (n < 1 || n > kMaxThreads)
    throw InvalidInput("thread count " + format_number(n) + " is outside [1, " + format_number(kMaxThreads) + "]");
  g_thread_count.store(n, std::memory_order_relaxed);
}

int thread_count() {
  const int set = g_thread_count.load(std::memory_order_relaxed);
  if (set > 0) return set;
  static const int fallback = [] {
    const int env = environment_threads();
    return env > 0 ? env : hardware_threads();
  }();
  return fallback;
}

}  // namespace fissure
