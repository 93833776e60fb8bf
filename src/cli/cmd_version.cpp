#include "cli_common.hpp"
#include "commands.hpp"

#include <iostream>

namespace fissure::cli {

void register_version(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand("version", "Print the Fissure version");
  add_threads_option(*cmd);
  cmd->callback([&action] {
    action = [] {
      std::cout << "fissure " << FISSURE_VERSION << '\n';
      return kExitOk;
    };
  });
}

}  // namespace fissure::cli
