#pragma once
// Pieces every command uses: the --threads option, where the summary goes, and a stopwatch.
// Nothing here may need a core module beyond base: every command's executable links this
// (fem_options.hpp and image_options.hpp hold what only some commands need).

#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <string>

namespace fissure::cli {

/// --threads N (1–1024) on every command: sets fissure::set_thread_count while parsing, so
/// assembly, CHOLMOD, OpenBLAS and every later parallel loop use at most N threads. Default:
/// $FISSURE_THREADS, else the hardware threads. Results are identical at any count.
void add_threads_option(CLI::App& cmd);

/// Where a command's summary goes: stdout, unless a result is written to stdout ("-").
std::FILE* summary_stream(const std::string& output);

class Stopwatch {
public:
  double milliseconds() const {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - m_start).count();
  }

private:
  std::chrono::steady_clock::time_point m_start = std::chrono::steady_clock::now();
};

}  // namespace fissure::cli
