// The scene writers (include/fissure/io/scene_export.hpp) read back by assimp, the library most
// engines and converters use: one node per part with its name and origin, closed parts, both
// materials, UVs, glTF extras; the same bytes every time; bad scenes and paths refused.
#include "fissure/io/scene_export.hpp"
#include "fissure/io/gltf_reader.hpp"

#include "fissure/base/atomic_file.hpp"
#include "fissure/base/error.hpp"

#include "test_support.hpp"

#include <Eigen/Geometry>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstring>
#include <map>

namespace fissure {
namespace {
namespace fs = std::filesystem;

// A unit cube at `origin` as a part: 24 vertices (one UV chart per face), the top face in
// material 1 ("crack"), the others in material 0.
ExportPart cube(const std::string& name, const Eigen::Vector3d& origin) {
  ExportPart p;
  p.name = name;
  p.translation = origin;
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  p.vertices.resize(24, 3);
  p.uvs.resize(24, 2);
  p.triangles.resize(12, 3);
  for (int f = 0; f < 6; ++f) {
    for (int i = 0; i < 4; ++i) {
      const int c = faces[f][i];
      p.vertices.row(4 * f + i) = Eigen::RowVector3d((c & 1) - 0.5, (c >> 1 & 1) - 0.5, (c >> 2 & 1) - 0.5);
      p.uvs.row(4 * f + i) = Eigen::RowVector2d(i == 1 || i == 2, i >= 2);
    }
    p.triangles.row(2 * f) = Eigen::RowVector3i(4 * f, 4 * f + 1, 4 * f + 2);
    p.triangles.row(2 * f + 1) = Eigen::RowVector3i(4 * f, 4 * f + 2, 4 * f + 3);
    p.triangle_material.push_back(f == 5 ? 1 : 0);
    p.triangle_material.push_back(f == 5 ? 1 : 0);
  }
  p.extras_json = R"({"volume_m3":1,"name":")" + name + "\"}";
  return p;
}

ExportScene two_cubes() {
  ExportScene s;
  s.materials = {{"surface", Eigen::Vector3d(0.6, 0.6, 0.6), {}}, {"crack", Eigen::Vector3d(0.3, 0.3, 0.3), {}}};
  s.parts = {cube("fragment_000", Eigen::Vector3d(0, 0, 0)), cube("fragment_001", Eigen::Vector3d(3, 0, 0.5))};
  return s;
}

// Per node: its meshes' triangles with vertices merged by position (world coordinates), then
// every edge used once each way (closed and consistently wound).
struct NodeReport {
  int triangles = 0;
  bool closed = true;
  double volume = 0.0;
  std::vector<std::string> materials;
  bool has_uvs = true;
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
};

std::map<std::string, NodeReport> read_back(const fs::path& file) {
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(file.string(), 0);
  EXPECT_NE(scene, nullptr) << file << ": " << importer.GetErrorString();
  std::map<std::string, NodeReport> out;
  if (!scene) return out;
  const std::function<void(const aiNode*, aiMatrix4x4)> walk = [&](const aiNode* node, aiMatrix4x4 parent) {
    const aiMatrix4x4 world = parent * node->mTransformation;
    if (node->mNumMeshes > 0) {
      NodeReport& r = out[node->mName.C_Str()];
      r.translation = Eigen::Vector3d(world.a4, world.b4, world.c4);
      std::map<std::array<float, 3>, int> ids;
      std::map<std::pair<int, int>, int> edges;
      for (unsigned k = 0; k < node->mNumMeshes; ++k) {
        const aiMesh* m = scene->mMeshes[node->mMeshes[k]];
        r.materials.push_back(scene->mMaterials[m->mMaterialIndex]->GetName().C_Str());
        r.has_uvs = r.has_uvs && m->HasTextureCoords(0);
        for (unsigned f = 0; f < m->mNumFaces; ++f) {
          ++r.triangles;
          int v[3];
          Eigen::Vector3d p[3];
          for (int i = 0; i < 3; ++i) {
            aiVector3D x = world * m->mVertices[m->mFaces[f].mIndices[i]];
            v[i] = ids.try_emplace({x.x, x.y, x.z}, static_cast<int>(ids.size())).first->second;
            p[i] = Eigen::Vector3d(x.x, x.y, x.z);
          }
          r.volume += p[0].dot(p[1].cross(p[2])) / 6.0;
          for (int i = 0; i < 3; ++i) ++edges[{v[i], v[(i + 1) % 3]}];
        }
      }
      for (const auto& [e, n] : edges)
        if (n != 1 || !edges.count({e.second, e.first}) || edges.at({e.second, e.first}) != 1) r.closed = false;
    }
    for (unsigned c = 0; c < node->mNumChildren; ++c) walk(node->mChildren[c], world);
  };
  walk(scene->mRootNode, aiMatrix4x4());
  return out;
}

class SceneExport : public ::testing::Test {
protected:
  void SetUp() override { dir = test::fresh_temp_dir("scene-export"); }
  fs::path dir;
};

TEST_F(SceneExport, GlbGltfAndObjReadBackByAssimpAsOneClosedObjectPerPart) {
  for (const char* name : {"cubes.glb", "cubes.gltf", "cubes.obj"}) {
    SCOPED_TRACE(name);
    write_scene(dir / name, two_cubes());
    const auto nodes = read_back(dir / name);
    ASSERT_EQ(nodes.size(), 2u);
    for (const char* part : {"fragment_000", "fragment_001"}) {
      ASSERT_TRUE(nodes.count(part)) << part;
      const NodeReport& r = nodes.at(part);
      EXPECT_EQ(r.triangles, 12);
      EXPECT_TRUE(r.closed);
      EXPECT_NEAR(r.volume, 1.0, 1e-6);  // float32 of small integers and halves: exact
      EXPECT_TRUE(r.has_uvs);
      std::vector<std::string> materials = r.materials;
      std::sort(materials.begin(), materials.end());
      EXPECT_EQ(materials, (std::vector<std::string>{"crack", "surface"}));
    }
    // glTF keeps the origin as the node's translation; OBJ has none (world positions).
    if (std::string(name) != "cubes.obj") {
      EXPECT_TRUE(nodes.at("fragment_001").translation.isApprox(Eigen::Vector3d(3, 0, 0.5)));
    }
  }
  EXPECT_TRUE(fs::exists(dir / "cubes.mtl"));
  EXPECT_NE(read_file(dir / "cubes.obj").find("mtllib cubes.mtl"), std::string::npos);
}

// The GLB's own structure, read as the glTF 2.0 spec lays it out: header, JSON chunk, BIN
// chunk, 4-byte alignment, node extras, accessor bounds.
TEST_F(SceneExport, GlbFollowsTheSpecLayoutAndKeepsNodeExtras) {
  const std::string bytes = encode_scene(two_cubes(), SceneFormat::Glb);
  ASSERT_GE(bytes.size(), 28u);
  std::uint32_t header[5];
  std::memcpy(header, bytes.data(), sizeof header);
  EXPECT_EQ(header[0], 0x46546C67u);
  EXPECT_EQ(header[1], 2u);
  EXPECT_EQ(header[2], bytes.size());
  EXPECT_EQ(header[3] % 4, 0u);
  EXPECT_EQ(header[4], 0x4E4F534Au);
  const auto gltf = nlohmann::json::parse(bytes.substr(20, header[3]));
  std::uint32_t bin[2];
  std::memcpy(bin, bytes.data() + 20 + header[3], sizeof bin);
  EXPECT_EQ(bin[1], 0x004E4942u);
  EXPECT_EQ(bin[0], gltf.at("buffers").at(0).at("byteLength").get<std::uint32_t>());
  EXPECT_EQ(20 + header[3] + 8 + bin[0], bytes.size());
  ASSERT_EQ(gltf.at("nodes").size(), 2u);
  EXPECT_EQ(gltf.at("nodes").at(1).at("extras").at("name"), "fragment_001");
  EXPECT_EQ(gltf.at("nodes").at(1).at("extras").at("volume_m3"), 1);
  for (const auto& view : gltf.at("bufferViews")) EXPECT_EQ(view.at("byteOffset").get<int>() % 4, 0);
  const auto& position = gltf.at("accessors").at(gltf.at("meshes").at(0).at("primitives").at(0).at("attributes").at("POSITION").get<int>());
  EXPECT_EQ(position.at("min"), nlohmann::json::array({-0.5, -0.5, -0.5}));
  EXPECT_EQ(position.at("max"), nlohmann::json::array({0.5, 0.5, 0.5}));
  // The two primitives of a part share its one vertex array: a closed part stays closed.
  const auto& primitives = gltf.at("meshes").at(0).at("primitives");
  ASSERT_EQ(primitives.size(), 2u);
  EXPECT_EQ(primitives.at(0).at("attributes"), primitives.at(1).at("attributes"));
}

TEST_F(SceneExport, PlyHoldsEveryPartTaggedByIndex) {
  write_scene(dir / "cubes.ply", two_cubes());
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile((dir / "cubes.ply").string(), 0);
  ASSERT_NE(scene, nullptr) << importer.GetErrorString();
  unsigned faces = 0;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) faces += scene->mMeshes[m]->mNumFaces;
  EXPECT_EQ(faces, 24u);
  const std::string text = read_file(dir / "cubes.ply");
  EXPECT_NE(text.find("property int part\n"), std::string::npos);
  EXPECT_NE(text.find("comment material 1 crack\n"), std::string::npos);
}

// Names come from imported files (a glTF material "Old Stone"): in OBJ and MTL, whose
// statements are words, blanks and control characters become '_'; glTF keeps them as given.
TEST_F(SceneExport, NamesWithBlanksStayOneWordInObj) {
  ExportScene s = two_cubes();
  s.materials[0].name = "Old Stone\nnewmtl x";
  s.parts[0].name = "part one";
  const std::string obj = encode_scene(s, SceneFormat::Obj, "x.mtl"), mtl = encode_obj_materials(s);
  EXPECT_NE(obj.find("\nusemtl Old_Stone_newmtl_x\n"), std::string::npos) << obj.substr(0, 300);
  EXPECT_NE(obj.find("\no part_one\n"), std::string::npos);
  EXPECT_NE(mtl.find("\nnewmtl Old_Stone_newmtl_x\n"), std::string::npos) << mtl;
  EXPECT_EQ(mtl.find("\nnewmtl x\n"), std::string::npos) << mtl;
  EXPECT_NE(encode_scene(s, SceneFormat::Gltf).find("Old Stone\\nnewmtl x"), std::string::npos);
}

// Each format in its own up convention (ExportScene::up): a part raised along the parts' up by 2
// comes out raised along +Y in glTF and OBJ (as Blender reads them) and along +Z in PLY (as CAD
// tools and Fissure's own reader take it). A +Z scene's glTF keeps its parts and their extras
// under one added root that turns them; OBJ and PLY have no hierarchy and turn the positions.
TEST_F(SceneExport, EachFormatIsWrittenInItsOwnUpAxis) {
  for (const Eigen::Vector3d up : {Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(-1, 0, 0)}) {
    SCOPED_TRACE(up.transpose());
    ExportScene s = two_cubes();
    s.up = up;
    s.frame_name = "tile";
    s.parts[1].translation = 2.0 * up;
    for (const char* name : {"up.glb", "up.obj"}) {
      SCOPED_TRACE(name);
      write_scene(dir / name, s);
      const auto nodes = read_back(dir / name);
      ASSERT_EQ(nodes.size(), 2u);
      const NodeReport& raised = nodes.at("fragment_001");
      EXPECT_NEAR(raised.volume, 1.0, 1e-6);  // turned, not mirrored
      EXPECT_TRUE(raised.closed);
      if (std::string(name) == "up.glb") EXPECT_TRUE(raised.translation.isApprox(Eigen::Vector3d(0, 2, 0), 1e-12));
    }
    const ExportScene back = read_fissure_gltf(dir / "up.glb");
    ASSERT_EQ(back.parts.size(), up == Eigen::Vector3d::UnitY() ? 2u : 3u);
    if (back.parts.size() == 3u) {
      EXPECT_EQ(back.parts[0].name, "tile");
      EXPECT_EQ(back.parts[1].parent, 0);
      // The part keeps its own frame, and its extras with it.
      EXPECT_EQ(back.parts[2].translation, 2.0 * up);
      EXPECT_EQ(nlohmann::json::parse(back.parts[2].extras_json).at("name"), "fragment_001");
      EXPECT_TRUE((back.parts[0].linear * up).isApprox(Eigen::Vector3d::UnitY(), 1e-15));
    }
    // PLY: the raised cube's vertices lie 1.5..2.5 along +Z.
    const std::string ply = encode_scene(s, SceneFormat::Ply);
    const std::size_t body = ply.find("end_header\n") + 11;
    float z_max = -1e9f;
    for (int v = 0; v < 48; ++v) {
      float x[3];
      std::memcpy(x, ply.data() + body + static_cast<std::size_t>(v) * 24, sizeof x);
      z_max = std::max(z_max, x[2]);
    }
    EXPECT_FLOAT_EQ(z_max, 2.5f);
  }
}

// turn_between: a rotation (orthonormal, det +1) taking `from` to `to`, exact between axes, and
// for opposite vectors a half turn.
TEST(TurnBetween, IsTheRotationFromOneAxisToAnother) {
  const Eigen::Vector3d axes[] = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ(),
                                  -Eigen::Vector3d::UnitX(), -Eigen::Vector3d::UnitY(), -Eigen::Vector3d::UnitZ(),
                                  Eigen::Vector3d(1, 2, -3).normalized(), Eigen::Vector3d(-1, -2, 3).normalized()};
  for (const Eigen::Vector3d& a : axes)
    for (const Eigen::Vector3d& b : axes) {
      const Eigen::Matrix3d r = turn_between(a, b);
      SCOPED_TRACE(testing::Message() << a.transpose() << " -> " << b.transpose());
      EXPECT_TRUE((r * a).isApprox(b, 1e-14));
      EXPECT_TRUE((r.transpose() * r).isApprox(Eigen::Matrix3d::Identity(), 1e-14));
      EXPECT_NEAR(r.determinant(), 1.0, 1e-14);
    }
  // Exact between coordinate axes: +Z to +Y writes 0 and ±1 only.
  Eigen::Matrix3d z_to_y;
  z_to_y << 1, 0, 0, 0, 0, 1, 0, -1, 0;
  EXPECT_EQ(turn_between(Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitY()), z_to_y);
  EXPECT_EQ(turn_between(Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitY()), Eigen::Matrix3d::Identity());
}

TEST_F(SceneExport, SameSceneSameBytes) {
  for (SceneFormat f : {SceneFormat::Glb, SceneFormat::Gltf, SceneFormat::Obj, SceneFormat::Ply})
    EXPECT_EQ(encode_scene(two_cubes(), f, "x.mtl"), encode_scene(two_cubes(), f, "x.mtl"));
}

// A scene with what scene_export (scene/scene_fracture.hpp) writes: a rotated and scaled group,
// parts under it, one without UVs, a textured material, extras on nodes and on the scene.
ExportScene rich_scene() {
  ExportScene s = two_cubes();
  s.materials[0].texture = "textures/stone.png";
  ExportPart group;
  group.name = "group";
  group.linear = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix() * 1.7;
  group.translation = Eigen::Vector3d(0.1, -2.5, 1e-7);
  s.parts.insert(s.parts.begin(), group);
  for (std::size_t k = 1; k < s.parts.size(); ++k) s.parts[k].parent = 0;
  ExportPart bare = cube("no_uvs", Eigen::Vector3d(-1, 0, 0));
  bare.uvs.resize(0, 2);
  bare.parent = 2;
  bare.vertices *= 1.0 / 3.0;  // values float32 rounds
  s.parts.push_back(bare);
  s.extras_json = R"({"fissure":{"slice":[1,1],"run":"abc"}})";
  return s;
}

// read_fissure_gltf gives back the scene it was written from: writing it again gives the same
// bytes, which is what `fissure scene merge` relies on for byte-identical slices.
TEST_F(SceneExport, FissureGltfReadsBackToTheSameBytes) {
  const ExportScene s = rich_scene();
  for (SceneFormat f : {SceneFormat::Glb, SceneFormat::Gltf}) {
    const std::string bytes = encode_scene(s, f);
    const ExportScene back = decode_fissure_gltf(bytes, "x");
    ASSERT_EQ(back.parts.size(), s.parts.size());
    for (std::size_t k = 0; k < s.parts.size(); ++k) {
      const ExportPart &a = s.parts[k], &b = back.parts[k];
      EXPECT_EQ(b.name, a.name);
      EXPECT_EQ(b.parent, a.parent);
      EXPECT_EQ(b.linear, a.linear) << "doubles in JSON read back exactly";
      EXPECT_EQ(b.translation, a.translation);
      EXPECT_EQ(b.uvs.rows(), a.uvs.rows()) << a.name;
      EXPECT_EQ(b.triangles.rows(), a.triangles.rows());
      // float32 in the buffer: half an ulp of 1 relative.
      if (a.vertices.rows() > 0) {
        EXPECT_LT((b.vertices - a.vertices).cwiseAbs().maxCoeff(), 6e-8) << a.name;
      }
      EXPECT_EQ(nlohmann::json::parse(b.extras_json), nlohmann::json::parse(a.extras_json));
    }
    EXPECT_EQ(back.materials.size(), 2u);
    EXPECT_EQ(back.materials[0].texture, "textures/stone.png");
    EXPECT_EQ(back.materials[1].colour, s.materials[1].colour);
    EXPECT_EQ(nlohmann::json::parse(back.extras_json), nlohmann::json::parse(s.extras_json));
    EXPECT_EQ(encode_scene(back, f), bytes) << "re-encoded differs";
  }
}

TEST_F(SceneExport, FissureGltfReaderRefusesWhatFissureDidNotWrite) {
  auto refused = [](const std::string& bytes, const std::string& expected) {
    try {
      decode_fissure_gltf(bytes, "in.glb");
      ADD_FAILURE() << "read: " << expected;
    } catch (const InvalidInput& e) {
      EXPECT_EQ(std::string(e.what()).rfind("in.glb: ", 0), 0u) << e.what();
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  };
  refused(R"({"asset":{"version":"2.0","generator":"Khronos glTF Blender I/O"}})", "not written by Fissure");
  refused("{", "does not parse");
  std::string glb = encode_scene(two_cubes(), SceneFormat::Glb);
  refused(glb.substr(0, glb.size() - 4), "header gives");
  std::string text = encode_scene(two_cubes(), SceneFormat::Gltf);
  const std::size_t at = text.find("\"bufferView\": 1");
  ASSERT_NE(at, std::string::npos);
  refused(text.replace(at, 15, "\"bufferView\": 99"), "bufferViews 99 does not exist");
}

TEST_F(SceneExport, BadScenesAndPathsAreRefusedNamingTheCulprit) {
  ExportScene s = two_cubes();
  s.parts[1].triangles(3, 1) = 99;
  try {
    write_scene(dir / "bad.glb", s);
    ADD_FAILURE() << "accepted a triangle past the vertices";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("part 2 (fragment_001): triangle 4 indexes vertex 100 of 24"), std::string::npos) << e.what();
  }
  s = two_cubes();
  s.parts[0].vertices(0, 0) = std::nan("");
  EXPECT_THROW(write_scene(dir / "bad.glb", s), InvalidInput);
  s = two_cubes();
  s.parts[0].extras_json = "[1]";
  EXPECT_THROW(write_scene(dir / "bad.glb", s), InvalidInput);
  EXPECT_FALSE(fs::exists(dir / "bad.glb"));
  for (const fs::path& p : {dir / "x.fbx", dir / "x", dir / "missing" / "x.glb"}) {
    try {
      write_scene(p, two_cubes());
      ADD_FAILURE() << p;
    } catch (const IoError& e) {
      EXPECT_NE(std::string(e.what()).find(p.string()), std::string::npos) << e.what();
    }
  }
  fs::create_directory(dir / "folder.glb");
  EXPECT_THROW(write_scene(dir / "folder.glb", two_cubes()), IoError);
  EXPECT_TRUE(fs::is_directory(dir / "folder.glb"));
}

}  // namespace
}  // namespace fissure
