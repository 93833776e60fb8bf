#include "terminal_progress.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <unistd.h>

namespace fissure::cli {
namespace {

// Length of the progress line now on the terminal (0: none), shared with the signal handler.
// One line at a time: the CLI runs one command, with one sink alive at a time.
std::atomic<std::size_t> g_shown_length{0};
static_assert(std::atomic<std::size_t>::is_always_lock_free, "read from a signal handler");

// write(2) until done or failed: progress is best effort, a failed write is not an error.
void write_all(const char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(STDERR_FILENO, data, size);
    if (n <= 0) return;
    data += n;
    size -= static_cast<std::size_t>(n);
  }
}

// "\r" + spaces over the old line + "\r". Fixed buffer: callable from a signal handler.
void erase_line() {
  const std::size_t length = g_shown_length.exchange(0);
  if (length == 0) return;
  char blanks[256];
  const std::size_t n = std::min(length, sizeof blanks - 2);
  blanks[0] = '\r';
  std::fill(blanks + 1, blanks + 1 + n, ' ');
  blanks[n + 1] = '\r';
  write_all(blanks, n + 2);
}

}  // namespace

TerminalProgress::TerminalProgress(bool quiet) : m_enabled(!quiet && ::isatty(STDERR_FILENO) == 1) {}

TerminalProgress::~TerminalProgress() { clear(); }

void TerminalProgress::report(std::string_view stage, double fraction) {
  if (!m_enabled || !(fraction >= 0.0)) return;  // NaN too
  const int percent = static_cast<int>(std::floor(std::min(fraction, 1.0) * 100.0));
  const auto now = std::chrono::steady_clock::now();
  std::lock_guard lock(m_mutex);
  const bool new_stage = stage != m_stage;
  if (!new_stage && (percent == m_percent || now - m_last < kMinInterval)) return;
  m_stage = stage;
  m_percent = percent;
  m_last = now;
  show(m_stage + " " + std::to_string(percent) + " %");
}

void TerminalProgress::stage(std::string_view name) {
  if (!m_enabled) return;
  std::lock_guard lock(m_mutex);
  m_stage = name;
  m_percent = -1;
  m_last = std::chrono::steady_clock::now();
  show(m_stage + " ...");
}

void TerminalProgress::clear() {
  if (!m_enabled) return;
  std::lock_guard lock(m_mutex);
  erase_line();
  m_stage.clear();
  m_percent = -1;
}

void TerminalProgress::show(const std::string& text) {
  // Pad over a longer previous line; the cursor stays at the end of the text.
  const std::size_t previous = g_shown_length.load();
  std::string line = "\r" + text;
  if (previous > text.size()) line.append(previous - text.size(), ' ');
  write_all(line.data(), line.size());
  g_shown_length.store(std::max(previous, text.size()));
}

void print_line_from_signal_handler(const char* line, std::size_t size) {
  erase_line();
  write_all(line, size);
}

}  // namespace fissure::cli
