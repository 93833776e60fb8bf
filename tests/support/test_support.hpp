#pragma once
// Paths and small utilities shared by the test binaries.

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

}  // namespace fissure::test
