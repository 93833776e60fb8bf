#pragma once
// The body of every command executable's main(): see command_main.cpp.

#include "commands.hpp"

namespace fissure::cli {

/// Parses `argv` ("fissure", "<command>", args...) for the one command `register_command` adds,
/// runs it, and returns the exit code; every error is one line on stderr.
int run_command(int argc, char** argv, void (*register_command)(CLI::App&, Action&));

}  // namespace fissure::cli
