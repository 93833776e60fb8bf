// The `fissure` executable end to end: exit codes, one-line messages, outputs gmsh opens, and
// byte-identical results at 1 and 2 threads.

#include "fissure/base/atomic_file.hpp"
#include "fissure/io/msh.hpp"

#include "test_support.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

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

// One line on stderr for a failure: the message, no stack of output.
void expect_failure(const test::CommandResult& r, int code, const std::string& words) {
  EXPECT_EQ(r.exit_code, code) << r.output;
  EXPECT_NE(r.output.find(words), std::string::npos) << r.output;
  EXPECT_LE(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
}

TEST_F(Cli, HelpOnEverySubcommand) {
  for (const char* sub : {"", " mesh", " solve", " modes", " version"}) {
    const auto r = test::run_command(fissure() + sub + " --help");
    EXPECT_EQ(r.exit_code, 0) << sub << r.output;
    EXPECT_NE(r.output.find("Usage"), std::string::npos) << sub;
  }
  EXPECT_EQ(test::run_command(fissure() + " solve").exit_code, 2);  // missing required arguments
  EXPECT_EQ(test::run_command(fissure() + " frobnicate").exit_code, 2);
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
  expect_failure(test::run_command(solve + " --E 3e10 --nu 0.5" + load + out), 3, "--nu 0.5 is outside [0, 0.5)");
  expect_failure(test::run_command(solve + " --E -1 --nu 0.2" + load + out), 3, "--E -1 is outside (0, inf] Pa");
  expect_failure(test::run_command(solve + " --E 3e10 --nu 0.2 --load ball:5,5,5,0.01=0,0,-1" + out), 3,
                 "load patch 'ball:5,5,5,0.01' touches no boundary face");
  expect_failure(test::run_command(solve + " --E 3e10 --nu 0.2 --fix ball:-0.3,-0.2,0,0.01" + load + out), 3,
                 "rigid motions free");
  expect_failure(test::run_command(solve + " --E 3e10 --nu 0.2 --fix box:1,0,0,1,0,1" + load + out), 3, "box bound x0");
  expect_failure(test::run_command(solve + " --E 3e10 --nu 0.2 --load zmax=1,2" + out), 3, "expected 3 force components");
  expect_failure(test::run_command(fissure() + " mesh tile:1,1,-1 -o " + (dir / "x.msh").string()), 3, "tile:1,1,-1");
  expect_failure(test::run_command(fissure() + " mesh " + (dir / "nothing.stl").string() + " -o " + (dir / "x.msh").string()),
                 4, "nothing.stl: no such file");
  expect_failure(test::run_command(solve + " --E 3e10 --nu 0.2" + load + " -o " + (dir / "no/such/dir.msh").string()), 4,
                 "does not exist");
  EXPECT_FALSE(fs::exists(dir / "never.msh"));
}

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
  EXPECT_EQ(differ.output.find("error 0.0000"), std::string::npos) << differ.output;
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

}  // namespace
}  // namespace fissure
