#pragma once
// Pieces every command uses: where the summary goes, and a stopwatch. Nothing here may need a
// core module: every command's executable links this (fem_options.hpp and image_options.hpp hold
// what only some commands need).

#include <chrono>
#include <cstdio>
#include <string>

namespace fissure::cli {

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
