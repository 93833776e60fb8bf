#pragma once
// Peak resident memory of a command, run through the peak_rss helper (see peak_rss.cpp for why a
// helper): the measured process is forked from a small program, not from the benchmark.

#include <sys/wait.h>

#include <cstdio>
#include <string>
#include <vector>

namespace fissure::bench {

/// Runs `argv` (argv[0] a path) and returns its peak resident set in MB, or −1 when it fails.
inline double child_peak_rss_mb(const std::vector<std::string>& argv) {
  std::string command = "'" FISSURE_BENCH_DIR "/peak_rss'";
  for (const std::string& a : argv) command += " '" + a + "'";  // the benchmarks' own paths: no quotes inside
  command += " 2>&1 >/dev/null";  // the command's output is not wanted; the helper's line comes last
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return -1.0;
  long kib = -1;
  char line[4096];
  while (std::fgets(line, sizeof line, pipe)) std::sscanf(line, "peak_rss_kib %ld", &kib);
  const int status = pclose(pipe);
  if (kib < 0 || status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) return -1.0;
  return static_cast<double>(kib) / 1024.0;
}

}  // namespace fissure::bench
