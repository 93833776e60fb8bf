// Scene import (scene_import.hpp): the node hierarchy, its transforms, mesh instances as bodies,
// scene material names and texture references, as written in a hand-made glTF and COLLADA file
// and read back through assimp; the simple formats as one node; wrong files named.

#include "fissure/base/atomic_file.hpp"
#include "fissure/base/error.hpp"
#include "fissure/io/scene_export.hpp"
#include "fissure/io/scene_import.hpp"

#include "collada_files.hpp"
#include "surface_files.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>

namespace fissure {
namespace {

namespace fs = std::filesystem;

// A street: "street" (moved 1 m along x) holds two nodes both named "slab" that share the mesh
// "Slab" (one moved 2 m up, one turned 90° about y), and "lamp" whose child "bulb" (scaled 2×)
// holds the mesh "Bulb". Each mesh is a tetrahedron as 4 unindexed triangles (144 bytes).
fs::path write_street(const fs::path& dir) {
  const std::array<std::array<float, 3>, 4> p = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  std::string bin;
  for (int corner : {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3}) {
    for (float c : p[static_cast<std::size_t>(corner)]) test::put(bin, c, false);
  }
  write_file_atomically(dir / "t.bin", bin);
  const double h = std::sqrt(0.5);
  write_file_atomically(dir / "street.gltf", R"({"asset": {"version": "2.0"},
    "buffers": [{"byteLength": 144, "uri": "t.bin"}],
    "bufferViews": [{"buffer": 0, "byteLength": 144}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "type": "VEC3", "count": 12,
                   "min": [0, 0, 0], "max": [1, 1, 1]}],
    "images": [{"uri": "concrete.png"}],
    "textures": [{"source": 0}],
    "materials": [{"name": "concrete", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.4, 0.3, 1],
                                                                 "baseColorTexture": {"index": 0}}},
                  {"name": "glass"}],
    "meshes": [{"name": "Slab", "primitives": [{"attributes": {"POSITION": 0}, "material": 0}]},
               {"name": "Bulb", "primitives": [{"attributes": {"POSITION": 0}, "material": 1}]}],
    "nodes": [{"name": "street", "translation": [1, 0, 0], "children": [1, 2, 3]},
              {"name": "slab", "mesh": 0, "translation": [0, 2, 0]},
              {"name": "slab", "mesh": 0, "rotation": [0, )" + std::to_string(h) + ", 0, " + std::to_string(h) + R"(]},
              {"name": "lamp", "children": [4]},
              {"name": "bulb", "mesh": 1, "scale": [2, 2, 2]}],
    "scenes": [{"nodes": [0]}], "scene": 0})");
  return dir / "street.gltf";
}

Eigen::Vector3d apply(const Eigen::Matrix4d& m, const Eigen::Vector3d& p) { return m.topLeftCorner<3, 3>() * p + m.topRightCorner<3, 1>(); }

TEST(SceneImport, GltfKeepsHierarchyInstancesMaterialsAndTextures) {
  const fs::path dir = test::fresh_temp_dir("scene-import-gltf");
  const ImportedScene scene = import_scene(write_street(dir));
  EXPECT_EQ(scene.format, "gltf");
  EXPECT_EQ(scene.up, Eigen::Vector3d::UnitY());
  ASSERT_EQ(scene.meshes.size(), 2u);
  EXPECT_EQ(scene.meshes[0].name, "Slab");
  EXPECT_EQ(scene.meshes[0].triangles.rows(), 4);
  std::string names;
  for (const SceneMaterial& m : scene.materials) names += " '" + m.name + "'";
  ASSERT_EQ(scene.materials.size(), 2u) << names;
  EXPECT_EQ(scene.materials[static_cast<std::size_t>(scene.meshes[0].material)].name, "concrete");
  EXPECT_EQ(scene.materials[static_cast<std::size_t>(scene.meshes[1].material)].name, "glass");
  const SceneMaterial& concrete = scene.materials[static_cast<std::size_t>(scene.meshes[0].material)];
  EXPECT_NEAR(concrete.colour.x(), 0.5, 1e-6);
  ASSERT_EQ(concrete.textures.size(), 1u) << "the reference is kept though concrete.png does not exist";
  EXPECT_EQ(concrete.textures[0], "concrete.png");

  // Parents before children; two siblings named "slab" get their own paths.
  std::vector<std::string> paths;
  for (std::size_t i = 0; i < scene.nodes.size(); ++i) {
    paths.push_back(scene.nodes[i].path);
    if (scene.nodes[i].parent >= 0) {
      EXPECT_LT(static_cast<std::size_t>(scene.nodes[i].parent), i);
    }
  }
  EXPECT_EQ(paths, (std::vector<std::string>{"/street", "/street/slab", "/street/slab#2", "/street/lamp", "/street/lamp/bulb"}));

  // Three bodies: the shared mesh twice, the bulb once, each with its world transform.
  const std::vector<SceneBody> bodies = scene_bodies(scene);
  ASSERT_EQ(bodies.size(), 3u);
  EXPECT_EQ(bodies[0].meshes, bodies[1].meshes) << "two nodes sharing one mesh are two bodies";
  EXPECT_EQ(bodies[0].path, "/street/slab");
  EXPECT_EQ(bodies[1].path, "/street/slab#2");
  EXPECT_EQ(bodies[2].path, "/street/lamp/bulb");
  // float32 in the file: 1e-6 is its resolution at 1 m.
  const Eigen::Vector3d x = Eigen::Vector3d::UnitX();
  EXPECT_TRUE(apply(bodies[0].world, x).isApprox(Eigen::Vector3d(2, 2, 0), 1e-6)) << apply(bodies[0].world, x).transpose();
  // 90° about +y takes +x to −z, then the street's 1 m along x.
  EXPECT_TRUE(apply(bodies[1].world, x).isApprox(Eigen::Vector3d(1, 0, -1), 1e-6)) << apply(bodies[1].world, x).transpose();
  EXPECT_TRUE(apply(bodies[2].world, x).isApprox(Eigen::Vector3d(3, 0, 0), 1e-6)) << apply(bodies[2].world, x).transpose();
  // The mesh keeps its own frame: the instances' geometry is the file's, unmoved.
  EXPECT_DOUBLE_EQ(scene.meshes[0].vertices.col(0).maxCoeff(), 1.0);
}

TEST(SceneImport, SimpleFormatsAreOneNodeWithTheirConventionalUp) {
  const fs::path dir = test::fresh_temp_dir("scene-import-simple");
  const test::Polygons box = test::box_polygons();
  test::write_test_file(dir / "box.obj", test::to_obj(box));
  test::write_test_file(dir / "box.stl", test::to_stl(box));
  const ImportedScene obj = import_scene(dir / "box.obj");
  EXPECT_EQ(obj.up, Eigen::Vector3d::UnitY());
  // The file's one object is named (`o solid`): a node of that name under the file's root.
  ASSERT_EQ(obj.nodes.size(), 2u);
  EXPECT_EQ(obj.nodes[1].path, "/box/solid");
  ASSERT_EQ(scene_bodies(obj).size(), 1u);
  EXPECT_EQ(obj.meshes[0].triangles.rows(), 12);
  EXPECT_EQ(import_scene(dir / "box.stl").up, Eigen::Vector3d::UnitZ());
}

// OBJ objects are nodes: `o` starts one, each holds a mesh per material its faces use, with its
// own vertices and the file's texture coordinates; and a scene Fissure writes as OBJ reads back
// with a node per part.
TEST(SceneImport, ObjObjectsAreNodesWithAMeshPerMaterial) {
  const fs::path dir = test::fresh_temp_dir("scene-import-obj-objects");
  // Two unit squares side by side (two triangles each) as object "left" (material a, uvs) and
  // object "right" (one triangle each of materials a and b).
  const std::string obj =
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\n"
      "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
      "o left\nusemtl a\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n"
      "o right\nf 2 5 6\nusemtl b\nf 2 6 3\n";
  test::write_test_file(dir / "yard.obj", obj);
  const ImportedScene scene = import_scene(dir / "yard.obj");
  ASSERT_EQ(scene.nodes.size(), 3u);
  EXPECT_EQ(scene.nodes[0].path, "/yard");
  EXPECT_EQ(scene.nodes[1].path, "/yard/left");
  EXPECT_EQ(scene.nodes[2].path, "/yard/right");
  ASSERT_EQ(scene.materials.size(), 2u);
  ASSERT_EQ(scene.nodes[1].meshes.size(), 1u);
  const SceneMesh& left = scene.meshes[static_cast<std::size_t>(scene.nodes[1].meshes[0])];
  EXPECT_EQ(left.vertices.rows(), 4);  // its own four corners, not the file's six
  EXPECT_EQ(left.triangles.rows(), 2);
  ASSERT_EQ(left.uvs.rows(), 4);
  EXPECT_EQ(scene.materials[static_cast<std::size_t>(left.material)].name, "a");
  // The uv of the corner at (1, 1, 0) is the file's (1, 1).
  for (Eigen::Index v = 0; v < 4; ++v)
    if (left.vertices.row(v) == Eigen::RowVector3d(1, 1, 0)) EXPECT_EQ(left.uvs.row(v), Eigen::RowVector2d(1, 1));
  ASSERT_EQ(scene.nodes[2].meshes.size(), 2u);  // materials a and b
  std::vector<std::string> right_materials;
  for (int m : scene.nodes[2].meshes) {
    EXPECT_EQ(scene.meshes[static_cast<std::size_t>(m)].triangles.rows(), 1);
    right_materials.push_back(scene.materials[static_cast<std::size_t>(scene.meshes[static_cast<std::size_t>(m)].material)].name);
  }
  EXPECT_EQ(right_materials, (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(scene_bodies(scene).size(), 2u);

  // Fissure's own OBJ of a two-part scene: a node per part, named as the parts.
  ExportScene two;
  two.materials = {{"stone", Eigen::Vector3d::Constant(0.5), {}}};
  for (const char* name : {"slab_a", "slab_b"}) {
    ExportPart p;
    p.name = name;
    p.vertices = Eigen::MatrixX3d(3, 3);
    p.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0;
    p.triangles = Eigen::MatrixX3i(1, 3);
    p.triangles << 0, 1, 2;
    p.triangle_material = {0};
    two.parts.push_back(p);
  }
  write_scene(dir / "two.obj", two);
  const ImportedScene back = import_scene(dir / "two.obj");
  std::vector<std::string> paths;
  for (const SceneBody& b : scene_bodies(back)) paths.push_back(b.path);
  EXPECT_EQ(paths, (std::vector<std::string>{"/two/slab_a", "/two/slab_b"}));

  // Parts under parts (a fractured scene: bodies, their fragments) keep their paths through OBJ:
  // the object is named by its path, so two bodies' fragment_000 stay two bodies.
  ExportScene nested;
  nested.materials = two.materials;
  nested.parts.push_back({});
  nested.parts[0].name = "street";
  for (const char* body : {"slab_a", "slab_b"}) {
    ExportPart group;
    group.name = body;
    group.parent = 0;
    nested.parts.push_back(group);
    ExportPart fragment = two.parts[0];
    fragment.name = "fragment_000";
    fragment.parent = static_cast<int>(nested.parts.size()) - 1;
    nested.parts.push_back(fragment);
  }
  write_scene(dir / "nested.obj", nested);
  paths.clear();
  for (const SceneBody& b : scene_bodies(import_scene(dir / "nested.obj"))) paths.push_back(b.path);
  EXPECT_EQ(paths, (std::vector<std::string>{"/nested/street/slab_a/fragment_000", "/nested/street/slab_b/fragment_000"}));

  // One named object, as Blender writes a lone cube: the name is kept under the file's root;
  // with no name, the file is the one node.
  test::write_test_file(dir / "nameless.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  const ImportedScene nameless = import_scene(dir / "nameless.obj");
  ASSERT_EQ(nameless.nodes.size(), 1u);
  EXPECT_EQ(nameless.nodes[0].path, "/nameless");
  test::write_test_file(dir / "lone.obj", "o Pillar\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  const ImportedScene lone = import_scene(dir / "lone.obj");
  ASSERT_EQ(scene_bodies(lone).size(), 1u);
  EXPECT_EQ(scene_bodies(lone)[0].path, "/lone/Pillar");
  EXPECT_EQ(lone.meshes[0].name, "Pillar");
}

// An OBJ's materials take their colours and textures from the MTL files its mtllib lines name
// (assimp did; Fissure's reader ignored them, and every material came out grey). A missing
// library is a warning; a corrupt one an error naming the OBJ, the library and the line.
TEST(SceneImport, ObjMaterialsTakeTheirColoursFromTheirLibrary) {
  const fs::path dir = test::fresh_temp_dir("scene-import-mtl");
  const std::string obj = "mtllib look.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nusemtl stone\nf 1 3 2\nf 1 2 4\n"
                          "usemtl moss\nf 1 4 3\nf 2 3 4\n";
  test::write_test_file(dir / "rock.obj", obj);
  test::write_test_file(dir / "look.mtl", "# two\nnewmtl stone\nKa 0 0 0\nKd 0.55 0.45 0.12\nnewmtl moss\nKd 0.1 0.5 0.2\n"
                                          "map_Kd -s 1 1 1 textures/moss.png\n");
  const ImportedScene scene = import_scene(dir / "rock.obj");
  ASSERT_EQ(scene.materials.size(), 2u);
  EXPECT_EQ(scene.materials[0].name, "stone");
  EXPECT_EQ(scene.materials[0].colour, Eigen::Vector3d(0.55, 0.45, 0.12));
  EXPECT_TRUE(scene.materials[0].textures.empty());
  EXPECT_EQ(scene.materials[1].colour, Eigen::Vector3d(0.1, 0.5, 0.2));
  EXPECT_EQ(scene.materials[1].textures, (std::vector<std::string>{"textures/moss.png"}));
  EXPECT_TRUE(scene.warnings.empty());
  EXPECT_EQ(scene_input_files(dir / "rock.obj"), (std::vector<fs::path>{dir / "rock.obj", dir / "look.mtl"}));

  fs::remove(dir / "look.mtl");
  const ImportedScene grey = import_scene(dir / "rock.obj");
  EXPECT_EQ(grey.materials[0].colour, Eigen::Vector3d(0.62, 0.60, 0.56));
  ASSERT_EQ(grey.warnings.size(), 1u);
  EXPECT_NE(grey.warnings[0].find("look.mtl is not beside it"), std::string::npos) << grey.warnings[0];
  EXPECT_EQ(scene_input_files(dir / "rock.obj"), (std::vector<fs::path>{dir / "rock.obj"}));

  test::write_test_file(dir / "look.mtl", "newmtl stone\nKd 0.5 green 0.1\n");
  try {
    (void)import_scene(dir / "rock.obj");
    ADD_FAILURE() << "a corrupt library was read";
  } catch (const IoError& e) {
    EXPECT_EQ(std::string(e.what()).rfind((dir / "rock.obj").string() + ": its material library " + (dir / "look.mtl").string() + ":2: ", 0), 0u)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("green"), std::string::npos) << e.what();
  }
}

// COLLADA's conventions: Z up and the file's unit, converted by assimp at the root node so the
// meshes keep their own frame (here centimetres). Nodes instance one geometry with different
// materials (assimp makes a mesh per primitive and binding); <library_nodes> are instanced; the
// texture reference is kept.
TEST(SceneImport, ColladaFollowsItsUpAxisAndUnit) {
  const fs::path dir = test::fresh_temp_dir("scene-import-dae");
  write_file_atomically(dir / "street.dae", test::collada_street());
  const ImportedScene scene = import_scene(dir / "street.dae");
  EXPECT_EQ(scene.format, "dae");
  EXPECT_EQ(scene.up, Eigen::Vector3d::UnitY()) << "assimp turns Z_UP into +y at the root";
  std::vector<std::string> paths;
  for (const SceneNode& n : scene.nodes) paths.push_back(n.path);
  // Nodes by their name, as a modeller shows them: slab_a's id is n_slab_a (assimp's choice).
  EXPECT_EQ(paths, (std::vector<std::string>{"/Scene", "/Scene/street", "/Scene/street/slab_a", "/Scene/street/slab_b",
                                             "/Scene/street/kerbs", "/Scene/street/kerbs/kerb"}));
  const std::vector<SceneBody> bodies = scene_bodies(scene);
  ASSERT_EQ(bodies.size(), 3u);
  const auto material_of = [&](const SceneBody& b) {
    EXPECT_EQ(b.meshes.size(), 2u) << b.path << ": the <triangles> and the <polylist>";
    return scene.materials[static_cast<std::size_t>(scene.meshes[static_cast<std::size_t>(b.meshes.at(0))].material)];
  };
  EXPECT_EQ(material_of(bodies[0]).name, "concrete");
  EXPECT_EQ(material_of(bodies[0]).textures, std::vector<std::string>{"concrete.png"});
  EXPECT_EQ(material_of(bodies[1]).name, "glass");
  EXPECT_EQ(material_of(bodies[2]).name, "glass");
  // The file's (100, 0, 0) cm: slab_a moves it 2 m along the file's z (up) and the street 1 m
  // along x; slab_b turns it 90° about z; the kerb's matrix moves it 3 m along the file's y. In
  // +y up and metres, those are (2, 2, 0), (1, 0, −1) and (2, 0, −3). Float parsing of the
  // file's decimals: 1e-6 relative.
  const SceneMesh& a = scene.meshes[static_cast<std::size_t>(bodies[0].meshes.at(0))];
  int corner = -1;
  for (int i = 0; i < a.vertices.rows(); ++i) {
    if (a.vertices.row(i).isApprox(Eigen::RowVector3d(100, 0, 0))) corner = i;
  }
  ASSERT_GE(corner, 0) << "the mesh is kept in the file's centimetres";
  const Eigen::Vector3d x = a.vertices.row(corner).transpose();
  EXPECT_TRUE(apply(bodies[0].world, x).isApprox(Eigen::Vector3d(2, 2, 0), 1e-6)) << apply(bodies[0].world, x).transpose();
  EXPECT_TRUE(apply(bodies[1].world, x).isApprox(Eigen::Vector3d(1, 0, -1), 1e-6)) << apply(bodies[1].world, x).transpose();
  EXPECT_TRUE(apply(bodies[2].world, x).isApprox(Eigen::Vector3d(2, 0, -3), 1e-6)) << apply(bodies[2].world, x).transpose();
}

TEST(SceneImport, WrongFilesAreNamed) {
  const fs::path dir = test::fresh_temp_dir("scene-import-bad");
  const auto message = [](const fs::path& p) {
    try {
      import_scene(p);
    } catch (const IoError& e) {
      return std::string(e.what());
    } catch (const InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message(dir / "none.glb").find("none.glb"), std::string::npos);
  write_file_atomically(dir / "scene.3ds", "MM");
  EXPECT_NE(message(dir / "scene.3ds").find("unsupported scene format '.3ds'"), std::string::npos) << message(dir / "scene.3ds");
  write_file_atomically(dir / "empty.dae", "<COLLADA/>");
  EXPECT_NE(message(dir / "empty.dae").find("empty.dae"), std::string::npos) << message(dir / "empty.dae");
  write_file_atomically(dir / "noise.glb", std::string(2000, '\x5a'));
  EXPECT_NE(message(dir / "noise.glb").find("noise.glb"), std::string::npos);
  // A node referencing a mesh the file does not have: assimp's validation or ours names it.
  std::string text = read_file(write_street(dir));
  text.replace(text.find(R"("mesh": 1)"), 9, R"("mesh": 7)");
  write_file_atomically(dir / "dangling.gltf", text);
  const std::string m = message(dir / "dangling.gltf");
  EXPECT_NE(m, "accepted");
  EXPECT_NE(m.find("dangling.gltf"), std::string::npos) << m;
}

}  // namespace
}  // namespace fissure
