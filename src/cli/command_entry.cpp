// main() of one command's executable, fissure-<name>. CMake compiles this file once per command
// with FISSURE_REGISTER_COMMAND set to that command's register function (src/cli/CMakeLists.txt).

#include "command_main.hpp"

int main(int argc, char** argv) { return fissure::cli::run_command(argc, argv, fissure::cli::FISSURE_REGISTER_COMMAND); }
