// fissure scene info as a user runs it (issue 13): a GLB written by Fissure's own exporter with a
// closed and an open box lists both bodies, their sizes and materials, fractures only the closed
// one and says why not the other; wrong files get one line.

#include "fissure/base/atomic_file.hpp"
#include "fissure/exemplar/crack_image.hpp"
#include "fissure/io/scene_export.hpp"
#include "fissure/mesh/tetrahedralize.hpp"

#include "test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <map>
#include <string>

#include <sys/stat.h>
#include <unistd.h>

namespace fissure {
namespace {

namespace fs = std::filesystem;

std::string fissure() { return test::fissure_executable().string(); }

// A W × H × D box, outward triangles; `open` drops its top (+z) face.
ExportPart box(const std::string& name, const Eigen::Vector3d& size, const Eigen::Vector3d& at, bool open) {
  ExportPart p;
  p.name = name;
  p.translation = at;
  p.vertices.resize(8, 3);
  for (int i = 0; i < 8; ++i) p.vertices.row(i) << (i & 1) * size.x(), ((i >> 1) & 1) * size.y(), ((i >> 2) & 1) * size.z();
  const int faces[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                            {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  const int count = open ? 10 : 12;
  p.triangles.resize(count, 3);
  int row = 0;
  for (int f = 0; f < 12; ++f) {
    if (open && (f == 2 || f == 3)) continue;  // the top, z = D
    p.triangles.row(row++) << faces[f][0], faces[f][1], faces[f][2];
  }
  p.uvs = Eigen::MatrixX2d::Zero(8, 2);
  p.triangle_material.assign(static_cast<std::size_t>(count), 0);
  return p;
}

TEST(SceneCli, InfoListsBodiesAndWhichCanBeFractured) {
  const fs::path dir = test::fresh_temp_dir("scene-cli-info");
  ExportScene scene;
  scene.materials = {{"concrete", Eigen::Vector3d(0.5, 0.5, 0.5), {}}};
  scene.parts = {box("slab", {2.0, 1.0, 0.1}, {0, 0, 0}, false), box("crate", {1, 1, 1}, {5, 0, 0}, true)};
  write_scene(dir / "yard.glb", scene);
  const auto r = test::run_command(fissure() + " scene info -q " + (dir / "yard.glb").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("2 bodies (1 fracturable)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("not fracturable: open"), std::string::npos) << r.output;

  const auto j = test::run_command(fissure() + " scene info -q --json " + (dir / "yard.glb").string());
  ASSERT_EQ(j.exit_code, 0) << j.output;
  const nlohmann::json info = nlohmann::json::parse(j.output);
  EXPECT_EQ(info["format"], "glb");
  EXPECT_EQ(info["up"], "+y");
  ASSERT_EQ(info["bodies"].size(), 2u);
  const nlohmann::json* slab = nullptr;
  const nlohmann::json* crate = nullptr;
  for (const auto& b : info["bodies"]) {
    const std::string path = b["path"];
    if (path.size() >= 5 && path.compare(path.size() - 5, 5, "/slab") == 0) slab = &b;
    if (path.size() >= 6 && path.compare(path.size() - 6, 6, "/crate") == 0) crate = &b;
  }
  ASSERT_TRUE(slab && crate) << info.dump(2);
  EXPECT_TRUE((*slab)["fracturable"].get<bool>());
  EXPECT_EQ((*slab)["material"], "concrete");
  // float32 in the file: 1e-6 relative.
  EXPECT_NEAR((*slab)["volume"].get<double>(), 0.2, 1e-6);
  EXPECT_NEAR((*slab)["size"][0].get<double>(), 2.0, 1e-6);
  EXPECT_NEAR((*slab)["size"][2].get<double>(), 0.1, 1e-6);
  EXPECT_FALSE((*crate)["fracturable"].get<bool>());
  EXPECT_NE((*crate)["reason"].get<std::string>().find("open"), std::string::npos) << crate->dump();
}

// The street demo as a batch user runs it: fracture every slab, a report per body, plain
// progress lines in a log; the same run in two --bodies slices merged is the same file.
TEST(SceneCli, FractureTheStreetInSlicesAndMergeThem) {
  const fs::path dir = test::fresh_temp_dir("scene-cli-fracture");
  const std::string street = (dir / "street.glb").string();
  auto r = test::run_command(fissure() + " scene demo street --slabs 2 --rows 1 -o " + street);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // ceramic-tile on the slabs: tens of fragments each at 800 tets, in a second.
  const std::string run = fissure() + " scene fracture " + street + " --assign concrete=ceramic-tile --tets 800 --seed 5";
  r = test::run_command(run + " --report " + (dir / "report.json").string() + " -o " + (dir / "whole.glb").string() + " 2>&1");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("fissure scene fracture: 2/2 /street/sidewalk/slab_"), std::string::npos) << "plain lines off a terminal: " << r.output;
  EXPECT_NE(r.output.find("2 bodies fractured into"), std::string::npos) << r.output;
  const nlohmann::json report = nlohmann::json::parse(read_file(dir / "report.json"));
  int fractured = 0;
  for (const auto& b : report["bodies"]) {
    if (b["status"] != "fractured") continue;
    ++fractured;
    EXPECT_GT(b["fragments"].get<int>(), 1) << b.dump();
    EXPECT_EQ(b["material"], "ceramic-tile");
  }
  EXPECT_EQ(fractured, 2) << report.dump(2);

  for (const char* k : {"1", "2"}) {
    r = test::run_command(run + " -q --bodies " + k + "/2 -o " + (dir / (std::string("slice") + k + ".glb")).string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  r = test::run_command(fissure() + " scene merge " + (dir / "slice2.glb").string() + " " + (dir / "slice1.glb").string() +
                        " -o " + (dir / "merged.glb").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(read_file(dir / "merged.glb") == read_file(dir / "whole.glb")) << "merged slices differ from the unsliced run";

  // A slice missing, a file that is not a slice: one line, nothing written.
  r = test::run_command(fissure() + " scene merge " + (dir / "slice1.glb").string() + " -o " + (dir / "m.glb").string());
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("slice 2/2 is missing"), std::string::npos) << r.output;
  r = test::run_command(fissure() + " scene merge " + street + " " + (dir / "slice1.glb").string() + " -o " + (dir / "m.glb").string());
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find(street + ": not a slice"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "m.glb"));
}

// The caches: a cold run makes and stores every body's tet mesh and static stress, a warm run
// reads them all (no mesher, no FEM), and both write the bytes a run without the cache writes.
TEST(SceneCli, AWarmCacheMeshesAndSolvesNothingAndChangesNoByte) {
  const fs::path dir = test::fresh_temp_dir("scene-cli-cache");
  const std::string street = (dir / "street.glb").string();
  ASSERT_EQ(test::run_command(fissure() + " scene demo street --slabs 2 --rows 1 -o " + street).exit_code, 0);
  const std::string run = fissure() + " scene fracture " + street + " --assign concrete=ceramic-tile --tets 800 -q";
  const std::string cache = " --cache-dir " + (dir / "cache").string();
  std::map<std::string, int> seen;  // "run mesh made", "run stress cached", … → bodies
  for (const char* name : {"cold", "warm"}) {
    const auto r = test::run_command(run + cache + " --report " + (dir / name).string() + ".json -o " + (dir / name).string() + ".glb");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const nlohmann::json report = nlohmann::json::parse(read_file(dir / (std::string(name) + ".json")));
    for (const auto& b : report["bodies"]) {
      if (b["status"] != "fractured") continue;
      ++seen[std::string(name) + " mesh " + b["mesh"].get<std::string>()];
      ++seen[std::string(name) + " stress " + b["stress"].get<std::string>()];
    }
  }
  const std::map<std::string, int> expected{
      {"cold mesh made", 2}, {"cold stress solved", 2}, {"warm mesh cached", 2}, {"warm stress cached", 2}};
  EXPECT_EQ(seen, expected) << "a body meshed or solved when it should have been cached, or the reverse";
  const auto r = test::run_command(run + " --no-cache -o " + (dir / "uncached.glb").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(read_file(dir / "cold.glb") == read_file(dir / "warm.glb"));
  EXPECT_TRUE(read_file(dir / "cold.glb") == read_file(dir / "uncached.glb"));

  // A cache that cannot be written (its directory is a file): the run still writes the same
  // bytes and says so once for each cache it could not fill, the tet meshes and the stresses.
  write_file_atomically(dir / "file", "not a directory");
  const auto blocked = test::run_command(run + " --cache-dir " + (dir / "file").string() + " -o " + (dir / "blocked.glb").string());
  ASSERT_EQ(blocked.exit_code, 0) << blocked.output;
  for (const char* kind : {"warning: tet mesh not cached", "warning: stress field not cached"}) {
    std::size_t seen_at = blocked.output.find(kind), count = 0;
    for (; seen_at != std::string::npos; seen_at = blocked.output.find(kind, seen_at + 1)) ++count;
    EXPECT_EQ(count, 1u) << kind << ": " << blocked.output;
  }
  EXPECT_TRUE(read_file(dir / "cold.glb") == read_file(dir / "blocked.glb"));
}

// Crack masks for decals: one PNG per fractured body in its UV space, named by its path, listed
// in the report and kept by a saved project; a folder that is not there is refused before any work.
TEST(SceneCli, CrackMasksAreDrawnPerFracturedBody) {
  const fs::path dir = test::fresh_temp_dir("scene-cli-masks");
  const std::string street = (dir / "street.glb").string();
  ASSERT_EQ(test::run_command(fissure() + " scene demo street --slabs 2 --rows 1 -o " + street).exit_code, 0);
  const std::string run = fissure() + " scene fracture " + street + " --assign /street/sidewalk=concrete --age 50 --tets 1500 -q";
  const auto missing = test::run_command(run + " --crack-masks " + (dir / "none").string() + " -o " + (dir / "m.glb").string());
  EXPECT_EQ(missing.exit_code, 4) << missing.output;
  EXPECT_NE(missing.output.find("--crack-masks " + (dir / "none").string() + ": not a directory"), std::string::npos) << missing.output;
  EXPECT_FALSE(fs::exists(dir / "m.glb"));

  fs::create_directory(dir / "masks");
  const auto r = test::run_command(run + " --crack-masks " + (dir / "masks").string() + " --crack-mask-size 256 --report " +
                                   (dir / "r.json").string() + " --save-project " + (dir / "p.json").string() + " -o " +
                                   (dir / "m.glb").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json report = nlohmann::json::parse(read_file(dir / "r.json"));
  int masks = 0;
  for (const auto& b : report["bodies"]) {
    if (b["status"] != "fractured") {
      EXPECT_FALSE(b.contains("crack_mask")) << b.dump();
      continue;
    }
    const fs::path file = b.at("crack_mask").get<std::string>();
    std::string expected = b["path"].get<std::string>().substr(1);  // "street/sidewalk/slab_01"
    std::replace(expected.begin(), expected.end(), '/', '_');
    EXPECT_EQ(file.filename().string(), expected + ".png");
    const GreyImage image = load_grey_image(file, 1 << 20);
    EXPECT_EQ(image.width, 256);
    // A broken slab's mask holds its cracks: some lit pixels (a short crack cut off one corner
    // under the sanitizer build's round-off: 23), most dark. Where they lie is the unit test's.
    const auto lit = std::count_if(image.pixels.begin(), image.pixels.end(), [](std::uint8_t p) { return p > 128; });
    if (b["fragments"].get<int>() > 1) {
      EXPECT_GT(lit, 0) << file;
    }
    EXPECT_LT(lit, static_cast<long>(image.pixels.size() / 4)) << file;
    ++masks;
  }
  EXPECT_EQ(masks, 2);
  const nlohmann::json project = nlohmann::json::parse(read_file(dir / "p.json"));
  EXPECT_EQ(project["export"]["crack_masks"], "masks");
  EXPECT_EQ(project["export"]["crack_mask_size"], 256);
}

// A --tets no body could be meshed with on this machine is refused before any work (it used to
// skip every body in turn, for memory, and exit 0); --allow-large is named as the way past it.
TEST(SceneCli, ATetCountBeyondMemoryIsRefusedUpFront) {
  const double physical = static_cast<double>(::sysconf(_SC_PHYS_PAGES)) * static_cast<double>(::sysconf(_SC_PAGE_SIZE));
  if (tetrahedralize_memory_estimate(50000000) <= physical) GTEST_SKIP() << "this machine could mesh 5e7 tets: nothing to refuse";
  const fs::path dir = test::fresh_temp_dir("scene-cli-large");
  const std::string street = (dir / "street.glb").string();
  ASSERT_EQ(test::run_command(fissure() + " scene demo street --slabs 1 --rows 1 -o " + street).exit_code, 0);
  const auto r = test::run_command(fissure() + " scene fracture " + street + " --assign concrete=concrete --tets 5e7 --save-project " +
                                   (dir / "p.json").string() + " -o " + (dir / "m.glb").string());
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("--tets 50000000 per body needs about"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("--allow-large tries anyway"), std::string::npos) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_FALSE(fs::exists(dir / "m.glb"));
  EXPECT_FALSE(fs::exists(dir / "p.json"));
}

// A project saved by one run repeats it: the same bytes from `scene fracture PROJECT`, its paths
// relative to the project's folder (so the folder can move whole); a corrupt project or one whose
// scene has moved gets one line and writes nothing.
TEST(SceneCli, AProjectRepeatsItsRunAndBadProjectsGetOneLine) {
  const fs::path dir = test::fresh_temp_dir("scene-cli-project");
  const std::string street = (dir / "street.glb").string();
  ASSERT_EQ(test::run_command(fissure() + " scene demo street --slabs 2 --rows 1 -o " + street).exit_code, 0);
  auto r = test::run_command(fissure() + " scene fracture " + street + " --assign concrete=ceramic-tile --tets 800 --seed 9 -q --strict" +
                             " --save-project " + (dir / "p.json").string() + " -o " + (dir / "first.glb").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json project = nlohmann::json::parse(read_file(dir / "p.json"));
  EXPECT_EQ(project["scene"], "street.glb");
  EXPECT_EQ(project["export"]["output"], "first.glb");
  EXPECT_EQ(project["seed"], 9);
  EXPECT_EQ(project["strict"], true);

  fs::create_directories(dir / "moved");
  for (const char* f : {"street.glb", "p.json"}) fs::rename(dir / f, dir / "moved" / f);
  r = test::run_command(fissure() + " scene fracture -q " + (dir / "moved" / "p.json").string() + " -o " + (dir / "again.glb").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(read_file(dir / "again.glb") == read_file(dir / "first.glb")) << "the project did not repeat its run";

  // The scene left without its project: named, with what to do.
  fs::rename(dir / "moved" / "street.glb", dir / "street.glb");
  r = test::run_command(fissure() + " scene fracture -q " + (dir / "moved" / "p.json").string() + " -o " + (dir / "x.glb").string());
  EXPECT_EQ(r.exit_code, 4) << "a file that is not there, as for scene info: " << r.output;
  EXPECT_NE(r.output.find("its scene street.glb is not at"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("was it moved?"), std::string::npos) << r.output;
  std::string text = read_file(dir / "moved" / "p.json");
  write_file_atomically(dir / "moved" / "p.json", text.substr(0, text.size() / 2));
  r = test::run_command(fissure() + " scene fracture -q " + (dir / "moved" / "p.json").string() + " -o " + (dir / "x.glb").string());
  EXPECT_EQ(r.exit_code, 4) << r.output;
  EXPECT_NE(r.output.find("p.json: not a valid Fissure project: syntax error"), std::string::npos) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_FALSE(fs::exists(dir / "x.glb"));
}

// Wrong assignments: a material name no library has, or a material file that is not there, is one
// line before any work (exit 3 or 4, nothing written); an assignment to a material the scene
// lacks is a warning, an error with --strict.
TEST(SceneCli, BadAssignmentsAreNamed) {
  const fs::path dir = test::fresh_temp_dir("scene-cli-assign");
  const std::string street = (dir / "street.glb").string();
  ASSERT_EQ(test::run_command(fissure() + " scene demo street --slabs 1 --rows 1 -o " + street).exit_code, 0);
  // A misspelt material is one line and nothing written, however many bodies use it.
  auto r = test::run_command(fissure() + " scene fracture " + street + " --assign concrete=no-such-material -o " +
                             (dir / "out.glb").string() + " 2>&1");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("assignment concrete=no-such-material: "), std::string::npos) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_FALSE(fs::exists(dir / "out.glb"));
  r = test::run_command(fissure() + " scene fracture " + street + " --assign concrete=" + (dir / "gone.json").string() +
                        " -o " + (dir / "out.glb").string() + " 2>&1");
  EXPECT_EQ(r.exit_code, 4) << r.output;
  EXPECT_NE(r.output.find("gone.json"), std::string::npos) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_FALSE(fs::exists(dir / "out.glb"));
  r = test::run_command(fissure() + " scene fracture " + street + " --strict --assign tiles=ceramic-tile -o " +
                        (dir / "strict.glb").string() + " 2>&1");
  EXPECT_NE(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("the scene has no material tiles"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "strict.glb"));
  r = test::run_command(fissure() + " scene fracture " + street + " -o " + (dir / "none.glb").string() + " 2>&1");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("nothing to fracture"), std::string::npos) << r.output;
}

// Every way a new user gave one file two jobs used to exit 0 having lost one of them: the input
// scene overwritten by -o or --report, the report and the scene written over each other, a merge
// written over its own slice, a read-only file replaced. Each is now refused before any work,
// naming both jobs, and every file keeps its bytes.
TEST(SceneCli, NoOutputLandsOnAnInputOrOnAnotherOutput) {
  const fs::path dir = test::fresh_temp_dir("scene-cli-collide");
  const std::string street = (dir / "street.glb").string();
  ASSERT_EQ(test::run_command(fissure() + " scene demo street --slabs 1 --rows 1 -o " + street).exit_code, 0);
  write_file_atomically(dir / "keep.glb", "kept");
  write_file_atomically(dir / "sealed.glb", "sealed");
  ASSERT_EQ(::chmod((dir / "sealed.glb").c_str(), 0444), 0);
  fs::create_symlink(dir / "street.glb", dir / "alias.glb");
  const std::string before = read_file(street);
  const std::string run = fissure() + " scene fracture " + street + " --assign concrete=concrete --tets 300 ";
  const std::string d = dir.string() + "/";
  // An OBJ scene whose library (lib.mtl) is what -o lib.obj would write beside it.
  ASSERT_EQ(test::run_command(fissure() + " scene demo street --slabs 1 --rows 1 -o " + d + "lib.obj").exit_code, 0);
  fs::rename(dir / "lib.obj", dir / "tiles.obj");
  const std::string library = read_file(dir / "lib.mtl");
  const std::pair<std::string, std::string> cases[] = {
      {run + "--report " + street + " -o " + d + "a.glb", "--report " + street + " is the input scene"},
      {run + "-o " + d + "./street.glb", "-o " + d + "./street.glb is the input scene"},
      {run + "-o " + d + "alias.glb", "-o " + d + "alias.glb is the input scene"},
      {run + "-o " + d + "keep.glb --report " + d + "keep.glb", "name the same file"},
      {run + "-o " + d + "b.glb --report " + d + "p.json --save-project " + d + "p.json", "--report " + d + "p.json and --save-project"},
      {run + "-o " + d + "c.obj --report " + d + "c.mtl", "-o " + d + "c.mtl and --report " + d + "c.mtl name the same file"},
      {run + "-o " + d + "sealed.glb", "sealed.glb: is read-only"},
      {fissure() + " scene fracture " + d + "tiles.obj --assign concrete=concrete -o " + d + "lib.obj",
       "-o " + d + "lib.mtl is the input scene's material library"},
      {fissure() + " scene merge " + street + " " + d + "other.glb -o " + street, "-o " + street + " is the input slice"},
  };
  for (const auto& [command, expected] : cases) {
    const auto r = test::run_command(command);
    EXPECT_NE(r.exit_code, 0) << command << "\n" << r.output;
    EXPECT_NE(r.output.find(expected), std::string::npos) << command << "\n" << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  }
  EXPECT_EQ(read_file(street), before);
  EXPECT_EQ(read_file(dir / "keep.glb"), "kept");
  EXPECT_EQ(read_file(dir / "sealed.glb"), "sealed");
  EXPECT_EQ(read_file(dir / "lib.mtl"), library);
  EXPECT_TRUE(fs::is_symlink(dir / "alias.glb"));
  for (const char* name : {"a.glb", "b.glb", "p.json", "c.obj", "c.mtl", "lib.obj"}) EXPECT_FALSE(fs::exists(dir / name)) << name;
}

// assets/scenes/ holds what `fissure scene demo` writes (scripts/make-demo-scenes.sh): a change
// to the demo code without regenerating them fails here.
TEST(SceneCli, TheBundledDemoScenesAreWhatTheCodeWrites) {
  const fs::path dir = test::fresh_temp_dir("scene-cli-demo");
  for (const std::string which : {"street", "bathroom"}) {
    const fs::path written = dir / (which + ".glb");
    const auto r = test::run_command(fissure() + " scene demo " + which + " -o " + written.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_TRUE(read_file(written) == read_file(test::source_dir() / "assets" / "scenes" / (which + ".glb")))
        << which << ": run scripts/make-demo-scenes.sh";
  }
}

TEST(SceneCli, WrongFilesGetOneLine) {
  const fs::path dir = test::fresh_temp_dir("scene-cli-bad");
  const auto missing = test::run_command(fissure() + " scene info -q " + (dir / "none.glb").string());
  EXPECT_EQ(missing.exit_code, 4) << missing.output;
  EXPECT_NE(missing.output.find("none.glb"), std::string::npos) << missing.output;
  EXPECT_EQ(std::count(missing.output.begin(), missing.output.end(), '\n'), 1) << missing.output;
  write_file_atomically(dir / "scene.blend", "BLENDER");
  const auto other = test::run_command(fissure() + " scene info -q " + (dir / "scene.blend").string());
  EXPECT_EQ(other.exit_code, 4) << other.output;
  EXPECT_NE(other.output.find("unsupported scene format '.blend'"), std::string::npos) << other.output;
  EXPECT_EQ(std::count(other.output.begin(), other.output.end(), '\n'), 1) << other.output;
  const auto bare = test::run_command(fissure() + " scene");
  EXPECT_EQ(bare.exit_code, 2) << bare.output;
  const auto shaped = test::run_command(fissure() + " scene demo bathroom --slabs 3 -o " + (dir / "b.glb").string());
  EXPECT_EQ(shaped.exit_code, 3) << shaped.output;
  EXPECT_NE(shaped.output.find("--slabs and --rows shape the street"), std::string::npos) << shaped.output;
  EXPECT_FALSE(fs::exists(dir / "b.glb"));
  // Flag values CLI11 used to let through (a wrapped seed, NaN) or that were found only later:
  // each a command-line error naming the flag, before any file is read.
  const std::string run = fissure() + " scene fracture " + (dir / "none.glb").string() + " -o " + (dir / "x.glb").string();
  for (const std::string flags : {"--assign a=b --seed -5", "--assign a=b --seed 18446744073709551616", "--assign a=b --age nan",
                                  "--assign a=b --unit nan", "--assign a=b --bodies 0/3", "--assign a", "--assign a=b --age 20000"}) {
    const auto r = test::run_command(run + " " + flags);
    EXPECT_EQ(r.exit_code, 2) << flags << ": " << r.output;
    const std::string flag = flags.substr(flags.rfind("--"), flags.find(' ', flags.rfind("--")) - flags.rfind("--"));
    EXPECT_NE(r.output.find(flag), std::string::npos) << flags << ": " << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    // The help named is the subcommand's own, where these flags are listed.
    EXPECT_NE(r.output.find("(see fissure scene fracture --help)"), std::string::npos) << flags << ": " << r.output;
  }
}

}  // namespace
}  // namespace fissure
