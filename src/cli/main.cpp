// `fissure`: the dispatcher. It answers --help, --version and `version` itself and hands every
// other command to its own executable, libexec/fissure/fissure-<command>, with the same argv
// (execv: same process, same signals and exit code). A command thus loads only the libraries it
// uses: mesh no sparse solver, solve no image codec, and `--version` nothing but the C++ runtime
// (docs/architecture.md, "Start-up"). Deliberately free of CLI11 and the core modules.

#include "command_table.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <string>
#include <string_view>
#include <system_error>
#include <unistd.h>

namespace {

using fissure::cli::kCommands;

constexpr int kExitInternal = 1;  // the exit codes of commands.hpp, which needs CLI11
constexpr int kExitUsage = 2;

std::string command_list() {
  std::string list;
  for (const auto& command : kCommands) list += (list.empty() ? "" : ", ") + std::string(command.name);
  return list;
}

void print_help() {
  std::cout << "Fissure: example-based fracture modelling\n"
               "Usage: fissure [OPTIONS] COMMAND [ARGS...]\n\n"
               "Options:\n"
               "  -h,--help                   Print this help message and exit\n"
               "  --version                   Display program version information and exit\n\n"
               "Commands (fissure COMMAND --help for each):\n";
  for (const auto& command : kCommands) {
    std::string name(command.name);
    name.resize(std::max<std::size_t>(name.size() + 1, 28), ' ');
    std::cout << "  " << name << command.summary << '\n';
  }
}

int usage_error(const std::string& message) {
  std::cerr << "fissure: " << message << '\n';
  return kExitUsage;
}

// `fissure version [--help]`: the one command without an executable of its own.
int version_command(int argc, char** argv) {
  if (argc == 2) {
    std::cout << "fissure " << FISSURE_VERSION << '\n';
    return 0;
  }
  const std::string_view arg = argv[2];
  if (argc == 3 && (arg == "-h" || arg == "--help")) {
    std::cout << fissure::cli::command_info("version").summary << "\nUsage: fissure version [OPTIONS]\n\n"
              << "Options:\n  -h,--help                   Print this help message and exit\n";
    return 0;
  }
  return usage_error("version takes no arguments, got '" + std::string(arg) + "' (see fissure version --help)");
}

// libexec/fissure/ beside the bin/ directory this executable is in, found through /proc so that
// a symlink to bin/fissure or a relative PATH entry still finds the real install.
std::filesystem::path libexec_directory() {
  std::error_code error;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error) return {};
  return self.parent_path().parent_path() / "libexec" / "fissure";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) return usage_error("a command is required (commands: " + command_list() + ")");
  const std::string_view first = argv[1];
  if (first == "-h" || first == "--help") {
    print_help();
    return 0;
  }
  if (first == "--version") {
    std::cout << FISSURE_VERSION << '\n';
    return 0;
  }
  if (first == "version") return version_command(argc, argv);
  if (first.starts_with('-')) return usage_error("unknown option '" + std::string(first) + "' (see fissure --help)");
  bool known = false;
  for (const auto& command : kCommands) known = known || command.name == first;
  if (!known) return usage_error("unknown command '" + std::string(first) + "' (commands: " + command_list() + ")");

  const std::filesystem::path executable = libexec_directory() / ("fissure-" + std::string(first));
  execv(executable.c_str(), argv);
  // Only reached when the installation is broken (a missing or non-executable file).
  std::cerr << "fissure: cannot run the " << first << " command: " << executable.string() << ": " << std::strerror(errno)
            << '\n';
  return kExitInternal;
}
