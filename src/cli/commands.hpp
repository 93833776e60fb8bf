#pragma once
// Subcommands of the `fissure` tool. Each register_* adds its subcommand to the app and stores
// the function that runs it; run_command() (command_main.hpp) runs it and turns core errors into
// exit codes.

#include <CLI/CLI.hpp>

#include <functional>

namespace fissure::cli {

/// Runs a parsed subcommand; returns the process exit code.
using Action = std::function<int()>;

/// Exit codes: one per error class, so scripts can tell a bad file from a bad parameter.
enum ExitCode : int {
  kExitOk = 0,
  kExitInternal = 1,      // a bug or an unexpected exception
  kExitUsage = 2,         // command-line syntax (CLI11)
  kExitInvalidInput = 3,  // InvalidInput: a parameter, mesh or selection is wrong
  kExitIo = 4,            // IoError: a file is missing, unreadable, corrupt or unwritable
  kExitNumerical = 5,     // NumericalFailure
  kExitCancelled = 6,     // Cancelled
};

void register_mesh(CLI::App& app, Action& action);
void register_solve(CLI::App& app, Action& action);
void register_modes(CLI::App& app, Action& action);
void register_analyze(CLI::App& app, Action& action);
void register_compare(CLI::App& app, Action& action);
void register_fracture(CLI::App& app, Action& action);
void register_fit(CLI::App& app, Action& action);
void register_scene(CLI::App& app, Action& action);

}  // namespace fissure::cli
