#pragma once
// Progress of a long command on the terminal: "\rtetrahedralize 37 %" rewritten in place on
// stderr. Silent when stderr is not a terminal (logs and pipes get no carriage returns) or when
// the user asked for --quiet.

#include "fissure/base/progress.hpp"

#include <chrono>
#include <cstddef>
#include <mutex>
#include <string>
#include <string_view>

namespace fissure::cli {

class TerminalProgress final : public ProgressSink {
public:
  /// Prints only when !quiet and stderr is a terminal.
  explicit TerminalProgress(bool quiet);
  /// Clears the line, so whatever is printed next starts at column 0.
  ~TerminalProgress() override;
  TerminalProgress(const TerminalProgress&) = delete;
  TerminalProgress& operator=(const TerminalProgress&) = delete;

  /// Thread-safe. A new stage is shown at once; within a stage the line is rewritten at most
  /// kMinInterval apart, and only when the whole percentage changed.
  void report(std::string_view stage, double fraction) override;
  /// A stage whose fraction is not known ("reading tile.msh"): shown as "reading tile.msh ...".
  void stage(std::string_view name);
  /// Erases the progress line.
  void clear();

  bool enabled() const { return m_enabled; }

  /// "A few times per second" (the brief of ProgressSink): fast enough to look alive, slow
  /// enough that a terminal over ssh is not flooded.
  static constexpr std::chrono::milliseconds kMinInterval{250};

private:
  void show(const std::string& text);

  const bool m_enabled;
  std::mutex m_mutex;
  std::string m_stage;
  int m_percent = -1;
  std::chrono::steady_clock::time_point m_last{};
};

/// Erases the progress line and prints `line` (with its newline) on stderr, from a signal
/// handler: async-signal-safe, write(2) only. For "fissure: cancelled".
void print_line_from_signal_handler(const char* line, std::size_t size);

}  // namespace fissure::cli
