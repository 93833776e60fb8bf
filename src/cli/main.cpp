// `fissure`: the command-line front end. A thin layer over the core: parse, call, report.

#include "commands.hpp"

#include "fissure/base/error.hpp"

#include <exception>
#include <iostream>

int main(int argc, char** argv) {
  using namespace fissure::cli;
  CLI::App app{"Fissure: example-based fracture modelling"};
  app.require_subcommand(1);
  app.set_version_flag("--version", FISSURE_VERSION);

  Action action;
  register_mesh(app, action);
  register_solve(app, action);
  register_modes(app, action);
  register_analyze(app, action);
  register_compare(app, action);
  register_version(app, action);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kExitOk : kExitUsage;
  }

  try {
    return action ? action() : kExitUsage;
  } catch (const fissure::InvalidInput& e) {
    std::cerr << "fissure: invalid input: " << e.what() << '\n';
    return kExitInvalidInput;
  } catch (const fissure::IoError& e) {
    std::cerr << "fissure: " << e.what() << '\n';
    return kExitIo;
  } catch (const fissure::NumericalFailure& e) {
    std::cerr << "fissure: numerical failure: " << e.what() << '\n';
    return kExitNumerical;
  } catch (const fissure::Cancelled& e) {
    std::cerr << "fissure: cancelled\n";
    return kExitCancelled;
  } catch (const std::exception& e) {
    std::cerr << "fissure: internal error: " << e.what() << '\n';
    return kExitInternal;
  }
}
