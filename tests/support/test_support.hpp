#pragma once
// Paths and small utilities shared by the test binaries.

#include <cstddef>
#include <filesystem>
#include <string>

namespace fissure::test {

/// The repository root.
std::filesystem::path source_dir();
/// The CMake build directory (holds bin/fissure).
std::filesystem::path binary_dir();
/// The shared third-party data folder: $FISSURE_SHARED_DIR, else <repo>/../shared. The exemplars
/// are read from there and never copied into the repository.
std::filesystem::path shared_dir();
/// A fresh, empty directory under the system temp dir, unique to this process and `name`.
std::filesystem::path fresh_temp_dir(const std::string& name);

/// Result of running a command through the shell.
struct CommandResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr, interleaved
};
/// Runs `command` with /bin/sh, capturing stdout and stderr.
CommandResult run_command(const std::string& command);
/// Path of the built `fissure` executable.
std::filesystem::path fissure_executable();

/// The process's peak resident memory so far (VmHWM), never smaller than an earlier answer.
/// The kernel's VmHWM itself can fall by a few hundred kB: it is max(recorded peak, current RSS),
/// and the recorded peak is only updated on some paths, so memory returned by madvise (as
/// AddressSanitizer's allocator does) lowers a peak that was only ever the current RSS. A fuzz
/// run under the sanitizers once saw it fall by 258 kB, which an unsigned difference turned into
/// +18 TB.
std::size_t peak_rss_bytes();
/// How much the peak grew since `before` (an earlier peak_rss_bytes()).
std::size_t peak_rss_growth(std::size_t before);

}  // namespace fissure::test
