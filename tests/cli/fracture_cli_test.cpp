// `fissure fracture` end to end, as a user runs it: outputs the other commands and gmsh read,
// the same bytes at 1 and 2 threads, --fragments, and one clear line for every bad input.

#include "fissure/base/atomic_file.hpp"

#include "test_shapes.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <regex>

namespace fissure {
namespace {
namespace fs = std::filesystem;

std::string fissure() { return test::fissure_executable().string(); }

class FractureCli : public ::testing::Test {
protected:
  static void SetUpTestSuite() {
    dir = test::fresh_temp_dir("fracture-cli");
    const auto r = test::run_command(fissure() + " mesh tile:0.4,0.4,0.03 --tets 3000 -q -o " + (dir / "tile.msh").string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  static fs::path dir;
  static std::string mesh() { return (dir / "tile.msh").string(); }
  static std::string path(const std::string& name) { return (dir / name).string(); }
};
fs::path FractureCli::dir;

void expect_failure(const test::CommandResult& r, int code, const std::string& words) {
  EXPECT_EQ(r.exit_code, code) << r.output;
  EXPECT_NE(r.output.find(words), std::string::npos) << r.output;
  EXPECT_EQ(r.output.rfind("fissure: ", 0), 0u) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
}

TEST_F(FractureCli, WritesStatisticsADrawingAndViewsTheOtherToolsRead) {
  const auto r = test::run_command(fissure() + " fracture " + mesh() + " --stats " + path("s.json") + " --pattern " +
                                   path("p.png") + " --msh " + path("f.msh"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("fragments"), std::string::npos) << r.output;
  const auto stats = nlohmann::json::parse(read_file(path("s.json")));
  const auto& f = stats.at("fracture");
  EXPECT_GE(f.at("fragments").get<int>(), 2) << "the default tile should break";
  EXPECT_GE(f.at("cracks").get<int>(), 1);
  for (const char* key : {"preparation", "simulation", "fragment_meshing", "export"}) {
    EXPECT_TRUE(f.at("seconds").contains(key)) << key;
  }
  // `fissure compare` reads the statistics (the schema of analyze --json): a pattern is at
  // distance 0 from itself.
  const auto c = test::run_command(fissure() + " compare " + path("s.json") + " " + path("s.json"));
  EXPECT_EQ(c.exit_code, 0) << c.output;
  EXPECT_EQ(c.output.rfind("Eq. 5 error 0 = ", 0), 0u) << c.output;
  // `fissure analyze` reads the drawing and finds the pattern's fragments (the geometric count
  // and the drawing's agree: visible_pattern_test measures by how much).
  const auto a = test::run_command(fissure() + " analyze " + path("p.png") + " --json " + path("a.json") + " -q");
  ASSERT_EQ(a.exit_code, 0) << a.output;
  const auto analysed = nlohmann::json::parse(read_file(path("a.json")));
  // The drawing's analysis finds the geometry's fragments, within the 10 % that
  // visible_pattern_test's SimulatedPatternsDrawnAndAnalysedAgree states and explains.
  const int geometric = stats.at("fragments").at("count").get<int>();
  EXPECT_NEAR(analysed.at("fragments").at("count").get<int>(), geometric, 0.10 * geometric);
  EXPECT_GE(analysed.at("fragments").at("count").get<int>(), 2);
  // gmsh opens the tet mesh with its three views.
  write_file_atomically(path("views.geo"), "Merge \"" + path("f.msh") + "\";\nPrintf(\"views=%g\", PostProcessing.NbViews);\n");
  const auto g = test::run_command("gmsh " + path("views.geo") + " -0 -o " + path("x.geo_unrolled"));
  EXPECT_NE(g.output.find("views=3"), std::string::npos) << g.output;
}

// The "seconds" differ run to run; everything else must be the same bytes.
std::string without_seconds(std::string json) {
  return std::regex_replace(json, std::regex("\"seconds\": \\{[^}]*\\}"), "\"seconds\": {}");
}

TEST_F(FractureCli, SameBytesAtOneAndTwoThreadsAndAnotherSeedDiffers) {
  std::string stats[3], msh[2];
  for (int run = 0; run < 3; ++run) {
    const int threads = run == 1 ? 2 : 1;
    const std::string seed = run == 2 ? "2" : "1";
    const auto r = test::run_command(fissure() + " fracture " + mesh() + " -q --seed " + seed + " --threads " +
                                     std::to_string(threads) + " --stats " + path("t.json") + " --msh " + path("t.msh"));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    stats[run] = without_seconds(read_file(path("t.json")));
    if (run < 2) msh[run] = read_file(path("t.msh"));
  }
  EXPECT_EQ(stats[0], stats[1]);
  EXPECT_EQ(msh[0], msh[1]);
  EXPECT_NE(stats[0], stats[2]);
}

TEST_F(FractureCli, FragmentsReachesAboutTheCountAsked) {
  const auto r = test::run_command(fissure() + " fracture " + mesh() + " -q --fragments 8 --stats " + path("n.json"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto f = nlohmann::json::parse(read_file(path("n.json"))).at("fracture");
  EXPECT_NEAR(f.at("fragments").get<int>(), 8, 8 * 0.2) << f.dump();
  EXPECT_EQ(f.at("fragments_requested"), 8);
}

// Issue 10: "with no flags at all, tiles from 0.3 m to 1 m and curved bodies (a bowl, a basin)
// break into several fragments" — as a user runs it, the curved bodies as OBJ files from a
// modeller. Only --tets differs from the defaults (8K instead of 24K, for the suite's time;
// curved_bodies_test checks the same bodies over seeds and where the supports and the load land).
// "Several" read as ≥ 3; the fewest measured over seeds 1–5 at 8K tets are 20 (bowl) and 28
// (0.3 m tile), so a failure means a default stopped breaking the body, not a seed's luck.
TEST_F(FractureCli, TilesABowlAndABasinBreakWithNoFlags) {
  test::write_obj(test::bowl(), path("bowl.obj"));
  test::write_obj(test::basin(), path("basin.obj"));
  for (const std::string& input : {std::string("tile:0.3,0.3,0.02"), std::string("tile:0.5,0.5,0.02"),
                                  std::string("tile:1,1,0.03"), path("bowl.obj"), path("basin.obj")}) {
    SCOPED_TRACE(input);
    const auto r = test::run_command(fissure() + " fracture " + input + " --tets 8000 -q --stats " + path("curved.json"));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto stats = nlohmann::json::parse(read_file(path("curved.json")));
    EXPECT_GE(stats.at("fracture").at("fragments").get<int>(), 3);
    // The visible face (up within 45°: the tiles' tops, the bowl's inside floor and rim, the
    // basin's floor and rim) exists and shows the breakage.
    ASSERT_TRUE(stats.contains("fragments")) << stats.dump();
    EXPECT_GE(stats.at("fragments").at("count").get<int>(), 3);
  }
}

TEST_F(FractureCli, BadInputIsOneLineAndWritesNothing) {
  const std::string run = fissure() + " fracture " + mesh();
  const std::string out = " --stats " + path("never.json");
  expect_failure(test::run_command(run + " --relax-radius -1" + out), 3, "--relax-radius -1 is outside (0, 100] m");
  expect_failure(test::run_command(run + " --material marble" + out), 3, "material \"marble\"");
  write_file_atomically(path("broken.json"), "{\"schema\": \"fissure-material\", \"version\": 1, \"name\": \"x\", \"parameters\": {}}");
  expect_failure(test::run_command(run + " --material " + path("broken.json") + out), 4, path("broken.json"));
  expect_failure(test::run_command(run + " --load ball:5,5,5,0.01=0,0,-100" + out), 3, "ball:5,5,5,0.01");
  expect_failure(test::run_command(run + " --up w" + out), 3, "--up w");
  expect_failure(test::run_command(run + " --stats /nonexistent-dir/s.json"), 4, "/nonexistent-dir");
  // An open surface: one triangle.
  write_file_atomically(path("open.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  expect_failure(test::run_command(fissure() + " fracture " + path("open.obj") + out), 3, path("open.obj"));
  EXPECT_FALSE(fs::exists(path("never.json")));
}

}  // namespace
}  // namespace fissure
