// The dispatcher (bin/fissure) and the per-command executables: each command loads only the
// shared libraries it uses, and a broken installation gets one line, not a crash.

#include "test_support.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <sstream>
#include <string>

namespace fissure {
namespace {
namespace fs = std::filesystem;

std::string fissure() { return test::fissure_executable().string(); }

// Base names ("libcholmod.so.3") of the libraries the loader initialises for `fissure ARGS`.
std::set<std::string> initialised_libraries(const std::string& args) {
  // The loader writes to stderr; the command's own output is dropped inside the subshell.
  const auto r = test::run_command("(LD_DEBUG=libs " + fissure() + " " + args + " 2>&1 >/dev/null)");
  EXPECT_EQ(r.exit_code, 0) << args;
  std::set<std::string> names;
  std::istringstream lines(r.output);
  const std::string marker = "calling init: ";
  for (std::string line; std::getline(lines, line);) {
    const auto at = line.find(marker);
    if (at == std::string::npos) continue;
    const std::string name = fs::path(line.substr(at + marker.size())).filename().string();
    // A sanitizer build's runtimes are not the command's choice.
    if (name.rfind("libasan", 0) != 0 && name.rfind("libubsan", 0) != 0 && name.rfind("libtsan", 0) != 0) names.insert(name);
  }
  return names;
}

bool loads(const std::set<std::string>& libraries, const std::string& prefix) {
  for (const std::string& name : libraries)
    if (name.rfind(prefix, 0) == 0) return true;
  return false;
}

// Before the split every command initialised the same 44 libraries, CHOLMOD, OpenBLAS, OpenCV,
// assimp and CGAL's GMP among them, for `--version` too.
TEST(Dispatcher, EachCommandLoadsOnlyTheLibrariesItUses) {
  const auto version = initialised_libraries("--version");
  EXPECT_LE(version.size(), 6u) << "the C runtime, libstdc++, libm, libgcc_s and the loader";
  for (const char* heavy : {"libcholmod", "libopenblas", "libopencv", "libassimp", "libgmp", "libpng"})
    EXPECT_FALSE(loads(version, heavy)) << heavy;

  const auto mesh = initialised_libraries("mesh --help");
  EXPECT_TRUE(loads(mesh, "libgmp")) << "CGAL's exact predicates";
  for (const char* unused : {"libcholmod", "libopenblas", "libopencv", "libpng", "libjpeg", "libtiff"})
    EXPECT_FALSE(loads(mesh, unused)) << "mesh: " << unused;

  for (const char* command : {"solve --help", "modes --help"}) {
    const auto solve = initialised_libraries(command);
    EXPECT_TRUE(loads(solve, "libcholmod")) << command;
    for (const char* unused : {"libopencv", "libassimp", "libgmp", "libpng", "libjpeg", "libtiff"})
      EXPECT_FALSE(loads(solve, unused)) << command << ": " << unused;
  }
  for (const char* command : {"analyze --help", "compare --help"}) {
    const auto analyze = initialised_libraries(command);
    EXPECT_TRUE(loads(analyze, "libpng")) << command;
    // (OpenBLAS does come, as a dependency of OpenCV's core.)
    for (const char* unused : {"libcholmod", "libassimp", "libgmp", "libmpfr"})
      EXPECT_FALSE(loads(analyze, unused)) << command << ": " << unused;
  }
}

// The dispatcher copied away from libexec/: the command cannot be found, and the user is told
// which file is missing.
TEST(Dispatcher, AMissingCommandExecutableIsNamed) {
  const fs::path dir = test::fresh_temp_dir("dispatcher");
  fs::create_directories(dir / "bin");
  fs::copy_file(fissure(), dir / "bin" / "fissure");
  const auto r = test::run_command((dir / "bin" / "fissure").string() + " mesh --help");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_EQ(r.output, "fissure: cannot run the mesh command: " + (dir / "libexec" / "fissure" / "fissure-mesh").string() +
                          ": No such file or directory\n");
  // What the dispatcher answers itself still works without them.
  EXPECT_EQ(test::run_command((dir / "bin" / "fissure").string() + " version").exit_code, 0);
}

TEST(Dispatcher, UsageErrorsAreOneLine) {
  auto r = test::run_command(fissure() + " --frobnicate");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.output, "fissure: unknown option '--frobnicate' (see fissure --help)\n");
  r = test::run_command(fissure() + " version now");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.output, "fissure: version takes no arguments, got 'now' (see fissure version --help)\n");
  r = test::run_command(fissure());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.output, "fissure: a command is required (commands: mesh, solve, modes, analyze, compare, version)\n");
  // Every command the help lists is one the dispatcher can run.
  r = test::run_command(fissure() + " --help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* command : {"mesh", "solve", "modes", "analyze", "compare"}) {
    EXPECT_NE(r.output.find("  " + std::string(command) + " "), std::string::npos) << command;
    EXPECT_EQ(test::run_command(fissure() + " " + command + " --help").exit_code, 0) << command;
  }
}

}  // namespace
}  // namespace fissure
