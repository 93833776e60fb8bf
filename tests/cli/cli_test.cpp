// The `fissure` executable end to end: exit codes, one-line messages, outputs gmsh opens,
// byte-identical results at 1 and 2 threads, progress on a terminal, Ctrl-C, memory limits and
// writes that lose nothing.

#include "fissure/base/atomic_file.hpp"
#include "fissure/io/msh.hpp"

#include "test_support.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <chrono>
#include <csignal>
#include <fcntl.h>
#include <fstream>
#include <optional>
#include <sstream>
#include <sys/mount.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

namespace fissure {
namespace {
namespace fs = std::filesystem;

std::string fissure() { return test::fissure_executable().string(); }

class Cli : public ::testing::Test {
protected:
  static void SetUpTestSuite() {
    dir = test::fresh_temp_dir("cli");
    const auto r = test::run_command(fissure() + " mesh tile:0.6,0.4,0.1 --tets 3000 -q -o " + (dir / "tile.msh").string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  static fs::path dir;
  std::string mesh() const { return (dir / "tile.msh").string(); }
  std::string corners() const {
    return " --fix box:-0.3,-0.25,-0.2,-0.15,0,0 --fix box:0.25,0.3,-0.2,-0.15,0,0"
           " --fix box:-0.3,-0.25,0.15,0.2,0,0 --fix box:0.25,0.3,0.15,0.2,0,0";
  }
};
fs::path Cli::dir;

// A brick-wall tracing (T junctions) and a honeycomb (Y junctions), drawn by the test.
void draw_tracings(const fs::path& dir) {
  cv::Mat bricks(300, 300, CV_8U, cv::Scalar(255));  // black cracks on white, as a pen tracing
  for (int y = 25; y < 300; y += 50) {
    cv::line(bricks, {0, y}, {299, y}, cv::Scalar(0), 2);
    for (int x = ((y / 50) % 2) * 50 + 25; x < 300; x += 100) cv::line(bricks, {x, y}, {x, std::min(y + 50, 299)}, cv::Scalar(0), 2);
  }
  cv::imwrite((dir / "bricks.png").string(), bricks);
  cv::Mat cells(300, 300, CV_8U, cv::Scalar(0));
  for (int row = -1; row < 12; ++row)
    for (int col = -1; col < 10; ++col) {
      std::vector<cv::Point> hex;
      const double cx = col * 34.64 + (row % 2 ? 17.32 : 0.0), cy = row * 30.0;
      for (int k = 0; k < 6; ++k) {
        const double a = (60.0 * k - 30.0) * 3.14159265358979 / 180.0;
        hex.emplace_back(static_cast<int>(cx + 20.0 * std::cos(a)), static_cast<int>(cy + 20.0 * std::sin(a)));
      }
      cv::polylines(cells, hex, true, cv::Scalar(255), 2);
    }
  cv::imwrite((dir / "cells.jpg").string(), cells);
}

// A failure is exactly one line, "fissure: <message naming the culprit>", and a distinct code.
// (CLI11's own errors used to take two lines without the prefix.)
void expect_failure(const test::CommandResult& r, int code, const std::string& words) {
  EXPECT_EQ(r.exit_code, code) << r.output;
  EXPECT_NE(r.output.find(words), std::string::npos) << r.output;
  EXPECT_EQ(r.output.rfind("fissure: ", 0), 0u) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_EQ(r.output.back(), '\n') << r.output;
}

std::size_t occurrences(const std::string& text, const std::string& word) {
  std::size_t n = 0;
  for (std::size_t at = text.find(word); at != std::string::npos; at = text.find(word, at + word.size())) ++n;
  return n;
}

// Every subcommand has a help that names its required arguments (marked REQUIRED on their line)
// and the options every command of its kind must have. analyze and compare used to be skipped,
// and compare had no --max-megapixels.
TEST_F(Cli, HelpOnEverySubcommand) {
  struct Help {
    const char* command;
    std::vector<std::string> required;
    std::vector<std::string> options;
  };
  const std::vector<Help> helps = {
      {"", {}, {"mesh", "solve", "modes", "analyze", "compare", "version"}},
      {"mesh", {"INPUT", "-o,--output"}, {"--tets", "--allow-large", "--quiet"}},
      {"solve", {"MESH", "--E", "--nu", "-o,--output"}, {"--fix", "--load", "--modes", "--allow-large", "--quiet"}},
      {"modes", {"MESH", "--E", "--nu", "--rho", "--count"}, {"--fix", "--cache-dir", "--allow-large", "--quiet"}},
      {"analyze", {"IMAGE"}, {"--json", "--overlay", "--max-megapixels", "--quiet"}},
      {"compare", {"A", "B"}, {"--weights", "--max-megapixels", "--quiet"}},
      {"version", {}, {}},
  };
  for (const Help& help : helps) {
    const std::string command = help.command;
    const auto r = test::run_command(fissure() + " " + command + " --help");
    EXPECT_EQ(r.exit_code, 0) << command << r.output;
    EXPECT_NE(r.output.find("Usage"), std::string::npos) << command;
    for (const std::string& name : help.required) {
      bool marked = false;
      std::istringstream lines(r.output);
      for (std::string line; std::getline(lines, line);) {
        if (line.rfind("  " + name + " ", 0) == 0 && line.find("REQUIRED") != std::string::npos) marked = true;
      }
      EXPECT_TRUE(marked) << command << " --help does not mark " << name << " as required:\n" << r.output;
    }
    for (const std::string& name : help.options) EXPECT_NE(r.output.find(name), std::string::npos) << command << ": " << name;
    if (!help.required.empty()) {
      // Without its required arguments: one line naming the first, and where help is.
      const auto missing = test::run_command(fissure() + " " + command);
      expect_failure(missing, 2, " is required (see fissure " + command + " --help)");
    }
  }
}

// Messages that named the wrong thing on today's main, each now one line naming the culprit.
TEST_F(Cli, MessagesNameTheCulprit) {
  // Used to be "A subcommand is required".
  expect_failure(test::run_command(fissure() + " foo"), 2,
                 "fissure: unknown command 'foo' (commands: mesh, solve, modes, analyze, compare, fracture, fit, scene, version)");
  // Used to be "expected three numbers x,y,z".
  draw_tracings(dir);
  const std::string bricks = (dir / "bricks.png").string();
  expect_failure(test::run_command(fissure() + " compare " + bricks + " " + bricks + " --weights 1,1"), 3,
                 "--weights: expected 3 numbers fragment,crack,junction, got 2");
  const std::string solve = fissure() + " solve " + mesh() + " --E 3e10 --nu 0.2" + corners();
  const std::string out = " -o " + (dir / "never.msh").string();
  expect_failure(test::run_command(solve + " --gravity 0,-9.81" + out), 3, "--gravity: expected 3 numbers gx,gy,gz (m/s^2), got 2");
  // compare decodes images too, so it has the pixel limit; the hint names the flag once.
  const auto big = test::run_command(fissure() + " compare " + bricks + " " + bricks + " --max-megapixels 0.01");
  expect_failure(big, 3, "above the limit");
  EXPECT_EQ(occurrences(big.output, "(raise it with --max-megapixels)"), 1u) << big.output;
  // Non-finite and absurd values: "inf" used to overflow the pixel count, NaN passed CLI11's Range.
  const std::string analyze = fissure() + " analyze " + bricks + " --json " + (dir / "never.json").string();
  expect_failure(test::run_command(analyze + " --max-megapixels inf"), 2, "--max-megapixels: 'inf' is not a finite number");
  expect_failure(test::run_command(analyze + " --max-megapixels 1e300"), 2, "--max-megapixels: 1e300 is outside [0.001, 10000]");
  expect_failure(test::run_command(analyze + " --spur-factor nan"), 2, "--spur-factor: 'nan' is not a finite number");
  expect_failure(test::run_command(solve + " --E nan --load zmax=0,0,-1" + out), 2, "--E: 'nan' is not a finite number");
  expect_failure(test::run_command(fissure() + " mesh tile:1,1,0.1 --tets 2.5" + out), 2, "--tets: '2.5' is not a whole number");
  // -o x.stl used to write STL although the help says MSH.
  const std::string stl = (dir / "x.stl").string();
  // Refused before any work, by the writer's own check (an output file problem: exit 4).
  expect_failure(test::run_command(fissure() + " mesh tile:1,1,0.1 --tets 500 -o " + stl), 4,
                 stl + ": the output must end in .msh");
  expect_failure(test::run_command(solve + " --load zmax=0,0,-1 -o " + stl), 4, stl + ": the output must end in .msh");
  EXPECT_FALSE(fs::exists(stl));
  EXPECT_FALSE(fs::exists(dir / "never.msh"));
  EXPECT_FALSE(fs::exists(dir / "never.json"));
}

TEST_F(Cli, SolveWritesViewsGmshOpens) {
  const std::string out = (dir / "result.msh").string();
  const auto r = test::run_command(fissure() + " solve " + mesh() + " --E 3e10 --nu 0.2" + corners() +
                                   " --load ball:0,0,0.1,0.05=0,0,-1e4 -o " + out);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("residual"), std::string::npos) << r.output;
  const fs::path script = dir / "views.geo";
  write_file_atomically(script, "Merge \"" + out + "\";\nPrintf(\"views=%g\", PostProcessing.NbViews);\n");
  const auto g = test::run_command("gmsh " + script.string() + " -0 -o " + (dir / "x.geo_unrolled").string());
  EXPECT_NE(g.output.find("views=3"), std::string::npos) << g.output;
  const TetMesh back = read_msh(out);
  EXPECT_EQ(back.tet_count(), read_msh(mesh()).tet_count());
}

TEST_F(Cli, ModesPrintJsonAndTheModalSolveRuns) {
  const std::string cache = " --cache-dir " + (dir / "cache").string();
  const auto r = test::run_command(fissure() + " modes " + mesh() + " --E 3e10 --nu 0.2 --rho 2400 --count 5" + cache);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("\"frequencies_hz\""), std::string::npos);
  EXPECT_NE(r.output.find("\"rigid_modes\": 6"), std::string::npos) << r.output;
  const auto s = test::run_command(fissure() + " solve " + mesh() + " --E 3e10 --nu 0.2" + corners() +
                                   " --load ball:0,0,0.1,0.05=0,0,-1e4 --modes 20" + cache + " -o " + (dir / "modal.msh").string());
  EXPECT_EQ(s.exit_code, 0) << s.output;
  EXPECT_NE(s.output.find("modal, 20 modes"), std::string::npos) << s.output;
}

TEST_F(Cli, SameBytesAtOneAndTwoThreads) {
  std::string bytes[2];
  for (int threads : {1, 2}) {
    const fs::path out = dir / ("threads" + std::to_string(threads) + ".msh");
    // CHOLMOD may use OpenMP and the BLAS its own threads: neither may change the bytes.
    const std::string env = "OMP_NUM_THREADS=" + std::to_string(threads) + " OPENBLAS_NUM_THREADS=" + std::to_string(threads) + " ";
    const auto r = test::run_command(env + fissure() + " solve " + mesh() + " --E 3e10 --nu 0.2 --gravity 0,0,-9.81" +
                                     corners() + " --threads " + std::to_string(threads) + " -q -o " + out.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    bytes[threads - 1] = read_file(out);
  }
  EXPECT_EQ(bytes[0], bytes[1]);
  const fs::path again = dir / "again.msh";
  ASSERT_EQ(test::run_command(fissure() + " mesh tile:0.6,0.4,0.1 --tets 3000 -q -o " + again.string()).exit_code, 0);
  EXPECT_EQ(read_file(again), read_file(mesh()));
}

TEST_F(Cli, BadInputGivesOneLineAndADistinctCode) {
  const std::string solve = fissure() + " solve " + mesh();
  const std::string out = " -o " + (dir / "never.msh").string();
  const std::string load = " --load ball:0,0,0.1,0.05=0,0,-1e4";
  expect_failure(test::run_command(fissure() + " solve " + (dir / "missing.msh").string() + " --E 3e10 --nu 0.2" + load + out),
                 4, "missing.msh: no such file");
  write_file_atomically(dir / "empty.msh", "");
  expect_failure(test::run_command(fissure() + " solve " + (dir / "empty.msh").string() + " --E 3e10 --nu 0.2" + load + out),
                 4, "empty.msh: file is empty");
  const std::string good = read_file(mesh());
  write_file_atomically(dir / "cut.msh", good.substr(0, good.size() / 3));
  expect_failure(test::run_command(fissure() + " solve " + (dir / "cut.msh").string() + " --E 3e10 --nu 0.2" + load + out),
                 4, "truncated");
  write_file_atomically(dir / "text.msh", "hello\n");
  expect_failure(test::run_command(fissure() + " solve " + (dir / "text.msh").string() + " --E 3e10 --nu 0.2" + load + out),
                 4, "not a gmsh MSH file");
  expect_failure(test::run_command(solve + " --E 3e10 --nu 0.5" + load + out), 2, "--nu: 0.5 is outside [0, 0.5)");
  expect_failure(test::run_command(solve + " --E -1 --nu 0.2" + load + out), 2, "--E: -1 is outside (0, inf] Pa");
  expect_failure(test::run_command(solve + " --E 3e10 --nu 0.2 --load ball:5,5,5,0.01=0,0,-1" + out), 3,
                 "load patch 'ball:5,5,5,0.01' touches no boundary face");
  expect_failure(test::run_command(solve + " --E 3e10 --nu 0.2 --fix ball:-0.3,-0.2,0,0.01" + load + out), 3,
                 "rigid motions free");
  expect_failure(test::run_command(solve + " --E 3e10 --nu 0.2 --fix box:1,0,0,1,0,1" + load + out), 3, "box bound x0");
  expect_failure(test::run_command(solve + " --E 3e10 --nu 0.2 --load zmax=1,2" + out), 3, "expected 3 numbers fx,fy,fz (newtons), got 2");
  expect_failure(test::run_command(fissure() + " mesh tile:1,1,-1 -o " + (dir / "x.msh").string()), 3, "tile:1,1,-1");
  expect_failure(test::run_command(fissure() + " mesh " + (dir / "nothing.stl").string() + " -o " + (dir / "x.msh").string()),
                 4, "nothing.stl: no such file");
  expect_failure(test::run_command(solve + " --E 3e10 --nu 0.2" + load + " -o " + (dir / "no/such/dir.msh").string()), 4,
                 "does not exist");
  EXPECT_FALSE(fs::exists(dir / "never.msh"));
}

TEST_F(Cli, AnalyzeAndCompareTracings) {
  draw_tracings(dir);
  const std::string json = (dir / "bricks.json").string(), overlay = (dir / "bricks-overlay.png").string();
  const auto a = test::run_command(fissure() + " analyze " + (dir / "bricks.png").string() + " --json " + json +
                                   " --overlay " + overlay);
  ASSERT_EQ(a.exit_code, 0) << a.output;
  EXPECT_NE(a.output.find("dark cracks"), std::string::npos) << a.output;
  EXPECT_NE(a.output.find("directional (Eq. 3)"), std::string::npos) << a.output;
  EXPECT_TRUE(fs::exists(overlay));
  const auto b = test::run_command(fissure() + " analyze " + (dir / "cells.jpg").string() + " --json " +
                                   (dir / "cells.json").string());
  ASSERT_EQ(b.exit_code, 0) << b.output;
  EXPECT_NE(b.output.find("isotropic (Eq. 4)"), std::string::npos) << b.output;
  // compare: a pattern with itself is 0; bricks and honeycomb differ; image and JSON inputs mix.
  const auto same = test::run_command(fissure() + " compare " + json + " " + (dir / "bricks.png").string() + " --json");
  ASSERT_EQ(same.exit_code, 0) << same.output;
  EXPECT_NE(same.output.find("\"error\": 0,"), std::string::npos) << same.output;
  const auto differ = test::run_command(fissure() + " compare " + json + " " + (dir / "cells.json").string());
  ASSERT_EQ(differ.exit_code, 0) << differ.output;
  EXPECT_NE(differ.output.find("Eq. 5 error"), std::string::npos) << differ.output;
  EXPECT_EQ(differ.output.find("error 0 "), std::string::npos) << differ.output;
}

TEST_F(Cli, AnalyzeBadInput) {
  const std::string out = " --json " + (dir / "never.json").string();
  expect_failure(test::run_command(fissure() + " analyze " + (dir / "nope.png").string() + out), 4, "nope.png: no such file");
  write_file_atomically(dir / "zero.png", "");
  expect_failure(test::run_command(fissure() + " analyze " + (dir / "zero.png").string() + out), 4, "zero.png: file is empty");
  write_file_atomically(dir / "junk.png", std::string(300, 'j'));
  expect_failure(test::run_command(fissure() + " analyze " + (dir / "junk.png").string() + out), 4, "cannot decode");
  cv::imwrite((dir / "blank.png").string(), cv::Mat(50, 50, CV_8U, cv::Scalar(255)));
  expect_failure(test::run_command(fissure() + " analyze " + (dir / "blank.png").string() + out), 3, "blank");
  cv::imwrite((dir / "three.png").string(), cv::Mat(3, 3, CV_8U, cv::Scalar(0)));
  expect_failure(test::run_command(fissure() + " analyze " + (dir / "three.png").string() + out), 3, "smaller than");
  draw_tracings(dir);
  cv::imwrite((dir / "roi.png").string(), cv::Mat(10, 10, CV_8U, cv::Scalar(255)));
  expect_failure(test::run_command(fissure() + " analyze " + (dir / "bricks.png").string() + " --roi " +
                                   (dir / "roi.png").string() + out),
                 3, "roi.png: region-of-interest mask is 10 x 10");
  expect_failure(test::run_command(fissure() + " analyze " + (dir / "bricks.png").string() + " --max-megapixels 0.01" + out), 3,
                 "above the limit");
  expect_failure(test::run_command(fissure() + " compare " + (dir / "bricks.png").string() + " " + (dir / "zero.png").string()),
                 4, "zero.png");
  write_file_atomically(dir / "bad.json", "{\"format\": 1}");
  expect_failure(test::run_command(fissure() + " compare " + (dir / "bad.json").string() + " " + (dir / "bricks.png").string()),
                 4, "bad.json: not valid pattern statistics JSON");
  expect_failure(test::run_command(fissure() + " compare " + (dir / "bricks.png").string() + " " + (dir / "bricks.png").string() +
                                   " --weights 1,-1,0"),
                 3, "crack weight");
  EXPECT_FALSE(fs::exists(dir / "never.json"));
}

// Progress on stderr when it is a terminal (a pseudo-terminal made by script(1)), rewritten in
// place with "\r"; nothing when stderr is a pipe or with --quiet. Used to print nothing at all.
TEST_F(Cli, ProgressOnATerminalOnly) {
  if (test::run_command("script --version").exit_code != 0) GTEST_SKIP() << "script(1) from util-linux is not installed";
  const std::string mesh_command = fissure() + " mesh tile:0.6,0.4,0.1 --tets 3000 -o " + (dir / "progress.msh").string();
  const auto tty = test::run_command("script -qec '" + mesh_command + "' /dev/null");
  ASSERT_EQ(tty.exit_code, 0) << tty.output;
  EXPECT_NE(tty.output.find("\rtetrahedralize 0 %"), std::string::npos) << tty.output;
  EXPECT_NE(tty.output.find("\rwriting "), std::string::npos) << tty.output;
  // The summary starts at column 0: the progress line was blanked and the cursor sent back.
  const std::size_t summary = tty.output.find("tile:0.6,0.4,0.1: ");
  ASSERT_NE(summary, std::string::npos) << tty.output;
  EXPECT_EQ(tty.output.substr(summary - 2, 2), " \r") << tty.output;
  const auto quiet = test::run_command("script -qec '" + mesh_command + " --quiet' /dev/null");
  ASSERT_EQ(quiet.exit_code, 0) << quiet.output;
  EXPECT_EQ(quiet.output.find('%'), std::string::npos) << quiet.output;
  const auto pipe = test::run_command(mesh_command);
  ASSERT_EQ(pipe.exit_code, 0) << pipe.output;
  EXPECT_EQ(pipe.output.find('%'), std::string::npos) << pipe.output;
  EXPECT_EQ(pipe.output.find('\r'), std::string::npos) << pipe.output;
}

// Runs `args` (argv[0] first) in `cwd` with stdout and stderr to `log`, SIGINT at its default
// action (a shell's background job would inherit it ignored).
pid_t spawn(const std::vector<std::string>& args, const fs::path& cwd, const fs::path& log) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0 || ::chdir(cwd.c_str()) != 0) ::_exit(127);
    ::dup2(fd, STDOUT_FILENO);
    ::dup2(fd, STDERR_FILENO);
    ::signal(SIGINT, SIG_DFL);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  return pid;
}

// True once `pid` catches SIGINT (its handler is installed: /proc/PID/status, SigCgt bit 1).
bool catches_sigint(pid_t pid) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  for (std::string line; std::getline(status, line);) {
    if (line.rfind("SigCgt:", 0) == 0) return (std::stoull(line.substr(7), nullptr, 16) >> (SIGINT - 1)) & 1u;
  }
  return false;
}

// The wait status of `pid` once it ends, or nothing after `timeout` (the child is then killed).
std::optional<int> wait_at_most(pid_t pid, std::chrono::milliseconds timeout) {
  const auto end = std::chrono::steady_clock::now() + timeout;
  int status = 0;
  while (std::chrono::steady_clock::now() < end) {
    if (::waitpid(pid, &status, WNOHANG) == pid) return status;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ::kill(pid, SIGKILL);
  ::waitpid(pid, &status, 0);
  return std::nullopt;
}

// Ctrl-C during a long mesh (2M tets: minutes) ends it within seconds with "fissure: cancelled",
// exit 6, and no output or temporary file. Used to kill the process by the signal.
TEST_F(Cli, InterruptCancelsWithoutOutput) {
  const fs::path work = dir / "interrupt";
  fs::create_directories(work);
  const pid_t pid = spawn({fissure(), "mesh", "tile:1,1,0.05", "--tets", "2000000", "-o", "out.msh"}, work, work / "log.txt");
  ASSERT_GT(pid, 0);
  // Start-up (loading CGAL, gmsh, OpenCV) takes over a second on a loaded machine: signal 1 s
  // after the handler is in place, when the mesher is surely running.
  for (int i = 0; i < 1500 && !catches_sigint(pid); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_TRUE(catches_sigint(pid)) << "fissure installed no SIGINT handler within 30 s";
  std::this_thread::sleep_for(std::chrono::seconds(1));
  ::kill(pid, SIGINT);
  const auto signalled = std::chrono::steady_clock::now();
  // 2 s of grace for the core to stop by itself, then the CLI ends the run; 8 s of slack for a
  // loaded CI machine and the sanitizer build.
  const std::optional<int> status = wait_at_most(pid, std::chrono::seconds(10));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - signalled).count();
  const std::string log = read_file(work / "log.txt");
  ASSERT_TRUE(status.has_value()) << "still running 10 s after SIGINT: " << log;
  ASSERT_TRUE(WIFEXITED(*status)) << "ended by signal " << (WIFSIGNALED(*status) ? WTERMSIG(*status) : 0) << ": " << log;
  EXPECT_EQ(WEXITSTATUS(*status), 6) << log;
  EXPECT_EQ(log, "fissure: cancelled\n");
  EXPECT_LT(seconds, 10.0);
  for (const auto& entry : fs::directory_iterator(work)) {
    EXPECT_EQ(entry.path().filename(), "log.txt") << "left behind: " << entry.path();
  }
}

// A request far beyond the machine is refused at once, with the estimate and the way out. Used
// to start a 50M-tet mesh (about 34 GB) on a 24 GB machine.
TEST_F(Cli, FarTooLargeRequestsAreRefusedUpFront) {
  const double physical = static_cast<double>(::sysconf(_SC_PHYS_PAGES)) * static_cast<double>(::sysconf(_SC_PAGE_SIZE));
  if (physical > 34e9) GTEST_SKIP() << "this machine has enough memory for 5e7 tets";
  const auto start = std::chrono::steady_clock::now();
  const auto r = test::run_command(fissure() + " mesh tile:1,1,0.05 --tets 5e7 -o " + (dir / "huge.msh").string());
  expect_failure(r, 3, "tetrahedralize: 5e+07 tets needs about ");
  EXPECT_NE(r.output.find("; --allow-large tries anyway"), std::string::npos) << r.output;
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 30.0);
  // --allow-large passes the check: the next problem (a missing input) is what stops it.
  expect_failure(test::run_command(fissure() + " mesh " + (dir / "absent.stl").string() + " --tets 5e7 --allow-large -o " +
                                   (dir / "huge.msh").string()),
                 4, "absent.stl: no such file");
  EXPECT_FALSE(fs::exists(dir / "huge.msh"));
}

// The number after "max |u| " in a solve's summary.
double max_displacement(const std::string& output) {
  const std::size_t at = output.find("max |u| ");
  if (at == std::string::npos) return -1.0;
  return std::strtod(output.c_str() + at + 8, nullptr);
}

// max |u| is proportional to 1/E under a given load (the stress is not: it depends on the load
// alone). It used to square the components: "inf m" at E = 1e-300 (|u| ~ 7e305 m), "0 m" at
// E = 3e170 (|u| ~ 2e-165 m, whose square underflows). A tiny load would show the same, but the
// core's max principal stress is not finite below ~1e-100 Pa, so the solve refuses to write.
// Printed with 4 significant digits, so the ratios hold to 5e-4 relative (rounding) plus the
// solver's round-off (residual ~1e-13).
TEST_F(Cli, LargestDisplacementNeitherOverflowsNorUnderflows) {
  const std::string solve = fissure() + " solve " + mesh() + " --nu 0.2" + corners() + " --load ball:0,0,0.1,0.05=0,0,-1e4 -o " +
                            (dir / "u.msh").string();
  const auto reference = test::run_command(solve + " --E 3e10");
  ASSERT_EQ(reference.exit_code, 0) << reference.output;
  const double u = max_displacement(reference.output);
  ASSERT_GT(u, 0.0) << reference.output;
  for (const double youngs_modulus : {1e-300, 3e170}) {
    std::ostringstream flag;
    flag << " --E " << youngs_modulus;
    const auto r = test::run_command(solve + flag.str());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NEAR(max_displacement(r.output) * youngs_modulus / 3e10 / u, 1.0, 1e-3) << r.output;
  }
}

// A cache directory that cannot be written is said once, and the analysis goes on. It used to
// be skipped silently.
TEST_F(Cli, UnwritableCacheDirectoryIsSaidOnce) {
  write_file_atomically(dir / "plain-file", "not a directory\n");
  const std::string cache = (dir / "plain-file" / "cache").string();
  const auto r = test::run_command(fissure() + " modes " + mesh() + " --E 3e10 --nu 0.2 --rho 2400 --count 3 --cache-dir " + cache);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("\"frequencies_hz\""), std::string::npos) << r.output;
  EXPECT_EQ(occurrences(r.output, "fissure: warning: modal basis not cached (cannot create " + cache + ": "), 1u) << r.output;
  EXPECT_NE(r.output.find("; it will be computed again next time\n"), std::string::npos) << r.output;
}

// Unmounts on scope exit.
struct Mount {
  fs::path where;
  ~Mount() {
    if (!where.empty()) ::umount(where.c_str());
  }
};

// On a full filesystem mesh fails naming the file and the lack of space, and the previous file
// stays intact with no temporary left. It used to leave a truncated .msh and exit 0.
TEST_F(Cli, FullDiskKeepsThePreviousMesh) {
  const fs::path small = dir / "small-disk";
  fs::create_directories(small);
  if (::mount("tmpfs", small.c_str(), "tmpfs", 0, "size=256k") != 0) GTEST_SKIP() << "cannot mount a tmpfs here (needs root)";
  Mount unmount{small};
  const std::string previous = read_file(mesh());  // ~130 kB: fits, while a 24K-tet mesh (~2 MB) does not
  const fs::path existing = small / "existing.msh";
  write_file_atomically(existing, previous);
  const auto r = test::run_command(fissure() + " mesh tile:1,1,0.05 --tets 24000 -o " + existing.string());
  EXPECT_NE(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find(existing.string()), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("space"), std::string::npos) << r.output;
  EXPECT_TRUE(read_file(existing) == previous) << "the previous mesh was changed";
  for (const auto& entry : fs::directory_iterator(small)) {
    EXPECT_EQ(entry.path().filename(), "existing.msh") << "left behind: " << entry.path();
  }
}

// analyze --json: a device is written, never replaced (/dev/full fails for lack of space and
// stays a character device); "-" is stdout, with the summary moved to stderr; a symlink is
// written through and kept.
TEST_F(Cli, AnalyzeWritesToDevicesStdoutAndThroughLinks) {
  draw_tracings(dir);
  const std::string analyze = fissure() + " analyze " + (dir / "bricks.png").string();
  expect_failure(test::run_command(analyze + " --json /dev/full"), 4, "/dev/full");
  struct stat st {};
  ASSERT_EQ(::stat("/dev/full", &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode));
  const auto out = test::run_command("{ " + analyze + " --json - 2>/dev/null; }");
  ASSERT_EQ(out.exit_code, 0) << out.output;
  ASSERT_FALSE(out.output.empty());
  EXPECT_EQ(out.output.front(), '{') << out.output;
  EXPECT_EQ(out.output.substr(out.output.size() - 2), "}\n") << out.output;
  const fs::path link = dir / "stats-link.json", target = dir / "stats-target.json";
  fs::remove(link);
  fs::remove(target);
  fs::create_symlink(target.filename(), link);
  const auto r = test::run_command(analyze + " -q --json " + link.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(read_file(target).front(), '{');
}

}  // namespace
}  // namespace fissure
