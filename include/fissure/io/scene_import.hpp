#pragma once
/// Scene import (issue 13): a file's node hierarchy, transforms, mesh instances, scene material
/// names and texture references, for the scene module to find its bodies in. glTF, GLB and FBX
/// through assimp (checked as import_surface() checks them: surface_import.hpp); OBJ, PLY, STL and
/// OFF, which have no hierarchy, through Fissure's own readers: an OBJ of several objects (`o`)
/// as a root named after the file with a node per object, holding a mesh per material; any
/// other file as one node holding one mesh.
///
/// A **body** is a node instance of its mesh: two nodes sharing one mesh are two bodies (they break
/// differently). Importers split a mesh by material (a glTF mesh's primitives, an FBX model's
/// materials become several assimp meshes on one node), so a node's meshes together are one body. Geometry stays in each mesh's own
/// coordinates; a body's world transform is the product of its node's ancestors' local
/// transforms. The up axis and unit follow the format's convention (glTF: +Y, metres; FBX:
/// converted to metres, its UpAxis setting; OBJ, PLY, STL, OFF: +Y as Blender writes OBJ, +Z as
/// STL and PLY usually are, metres) and can be overridden by the caller.
#include <Eigen/Core>

#include <filesystem>
#include <string>
#include <vector>

namespace fissure {

struct SceneNode {
  std::string name;             ///< as in the file (made unique among siblings, see path)
  int parent = -1;              ///< index into ImportedScene::nodes; -1 for the root
  Eigen::Matrix4d local = Eigen::Matrix4d::Identity();  ///< to the parent's frame, m
  std::vector<int> meshes;      ///< indices into ImportedScene::meshes
  /// "/root/street/slab_03": the names from the root, a sibling's repeated name suffixed "#2",
  /// "#3"… so every node has its own path (seeds and assignments use it).
  std::string path;
};

struct SceneMesh {
  std::string name;
  Eigen::MatrixX3d vertices;    ///< the mesh's own frame, m
  Eigen::MatrixX3i triangles;
  Eigen::MatrixX2d uvs;         ///< one per vertex, or empty
  int material = -1;            ///< index into ImportedScene::materials, or -1
};

struct SceneMaterial {
  std::string name;
  Eigen::Vector3d colour = Eigen::Vector3d::Constant(0.8);  ///< linear RGB base colour
  std::vector<std::string> textures;  ///< texture references as the file gives them (paths or "*0")
};

struct ImportedScene {
  std::string source;           ///< the file, for messages
  std::string format;           ///< "gltf", "glb", "fbx", "obj", "ply", "stl", "off"
  Eigen::Vector3d up = Eigen::Vector3d::UnitY();  ///< the format's up axis (see above)
  std::vector<SceneNode> nodes; ///< parents before children; nodes[0] is the root
  std::vector<SceneMesh> meshes;
  std::vector<SceneMaterial> materials;
  /// What was read but could not be used whole (an OBJ's missing material library), for the
  /// commands to print; the scene is still valid.
  std::vector<std::string> warnings;
};

/// One node instance of its meshes (one surface, each part with its material).
struct SceneBody {
  int node = -1;
  std::vector<int> meshes;      ///< the node's, in order: indices into ImportedScene::meshes
  Eigen::Matrix4d world = Eigen::Matrix4d::Identity();  ///< mesh frame → world, m
  std::string path;             ///< the node's path
};

/// Reads `path`. Throws IoError naming the file when it is missing, corrupt or of a format not
/// listed above, and InvalidInput when it holds no triangles (the messages of import_surface()).
ImportedScene import_scene(const std::filesystem::path& path);

/// The files import_scene(path) reads: `path`, and for an OBJ the material libraries its
/// mtllib lines name that exist beside it, so a command can refuse to write over any of them.
std::vector<std::filesystem::path> scene_input_files(const std::filesystem::path& path);

/// Every body of the scene (every node holding a mesh), in node order.
std::vector<SceneBody> scene_bodies(const ImportedScene& scene);

}  // namespace fissure
