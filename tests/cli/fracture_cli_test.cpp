// `fissure fracture` end to end, as a user runs it: outputs the other commands and gmsh read,
// the same bytes at 1 and 2 threads, --fragments, and one clear line for every bad input.

#include "fissure/base/atomic_file.hpp"

#include "test_shapes.hpp"
#include "test_support.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <assimp/Importer.hpp>
#include <assimp/scene.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <functional>
#include <map>
#include <regex>
#include <set>

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
  // Each fragment's tets are a 3-D physical group named like the exported meshes.
  EXPECT_NE(read_file(path("f.msh")).find("\"fragment_000\""), std::string::npos);
  EXPECT_NE(read_file(path("f.msh")).find("\"fragment_001\""), std::string::npos);
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

  // With -o the closed meshes are counted. On this tile at N = 100 the labeller's state has
  // 80–88 meshes (seeds 1–3), and the search on the meshes' own count aims within 10 % (95 on
  // an AMD EPYC machine). Not more: this material's fragments saturate at the largest age near
  // 100–140 meshes here, by seed (150 was asked once, reached only by counting dust).
  int searched = 0;
  for (const char* seed : {"1", "2", "3"}) {
    SCOPED_TRACE(seed);
    const auto o = test::run_command(fissure() + " fracture " + mesh() + " -q --fragments 100 --seed " + seed + " -o " +
                                     path("n.glb") + " --stats " + path("n.json"));
    ASSERT_EQ(o.exit_code, 0) << o.output;
    EXPECT_EQ(o.output.find("warning"), std::string::npos) << o.output;
    const auto g = nlohmann::json::parse(read_file(path("n.json"))).at("fracture");
    EXPECT_NEAR(g.at("fragment_meshes").get<int>(), 100, 100 * 0.2) << g.dump();
    searched += g.at("fragment_meshings").get<int>() > 1;
  }
  EXPECT_GT(searched, 0) << "the labeller's states were all close: the case no longer tests the search";
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

// Issue 11: the fragments as closed meshes, as assimp (the importer engines and converters use)
// reads them back: one object per fragment named fragment_NNN, closed once its vertices are
// merged by position (the UV seams split them, as glTF requires), both materials, the volumes
// adding up to the tile's, the per-fragment values as glTF node extras.
TEST_F(FractureCli, WritesClosedFragmentMeshesThatAssimpReadsBack) {
  for (const char* name : {"f.glb", "f.obj"}) {
    SCOPED_TRACE(name);
    const auto r = test::run_command(fissure() + " fracture " + mesh() + " -q -o " + path(name) + " --stats " + path("f.json"));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto f = nlohmann::json::parse(read_file(path("f.json"))).at("fracture");
    const int fragments = f.at("fragment_meshes").get<int>();
    EXPECT_GE(fragments, 2);
    EXPECT_GT(f.at("seconds").at("fragment_meshing").get<double>(), 0.0);
    EXPECT_GT(f.at("seconds").at("export").get<double>(), 0.0);
    Assimp::Importer importer;
    const aiScene* scene = importer.ReadFile(path(name), 0);
    ASSERT_NE(scene, nullptr) << importer.GetErrorString();
    std::map<std::string, std::map<std::pair<int, int>, int>> edges;  // node → directed edge → uses
    std::set<std::string> materials;
    double volume = 0.0;
    Eigen::AlignedBox3d bounds;
    const std::function<void(const aiNode*, aiMatrix4x4)> walk = [&](const aiNode* node, aiMatrix4x4 parent) {
      const aiMatrix4x4 world = parent * node->mTransformation;
      std::map<std::array<float, 3>, int> ids;
      for (unsigned k = 0; k < node->mNumMeshes; ++k) {
        const aiMesh* m = scene->mMeshes[node->mMeshes[k]];
        materials.insert(scene->mMaterials[m->mMaterialIndex]->GetName().C_Str());
        for (unsigned t = 0; t < m->mNumFaces; ++t) {
          int v[3];
          aiVector3D x[3];
          for (int i = 0; i < 3; ++i) {
            x[i] = world * m->mVertices[m->mFaces[t].mIndices[i]];
            v[i] = ids.try_emplace({x[i].x, x[i].y, x[i].z}, static_cast<int>(ids.size())).first->second;
            bounds.extend(Eigen::Vector3d(x[i].x, x[i].y, x[i].z));
          }
          volume += static_cast<double>(x[0] * (x[1] ^ x[2])) / 6.0;
          for (int i = 0; i < 3; ++i) ++edges[node->mName.C_Str()][{v[i], v[(i + 1) % 3]}];
        }
      }
      for (unsigned c = 0; c < node->mNumChildren; ++c) walk(node->mChildren[c], world);
    };
    walk(scene->mRootNode, aiMatrix4x4());
    ASSERT_EQ(static_cast<int>(edges.size()), fragments);
    EXPECT_TRUE(edges.count("fragment_000"));
    int open = 0;
    for (const auto& [node, e] : edges)
      for (const auto& [edge, uses] : e) {
        const auto back = e.find({edge.second, edge.first});
        if (uses != 1 || back == e.end() || back->second != 1) {
          ++open;
          ADD_FAILURE() << node << " is open at an edge";
          break;
        }
      }
    EXPECT_EQ(materials, (std::set<std::string>{"crack", "surface"}));
    // The tile's 0.4 × 0.4 × 0.03 m³, to float32's resolution of the coordinates (~3e-8 m over
    // ~1e4 triangles of ≤ 1e-3 m²).
    EXPECT_NEAR(volume, 0.4 * 0.4 * 0.03, 1e-7);
    // The tile lies flat in glTF's and OBJ's +Y up (as Blender opens them): its 3 cm along Y.
    EXPECT_NEAR(bounds.sizes().y(), 0.03, 1e-6) << bounds.sizes().transpose();
    EXPECT_NEAR(bounds.sizes().x(), 0.4, 1e-6);
    EXPECT_NEAR(bounds.sizes().z(), 0.4, 1e-6);
  }
  // Node extras, as a glTF reader sees them.
  const std::string glb = read_file(path("f.glb"));
  std::uint32_t json_length = 0;
  std::memcpy(&json_length, glb.data() + 12, 4);
  const auto gltf = nlohmann::json::parse(glb.substr(20, json_length));
  double mass = 0.0;
  // Node 0 turns the tile's +Z up to glTF's +Y; the fragments are its children, in the tile's frame.
  const auto& frame = gltf.at("nodes").at(0);
  EXPECT_EQ(frame.at("name"), "tile");
  EXPECT_EQ(frame.at("children").size(), gltf.at("nodes").size() - 1);
  EXPECT_EQ(gltf.at("scenes").at(0).at("nodes"), nlohmann::json::array({0}));
  for (const auto& node : gltf.at("nodes")) {
    if (!node.contains("mesh")) continue;
    const auto& extras = node.at("extras");
    mass += extras.at("mass_kg").get<double>();
    EXPECT_EQ(node.at("translation"), extras.at("centre_of_mass_m"));
    EXPECT_TRUE(extras.at("contacts").is_array());
  }
  EXPECT_NEAR(mass, 0.4 * 0.4 * 0.03 * 2400.0, 1e-6);  // ceramic-tile's density, kg/m³
}

// A box as a modeller exports it: one material per face and a different linear UV map on
// each. The fragments' outer faces keep the material of the face they lie on and its UVs, in
// the OBJ and the GLB, as assimp reads them back.
TEST_F(FractureCli, OuterFacesKeepTheInputsMaterialsAndUVs) {
  struct Face {
    const char* name;
    int axis;      // the face's normal axis
    double side;   // its coordinate on that axis
    std::array<int, 4> corners;  // vertex numbers from 1: bit 2 → +x, bit 1 → +y, bit 0 → +z
    std::function<std::array<double, 2>(const std::array<double, 3>&)> uv;
  };
  const std::vector<Face> faces = {
      {"top", 2, 0.015, {1, 5, 7, 3}, [](const auto& p) { return std::array{2 * p[0] + 0.1, 3 * p[1] - 0.2}; }},
      {"bottom", 2, -0.015, {0, 2, 6, 4}, [](const auto& p) { return std::array{p[0], -p[1]}; }},
      {"px", 0, 0.2, {4, 6, 7, 5}, [](const auto& p) { return std::array{p[1], 5 * p[2]}; }},
      {"nx", 0, -0.2, {0, 1, 3, 2}, [](const auto& p) { return std::array{-p[1], 5 * p[2]}; }},
      {"py", 1, 0.2, {2, 3, 7, 6}, [](const auto& p) { return std::array{p[0] + 1, p[2]}; }},
      {"ny", 1, -0.2, {0, 4, 5, 1}, [](const auto& p) { return std::array{p[0] - 1, p[2]}; }}};
  const auto corner = [](int i) {
    return std::array<double, 3>{(i & 4) ? 0.2 : -0.2, (i & 2) ? 0.2 : -0.2, (i & 1) ? 0.015 : -0.015};
  };
  std::string obj;
  for (int i = 0; i < 8; ++i) obj += "v " + std::to_string(corner(i)[0]) + " " + std::to_string(corner(i)[1]) + " " + std::to_string(corner(i)[2]) + "\n";
  int uvs = 0;
  for (const Face& f : faces) {
    std::string line = "usemtl " + std::string(f.name) + "\nf";
    for (int c : f.corners) {
      const auto uv = f.uv(corner(c));
      obj += "vt " + std::to_string(uv[0]) + " " + std::to_string(uv[1]) + "\n";
      line += " " + std::to_string(c + 1) + "/" + std::to_string(++uvs);
    }
    obj += line + "\n";
  }
  write_file_atomically(path("box.obj"), obj);

  for (const char* name : {"box-f.obj", "box-f.glb"}) {
    SCOPED_TRACE(name);
    const auto r = test::run_command(fissure() + " fracture " + path("box.obj") + " --tets 3000 -q -o " + path(name));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    Assimp::Importer importer;
    const aiScene* scene = importer.ReadFile(path(name), 0);
    ASSERT_NE(scene, nullptr) << importer.GetErrorString();
    std::set<std::string> materials;
    int checked = 0;
    const std::function<void(const aiNode*, aiMatrix4x4)> walk = [&](const aiNode* node, aiMatrix4x4 parent) {
      const aiMatrix4x4 world = parent * node->mTransformation;
      for (unsigned k = 0; k < node->mNumMeshes; ++k) {
        const aiMesh* m = scene->mMeshes[node->mMeshes[k]];
        const std::string material = scene->mMaterials[m->mMaterialIndex]->GetName().C_Str();
        materials.insert(material);
        const auto face = std::find_if(faces.begin(), faces.end(), [&](const Face& f) { return material == f.name; });
        if (face == faces.end()) continue;  // the crack's
        ASSERT_TRUE(m->HasTextureCoords(0));
        // The vertices its triangles use (a GLB's primitives share their fragment's vertices).
        std::set<unsigned> used;
        for (unsigned t = 0; t < m->mNumFaces; ++t) used.insert(m->mFaces[t].mIndices, m->mFaces[t].mIndices + m->mFaces[t].mNumIndices);
        for (const unsigned v : used) {
          const aiVector3D x = world * m->mVertices[v];
          const std::array<double, 3> p{x.x, x.y, x.z};
          // On its own face, to float32's resolution of the coordinates (~3e-8 m).
          ASSERT_NEAR(p[static_cast<std::size_t>(face->axis)], face->side, 1e-6) << material;
          // The face's UV map, to float32's resolution of positions and UVs (the maps' slopes ≤ 5).
          const auto uv = face->uv(p);
          EXPECT_NEAR(m->mTextureCoords[0][v].x, uv[0], 1e-5) << material;
          EXPECT_NEAR(m->mTextureCoords[0][v].y, uv[1], 1e-5) << material;
          ++checked;
        }
      }
      for (unsigned c = 0; c < node->mNumChildren; ++c) walk(node->mChildren[c], world);
    };
    walk(scene->mRootNode, aiMatrix4x4());
    EXPECT_EQ(materials, (std::set<std::string>{"top", "bottom", "px", "nx", "py", "ny", "crack"}));
    EXPECT_GT(checked, 100);
  }
}

// Same seed, same bytes in every format, at 1 and 2 threads.
TEST_F(FractureCli, FragmentExportsAreTheSameBytesAtOneAndTwoThreads) {
  for (const char* name : {"d.glb", "d.gltf", "d.obj", "d.ply"}) {
    std::string bytes[2];
    for (int threads = 1; threads <= 2; ++threads) {
      const auto r = test::run_command(fissure() + " fracture " + mesh() + " -q --threads " + std::to_string(threads) +
                                       " -o " + path(name));
      ASSERT_EQ(r.exit_code, 0) << r.output;
      bytes[threads - 1] = read_file(path(name));
    }
    EXPECT_EQ(bytes[0], bytes[1]) << name;
    EXPECT_GT(bytes[0].size(), 1000u) << name;
  }
}

// A load with a few digits too many is finite physics, so it runs, but it is said: 1e300 N
// shatters the tile at once. A hammer's 1e4 N over 3 cm is not flagged.
TEST_F(FractureCli, AnAbsurdLoadIsSaid) {
  const std::string run = fissure() + " fracture tile:0.3,0.3,0.02 --tets 2000 -q --stats " + path("load.json");
  auto r = test::run_command(run + " --load ball:0,0,0.01,0.03=0,0,-1e300");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("warning: the loads stress"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("are the forces in newtons?"), std::string::npos) << r.output;
  r = test::run_command(run + " --load ball:0,0,0.01,0.03=0,0,-1e4");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output.find("warning"), std::string::npos) << r.output;
}

TEST_F(FractureCli, BadInputIsOneLineAndWritesNothing) {
  const std::string run = fissure() + " fracture " + mesh();
  const std::string out = " --stats " + path("never.json");
  // A value outside its table range is a command-line error (2), like any other flag's range.
  expect_failure(test::run_command(run + " --relax-radius -1" + out), 2, "--relax-radius: -1 is outside (0, 100] m");
  expect_failure(test::run_command(run + " --material marble" + out), 3, "material \"marble\"");
  write_file_atomically(path("broken.json"), "{\"schema\": \"fissure-material\", \"version\": 1, \"name\": \"x\", \"parameters\": {}}");
  expect_failure(test::run_command(run + " --material " + path("broken.json") + out), 4, path("broken.json"));
  expect_failure(test::run_command(run + " --load ball:5,5,5,0.01=0,0,-100" + out), 3, "ball:5,5,5,0.01");
  expect_failure(test::run_command(run + " --up w" + out), 3, "--up w");
  expect_failure(test::run_command(run + " --stats /nonexistent-dir/s.json"), 4, "/nonexistent-dir");
  expect_failure(test::run_command(run + " -o " + path("f.fbx") + out), 4, "the output must end in .glb, .gltf, .obj or .ply");
  expect_failure(test::run_command(run + " -o /nonexistent-dir/f.glb" + out), 4, "/nonexistent-dir");
  fs::create_directory(path("folder.glb"));
  expect_failure(test::run_command(run + " -o " + path("folder.glb") + out), 4, path("folder.glb"));
  expect_failure(test::run_command(run + " -o -" + out), 3, "only --stats may be -");
  expect_failure(test::run_command(run + " --pattern " + path("p.jpg") + out), 2,
                 "--pattern: " + path("p.jpg") + ": the image is written as PNG; name it .png");
  // An open surface: one triangle.
  write_file_atomically(path("open.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  expect_failure(test::run_command(fissure() + " fracture " + path("open.obj") + out), 3, path("open.obj"));
  // A whole scene (slabs, a curb touching the road) read as one surface crosses itself: the
  // message says what it likely is and which command breaks each object.
  const std::string street = (test::source_dir() / "assets" / "scenes" / "street.glb").string();
  expect_failure(test::run_command(fissure() + " fracture " + street + " --tets 500" + out), 3,
                 "self-intersecting: 24 pairs of faces cross (a scene of several objects that touch? fissure scene fracture");
  // Supports that hold every node: nothing can move (CHOLMOD used to say "out of memory?").
  expect_failure(test::run_command(run + " --fix box:-1,1,-1,1,-1,1" + out), 3, "the supports fix every node");
  EXPECT_FALSE(fs::exists(path("never.json")));
}

}  // namespace
}  // namespace fissure
