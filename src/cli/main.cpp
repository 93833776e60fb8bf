// `fissure`: the command-line front end. A thin layer over the core: parse, call, report.

#include "cli_common.hpp"
#include "commands.hpp"
#include "interruption.hpp"

#include "fissure/base/error.hpp"

#include <cstring>
#include <exception>
#include <iostream>
#include <new>
#include <string>

namespace {

using namespace fissure::cli;

// Every failure is one line: a message from a library may hold newlines (CLI11's own, or a
// core message quoting a file).
std::string one_line(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r' || text.back() == ' ')) text.pop_back();
  for (char& c : text)
    if (c == '\n' || c == '\r') c = ' ';
  return text;
}

// "mesh, solve, modes, analyze, compare, version", in the order they were registered.
std::string command_list(CLI::App& app) {
  std::string list;
  for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
    list += (list.empty() ? "" : ", ") + sub->get_name();
  }
  return list;
}

}  // namespace

int main(int argc, char** argv) {
  install_interrupt_handlers();
  CLI::App app{"Fissure: example-based fracture modelling"};
  app.require_subcommand(1);
  app.set_version_flag("--version", FISSURE_VERSION);
  add_threads_option(app);

  Action action;
  register_mesh(app, action);
  register_solve(app, action);
  register_modes(app, action);
  register_analyze(app, action);
  register_compare(app, action);
  register_version(app, action);

  // CLI11 answers an unknown command with "A subcommand is required": name it instead.
  if (argc < 2 || (argv[1][0] != '-' && app.get_subcommands([&](CLI::App* sub) { return sub->check_name(argv[1]); }).empty())) {
    std::cerr << "fissure: " << (argc < 2 ? std::string("a command is required") : "unknown command '" + std::string(argv[1]) + "'")
              << " (commands: " << command_list(app) << ")\n";
    return kExitUsage;
  }
  // CLI11's messages, in one line that says where help is.
  app.failure_message([](const CLI::App* top, const CLI::Error& e) {
    const auto chosen = top->get_subcommands();
    const std::string help = chosen.empty() ? "fissure --help" : "fissure " + chosen.front()->get_name() + " --help";
    return "fissure: " + one_line(e.what()) + " (see " + help + ")\n";
  });

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kExitOk : kExitUsage;
  }

  try {
    return action ? action() : kExitUsage;
  } catch (const fissure::MemoryLimitExceeded& e) {
    // Every command that can be refused for its memory estimate takes --allow-large.
    std::cerr << "fissure: invalid input: " << one_line(e.what()) << "; --allow-large tries anyway\n";
    return kExitInvalidInput;
  } catch (const fissure::InvalidInput& e) {
    std::cerr << "fissure: invalid input: " << one_line(e.what()) << '\n';
    return kExitInvalidInput;
  } catch (const fissure::IoError& e) {
    std::cerr << "fissure: " << one_line(e.what()) << '\n';
    return kExitIo;
  } catch (const fissure::NumericalFailure& e) {
    std::cerr << "fissure: numerical failure: " << one_line(e.what()) << '\n';
    return kExitNumerical;
  } catch (const fissure::Cancelled&) {
    std::cerr << "fissure: cancelled\n";
    return kExitCancelled;
  } catch (const std::bad_alloc&) {
    std::cerr << "fissure: out of memory (try a smaller request)\n";
    return kExitInternal;
  } catch (const std::exception& e) {
    std::cerr << "fissure: internal error: " << one_line(e.what()) << '\n';
    return kExitInternal;
  }
}
