// Scene projects (scene_project.hpp): a project file reads back as written, every malformed
// field is named with the file, a moved scene is said to have moved, per-body loads and supports
// reach their body and only it, and no byte sequence crashes the reader.

#include "fissure/base/atomic_file.hpp"
#include "fissure/base/error.hpp"
#include "fissure/base/rng.hpp"
#include "fissure/io/scene_export.hpp"
#include "fissure/io/scene_import.hpp"
#include "fissure/scene/demo_scenes.hpp"
#include "fissure/scene/scene_project.hpp"

#include "test_support.hpp"

#include <gtest/gtest.h>

#include <random>

namespace fissure {
namespace {

namespace fs = std::filesystem;

SceneProject full_project() {
  SceneProject p;
  p.scene = "street.glb";
  p.seed = 42;
  p.age = 12.5;
  p.up = "+y";
  p.tets = 900;
  p.slice = 2;
  p.slices = 3;
  p.strict = true;
  p.assignments.by_material["concrete"] = "ceramic-tile";
  p.assignments.by_path["/street/curb"] = "concrete";
  SceneBodySetupEntry slab;
  slab.loads.push_back({Eigen::Vector3d(0.1, 0.05, 0.1), Eigen::Vector3d(0, 1, 0), 3000.0, 0.05});
  slab.supports = {"box:0,0.7,-1,0.001,0,0.7@y"};
  p.bodies["/street/sidewalk/slab_01"] = slab;
  SceneBodySetupEntry free;
  free.free_body = true;
  p.bodies["/street/sidewalk/slab_02"] = free;
  SceneBodySetupEntry faced;
  faced.up = "+z";
  p.bodies["/street/curb"] = faced;
  p.output = "out/broken.glb";
  p.report = "report.json";
  return p;
}

fs::path project_dir(const std::string& name) {
  const fs::path dir = test::fresh_temp_dir(name);
  DemoStreetOptions o;
  o.slabs_along = 3;
  o.slabs_across = 1;
  write_scene(dir / "street.glb", demo_street(o));
  return dir;
}

TEST(SceneProject, AProjectReadsBackAsWritten) {
  const fs::path dir = project_dir("project-roundtrip");
  const SceneProject p = full_project();
  write_scene_project(dir / "p.json", p);
  const SceneProject q = read_scene_project(dir / "p.json");
  EXPECT_EQ(scene_project_to_json(q), scene_project_to_json(p));
  EXPECT_EQ(q.seed, 42u);
  EXPECT_EQ(q.age, 12.5);
  ASSERT_EQ(q.bodies.at("/street/sidewalk/slab_01").loads.size(), 1u);
  EXPECT_EQ(q.bodies.at("/street/sidewalk/slab_01").loads[0].magnitude, 3000.0);
  EXPECT_TRUE(q.bodies.at("/street/sidewalk/slab_02").free_body);
  EXPECT_EQ(q.bodies.at("/street/curb").up, std::optional<std::string>("+z"));
  EXPECT_EQ(project_path(dir / "p.json", q.output), dir / "out/broken.glb");
  EXPECT_EQ(project_path(dir / "p.json", "/abs/x.glb"), fs::path("/abs/x.glb"));
  // A project named without a folder is in the working one: its paths stay as written.
  EXPECT_EQ(project_path("p.json", "out/s.glb").string(), "out/s.glb");

  const SceneFractureOptions o = scene_fracture_options(q, "p.json");
  EXPECT_EQ(o.seed, 42u);
  EXPECT_EQ(*o.age, 12.5);
  EXPECT_TRUE(o.up->isApprox(Eigen::Vector3d::UnitY()));
  EXPECT_EQ(o.target_tets, 900);
  EXPECT_EQ(o.slice, 2);
  EXPECT_EQ(o.slices, 3);
  EXPECT_TRUE(q.strict);
  EXPECT_EQ(o.assignments.by_path.at("/street/curb"), "concrete");
  ASSERT_EQ(o.body_setups.at("/street/sidewalk/slab_01").supports.size(), 1u);
  EXPECT_TRUE(o.body_setups.at("/street/sidewalk/slab_02").free_body);

  // A minimal project: only the version and the scene; everything else its default.
  write_file_atomically(dir / "min.json", R"({"fissure_project": 1, "scene": "street.glb"})");
  const SceneProject m = read_scene_project(dir / "min.json");
  EXPECT_EQ(m.seed, 1u);
  EXPECT_FALSE(m.age);
  EXPECT_TRUE(m.bodies.empty());
  EXPECT_EQ(m.slices, 1);
  EXPECT_FALSE(m.strict);
}

TEST(SceneProject, EveryMalformedFieldIsNamedWithTheFile) {
  const fs::path dir = project_dir("project-bad");
  const std::string head = R"({"fissure_project": 1, "scene": "street.glb", )";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"", "syntax error at line 1, column 1"},
      {R"({"fissure_project": 1, "scene": "street.glb")", "syntax error"},
      {R"([1, 2])", "the document is array, not an object"},
      {R"({"scene": "street.glb"})", "missing key fissure_project"},
      {R"({"fissure_project": 9, "scene": "street.glb"})", "fissure_project 9 is from a newer Fissure"},
      {R"({"fissure_project": "1", "scene": "street.glb"})", "fissure_project is \"1\", not a version number"},
      {R"({"fissure_project": 1})", "missing key scene"},
      {head + R"("seed": -3})", "seed is -3, not a whole number"},
      {head + R"("seed": 1, "seed": 2})", "key seed appears twice"},
      {head + R"("sed": 2})", "unknown key \"sed\" (did you mean seed?)"},
      {head + R"("age": -1})", "age is -1, not in 0..10000"},
      {head + R"("age": 50000})", "age is 50000, not in 0..10000"},
      {head + R"("age": 1e999})", "1e999"},
      {head + R"("up": "sideways"})", "up: "},
      {head + R"("tets": 5})", "tets is 5, not 0 (the default) or a count in 10..5e7"},
      {head + R"("slice": [3, 2]})", "slice is [3,2], not [K, N] with K from 1 to N"},
      {head + R"("slice": "1/2"})", "slice is \"1/2\", not [K, N]"},
      {head + R"("slice": [0, 2]})", "slice is [0,2]"},
      {head + R"("strict": 1})", "strict is 1, not true or false"},
      {head + R"("assign": {"materials": {"concrete": 3}}})", "assign.materials.concrete is number, not a string"},
      {head + R"("assign": {"nodes": {"curb": "concrete"}}})", "assign.nodes.curb: a node path starts with /"},
      {head + R"("assign": {"material": {}}})", "unknown key assign.\"material\" (did you mean assign.materials?)"},
      {head + R"("bodies": {"/a": {"loads": [{"position": [0, 0], "normal": [0, 1, 0], "magnitude": 1, "radius": 1}]}}})",
       "bodies./a.loads[0].position is [0,0], not [x, y, z]"},
      {head + R"("bodies": {"/a": {"loads": [{"position": [0, 0, 0], "normal": [0, 0, 0], "magnitude": 1, "radius": 1}]}}})",
       "bodies./a.loads[0].normal is zero"},
      {head + R"("bodies": {"/a": {"loads": [{"position": [0, 0, 0], "normal": [0, 1, 0], "magnitude": 1, "radius": 0}]}}})",
       "bodies./a.loads[0].radius is 0, not positive"},
      {head + R"("bodies": {"/a": {"loads": [{"position": [0, 0, 0], "normal": [0, 1, 0], "radius": 1}]}}})",
       "missing key bodies./a.loads[0].magnitude"},
      {head + R"("bodies": {"/a": {"supports": ["cube:1"]}}})", "bodies./a.supports[0]: "},
      {head + R"("bodies": {"/a": {"supports": ["ball:0,0,0,1"], "free": true}}})", "bodies./a is free and has supports"},
      {head + R"("bodies": {"/a": {"free": "yes"}}})", "bodies./a.free is string, not true or false"},
      {head + R"("bodies": {"/a": {"up": "front"}}})", "bodies./a.up: --up front is not an axis"},
      {head + R"("bodies": {"/a": {"up": 3}}})", "bodies./a.up is number, not a string"},
      {head + R"("export": {"output": 1}})", "export.output is number, not a string"},
  };
  for (const auto& [text, expected] : cases) {
    write_file_atomically(dir / "bad.json", text);
    try {
      read_scene_project(dir / "bad.json");
      ADD_FAILURE() << "read: " << text;
    } catch (const IoError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind((dir / "bad.json").string() + ": not a valid Fissure project: ", 0), 0u) << what;
      EXPECT_NE(what.find(expected), std::string::npos) << "for " << text << "\ngot: " << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }
  EXPECT_THROW(read_scene_project(dir / "missing.json"), IoError);
}

TEST(SceneProject, AMovedSceneIsSaidToHaveMoved) {
  const fs::path dir = project_dir("project-moved");
  write_scene_project(dir / "p.json", full_project());
  EXPECT_NO_THROW(read_scene_project(dir / "p.json"));
  fs::rename(dir / "street.glb", dir / "elsewhere.glb");
  try {
    read_scene_project(dir / "p.json");
    ADD_FAILURE() << "a project whose scene is gone was read";
  } catch (const IoError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find((dir / "p.json").string() + ": its scene street.glb is not at " + (dir / "street.glb").string()),
              std::string::npos) << what;
    EXPECT_NE(what.find("was it moved?"), std::string::npos) << what;
  }
}

// A load in the project reaches its body, and only it: the other slabs break as they would
// without it, byte for byte; a support that holds nothing skips its body with the reason.
TEST(SceneProject, PerBodyLoadsAndSupportsReachTheirBodyOnly) {
  const fs::path dir = project_dir("project-loads");
  const ImportedScene scene = import_scene(dir / "street.glb");
  SceneProject p;
  p.scene = "street.glb";
  p.tets = 900;
  p.assignments.by_material["concrete"] = "ceramic-tile";
  const SceneFracture plain = fracture_scene(scene, scene_fracture_options(p, "p"));

  SceneBodySetupEntry struck;  // a corner blow on slab_01, far from where its material's rule strikes
  struck.loads.push_back({Eigen::Vector3d(0.06, 0.05, 0.06), Eigen::Vector3d(0, 1, 0), 20000.0, 0.04});
  p.bodies["/street/sidewalk/slab_01"] = struck;
  SceneBodySetupEntry nothing;  // a support far below the slab holds no node
  nothing.supports = {"ball:0,-10,0,0.01"};
  p.bodies["/street/sidewalk/slab_02"] = nothing;
  const SceneFracture loaded = fracture_scene(scene, scene_fracture_options(p, "p"));

  EXPECT_NE(plain.run, loaded.run);  // the setups are part of the run's identity
  for (std::size_t b = 0; b < loaded.bodies.size(); ++b) {
    const std::string& path = loaded.reports[b].path;
    if (path == "/street/sidewalk/slab_01") {
      ASSERT_TRUE(loaded.results[b]) << loaded.reports[b].reason;
      const BodyFracture& f = loaded.results[b]->fracture;
      ASSERT_EQ(f.loads.size(), 1u);
      EXPECT_NEAR(f.loads[0].force.y(), -20000.0, 1e-9);  // exactly the project's, not the rule's
      EXPECT_NE(f.loads[0].spec, plain.results[b]->fracture.loads[0].spec);
      EXPECT_NE(f.fragments.size() == plain.results[b]->fracture.fragments.size() &&
                    f.fragments.front().volume == plain.results[b]->fracture.fragments.front().volume,
                true);
    } else if (path == "/street/sidewalk/slab_02") {
      EXPECT_EQ(loaded.reports[b].status, SceneBodyReport::Status::Skipped);
      EXPECT_NE(loaded.reports[b].reason.find("ball:0,-10,0,0.01"), std::string::npos) << loaded.reports[b].reason;
    } else if (loaded.results[b]) {
      ASSERT_TRUE(plain.results[b]);
      const auto& a = loaded.results[b]->fracture.fragments;
      const auto& c = plain.results[b]->fracture.fragments;
      ASSERT_EQ(a.size(), c.size()) << path;
      for (std::size_t k = 0; k < a.size(); ++k) EXPECT_TRUE(a[k].vertices == c[k].vertices) << path << " fragment " << k;
    }
  }
}

// Mutations of a valid project (flipped, inserted and dropped bytes, truncations): every one
// reads or is refused with IoError / InvalidInput; none crashes or hangs.
TEST(SceneProject, NoByteSequenceCrashesTheReader) {
  const fs::path dir = project_dir("project-fuzz");
  const std::string good = scene_project_to_json(full_project());
  std::mt19937_64 rng(7);
  int read = 0, refused = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    std::string text = good;
    const int edits = 1 + static_cast<int>(rng() % 4);
    for (int e = 0; e < edits && !text.empty(); ++e) {
      const std::size_t at = rng() % text.size();
      switch (rng() % 4) {
        case 0: text[at] = static_cast<char>(rng()); break;
        case 1: text.insert(at, 1, "{}[]\",:0-e.\\"[rng() % 13]); break;
        case 2: text.erase(at, 1 + rng() % 8); break;
        case 3: text.resize(at); break;
      }
    }
    write_file_atomically(dir / "f.json", text);
    try {
      read_scene_project(dir / "f.json");
      ++read;
    } catch (const IoError&) {
      ++refused;
    } catch (const InvalidInput&) {
      ++refused;
    }
  }
  EXPECT_GT(refused, 1000);  // the mutations did reach the checks
  EXPECT_EQ(read + refused, 3000);
}

}  // namespace
}  // namespace fissure
