#include "fissure/base/parallel.hpp"

#include "fissure/base/thread_count.hpp"

#include <algorithm>
#include <atomic>
#include <mutex>
#include <exception>
#include <thread>
#include <vector>

namespace fissure {

namespace {
std::size_t worker_count(std::size_t count, int threads) {
  return std::min<std::size_t>(count, static_cast<std::size_t>(std::max(std::min(threads, thread_count()), 1)));
}
}  // namespace

void parallel_for(std::size_t count, int threads, const std::function<void(std::size_t)>& body) {
  const std::size_t workers = worker_count(count, threads);
  if (workers <= 1) {
    for (std::size_t i = 0; i < count; ++i) body(i);
    return;
  }
  std::vector<std::exception_ptr> errors(workers);
  const auto run_block = [&](std::size_t w) {
    const std::size_t begin = count * w / workers;
    const std::size_t end = count * (w + 1) / workers;
    for (std::size_t i = begin; i < end; ++i) {
      try {
        body(i);
      } catch (...) {
        errors[w] = std::current_exception();
        return;
      }
    }
  };
  // The calling thread takes the first block, so N threads means N threads in the process, not
  // N workers beside an idle caller.
  std::vector<std::thread> pool;
  pool.reserve(workers - 1);
  for (std::size_t w = 1; w < workers; ++w) pool.emplace_back(run_block, w);
  run_block(0);
  for (auto& t : pool) t.join();
  // Blocks are in index order, so the first worker with an error holds the lowest failing index.
  for (std::size_t w = 0; w < workers; ++w) {
    if (errors[w]) std::rethrow_exception(errors[w]);
  }
}

void parallel_for_dynamic(std::size_t count, int threads, const std::function<void(std::size_t)>& body) {
  const std::size_t workers = worker_count(count, threads);
  if (workers <= 1) {
    for (std::size_t i = 0; i < count; ++i) body(i);
    return;
  }
  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  std::mutex error_mutex;
  std::size_t error_index = count;
  std::exception_ptr error;
  const auto work = [&] {
    for (;;) {
      if (failed.load(std::memory_order_relaxed)) return;
      const std::size_t i = next.fetch_add(1, std::memory_order_relaxed);
      if (i >= count) return;
      try {
        body(i);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(error_mutex);
        if (i < error_index) error_index = i, error = std::current_exception();
        failed.store(true, std::memory_order_relaxed);
        return;
      }
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(workers - 1);
  for (std::size_t w = 1; w < workers; ++w) pool.emplace_back(work);
  work();
  for (auto& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

int hardware_threads() { return std::max(1u, std::thread::hardware_concurrency()); }

}  // namespace fissure
