// `fissure`: the dispatcher. It answers --help, --version and `version` itself and hands every
// other command to its own executable, libexec/fissure/fissure-<command>, with the same argv
// (execv: same process, same signals and exit code). A command thus loads only the libraries it
// uses: mesh no sparse solver, solve no image codec, and `--version` nothing but the C++ runtime
// (docs/architecture.md, "Start-up"). Deliberately free of CLI11 and the core modules.

#include "command_table.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <string>
#include <string_view>
#include <system_error>
#include <thread>
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

// The thread count a command will run with: its --threads N, else $FISSURE_THREADS, else the
// hardware threads (the rule of base/thread_count.hpp); 0 when a value does not parse (the
// command then refuses it).
unsigned requested_threads(int argc, char** argv) {
  auto parse = [](std::string_view text) -> unsigned {
    unsigned n = 0;
    for (char c : text) {
      if (c < '0' || c > '9' || n > 1024) return 0;
      n = n * 10 + static_cast<unsigned>(c - '0');
    }
    return n >= 1 && n <= 1024 ? n : 0;
  };
  for (int i = 2; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (arg == "--") break;
    if (arg == "--threads" && i + 1 < argc) return parse(argv[i + 1]);
    if (arg.starts_with("--threads=")) return parse(arg.substr(10));
  }
  if (const char* env = std::getenv("FISSURE_THREADS")) {
    if (const unsigned n = parse(env)) return n;
  }
  return std::max(1u, std::thread::hardware_concurrency());
}

// Holds the libraries that size their thread pools when they load, before the command can call
// anything: CHOLMOD 3 asks libgomp for a fixed team of 4 that only OMP_THREAD_LIMIT caps, and the
// pthread OpenBLAS starts a pool at load that Fissure never uses (it runs BLAS on one thread at
// every count so that results do not depend on it: fem/sparse_cholesky.cpp). A limit the user set
// is kept.
void limit_library_threads(unsigned threads) {
  setenv("OPENBLAS_NUM_THREADS", "1", 0);
  if (threads > 0) setenv("OMP_THREAD_LIMIT", std::to_string(threads).c_str(), 0);
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
  limit_library_threads(requested_threads(argc, argv));
  execv(executable.c_str(), argv);
  // Only reached when the installation is broken (a missing or non-executable file).
  std::cerr << "fissure: cannot run the " << first << " command: " << executable.string() << ": " << std::strerror(errno)
            << '\n';
  return kExitInternal;
}
