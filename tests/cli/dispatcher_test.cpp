// The dispatcher (bin/fissure) and the per-command executables: each command loads only the
// shared libraries it uses, and a broken installation gets one line, not a crash.

#include "test_support.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <spawn.h>
#include <sys/wait.h>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

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
  // Used to read "Value abc not in range 1 to 1024".
  r = test::run_command(fissure() + " mesh tile:1,1,0.05 --threads abc -o never.msh");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.output, "fissure: --threads: 'abc' is not a whole number (see fissure mesh --help)\n");
  // A bad FISSURE_THREADS is ignored, but said (it used to be ignored silently).
  r = test::run_command("FISSURE_THREADS=abc " + fissure() + " analyze /nonexistent.png");
  EXPECT_EQ(r.exit_code, 4);
  EXPECT_EQ(r.output.rfind("fissure: warning: FISSURE_THREADS=abc is not a whole number in [1, 1024]; it is ignored\n", 0), 0u)
      << r.output;
  r = test::run_command(fissure());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.output, "fissure: a command is required (commands: mesh, solve, modes, analyze, compare, fracture, fit, scene, version)\n");
  // Every command the help lists is one the dispatcher can run.
  r = test::run_command(fissure() + " --help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* command : {"mesh", "solve", "modes", "analyze", "compare", "fracture"}) {
    EXPECT_NE(r.output.find("  " + std::string(command) + " "), std::string::npos) << command;
    EXPECT_EQ(test::run_command(fissure() + " " + command + " --help").exit_code, 0) << command;
  }
}

// Threads of process `pid` now (0 once it is gone).
std::size_t task_count(pid_t pid) {
  std::error_code error;
  std::size_t n = 0;
  for (fs::directory_iterator it("/proc/" + std::to_string(pid) + "/task", error), end; !error && it != end; it.increment(error)) ++n;
  return n;
}

// --threads 2 holds the libraries too: CHOLMOD 3 asks libgomp for a fixed team of 4 and the
// pthread OpenBLAS starts a pool when it loads, both before the command runs; the dispatcher caps
// them through the environment. Without that, this solve peaked at 4 threads.
TEST(Dispatcher, TheThreadOptionHoldsTheLibrariesToo) {
  const fs::path dir = test::fresh_temp_dir("dispatcher-threads");
  const std::string mesh = (dir / "tile.msh").string();
  ASSERT_EQ(test::run_command(fissure() + " mesh tile:1,1,0.05 --tets 24000 -q -o " + mesh).exit_code, 0);
  std::vector<std::string> args{fissure(), "solve", mesh, "--E", "3e10", "--nu", "0.2", "--load",
                                "ball:0,0,0.05,0.05=0,0,-1e4", "--threads", "2", "-q", "-o", (dir / "out.msh").string()};
  for (const char* corner : {"box:-0.5,-0.45,-0.5,-0.45,0,0", "box:0.45,0.5,-0.5,-0.45,0,0", "box:-0.5,-0.45,0.45,0.5,0,0",
                             "box:0.45,0.5,0.45,0.5,0,0"}) {
    args.push_back("--fix");
    args.push_back(corner);
  }
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  // Without the variables a user may have set, which would hide what the dispatcher does.
  std::vector<std::string> env_strings{"PATH=/usr/bin:/bin", "HOME=" + dir.string()};
  std::vector<char*> env;
  for (std::string& e : env_strings) env.push_back(e.data());
  env.push_back(nullptr);
  pid_t pid = 0;
  ASSERT_EQ(posix_spawn(&pid, argv[0], nullptr, nullptr, argv.data(), env.data()), 0);
  std::size_t peak = 0;
  int status = 0;
  while (waitpid(pid, &status, WNOHANG) == 0) {
    peak = std::max(peak, task_count(pid));
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  EXPECT_GE(peak, 1u);
  EXPECT_LE(peak, 2u) << "threads of `fissure solve --threads 2` at their peak";
}

}  // namespace
}  // namespace fissure
