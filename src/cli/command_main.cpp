// What every command's executable does around its command: parse, run, and turn a core error
// into one line and an exit code. Each fissure-<name> executable's main() is run_command(...).

#include "command_main.hpp"
#include "interruption.hpp"

#include "fissure/base/error.hpp"

#include <cstring>
#include <exception>
#include <cstdlib>
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

}  // namespace

namespace fissure::cli {

int run_command(int argc, char** argv, void (*register_command)(CLI::App&, Action&)) {
  install_interrupt_handlers();
  // The top level is `fissure` with this one subcommand, so usage lines and messages read
  // "fissure mesh ..." as the user typed them: the dispatcher passes its argv unchanged.
  CLI::App app{"Fissure: example-based fracture modelling", "fissure"};
  app.require_subcommand(1);
  Action action;
  register_command(app, action);

  // CLI11's messages, in one line that says where help is.
  app.failure_message([](const CLI::App* top, const CLI::Error& e) {
    // The deepest subcommand chosen ("fissure scene fracture --help", not "fissure scene --help").
    std::string help = "fissure";
    for (const CLI::App* at = top; !at->get_subcommands().empty();) {
      at = at->get_subcommands().front();
      help += " " + at->get_name();
    }
    help += " --help";
    return "fissure: " + one_line(e.what()) + " (see " + help + ")\n";
  });

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kExitOk : kExitUsage;
  }

  // FISSURE_THREADS is a hint: a value that is not a count falls back to the default
  // (base/thread_count.cpp), but not silently.
  if (const char* text = std::getenv("FISSURE_THREADS"); text && *text) {
    char* end = nullptr;
    const long n = std::strtol(text, &end, 10);
    if (*end != '\0' || n < 1 || n > 1024) {
      std::cerr << "fissure: warning: FISSURE_THREADS=" << text
                << " is not a whole number in [1, 1024]; it is ignored\n";
    }
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

}  // namespace fissure::cli
