#pragma once
/// Writes a scene of separate parts (the fragments of a fractured body) for the programs artists
/// open them in: binary glTF (.glb), glTF with its buffer embedded (.gltf), Wavefront OBJ with a
/// .mtl beside it, and PLY. Fissure writes these itself: assimp 5.2.5's glTF2 exporter drops
/// node extras, its OBJ exporter splits a part with two materials into two open groups, and its
/// binary FBX is unreadable by assimp and Blender alike (assimp issue 4686), so FBX is left out.
///
/// What each format keeps:
/// - GLB, glTF: one node per part (its name, its parent, its translation or, when it rotates or
///   scales, its matrix, its extras object); one mesh per
///   part with one primitive per material it uses, the primitives sharing one vertex array, so
///   a closed part stays one closed surface; positions and UVs as float32, indices uint32; no
///   normals (clients shade flat, which a fracture surface is); the scene's extras object.
///   read_fissure_gltf() (gltf_reader.hpp) reads such a file back exactly.
/// - OBJ: one `o NAME` per part with triangles, positions in the scene's frame, `vt` UVs, `usemtl` switching per material
///   inside the object, and `mtllib` naming NAME.mtl, written beside it. Extras become comments.
/// - PLY: one binary little-endian mesh of positions in the scene's frame, with per-vertex `part` (the part's
///   index) and u, v, and per-face `material` (index into the scene's materials).
/// Every file is written atomically (base/atomic_file.hpp); the same scene gives the same bytes.

#include <Eigen/Core>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace fissure {

/// One node: its transform in its parent's frame (linear · x + translation) and, optionally, its
/// geometry in its own frame. A part with no triangles is an empty node (a group).
struct ExportPart {
  std::string name;
  int parent = -1;             ///< the parent part's index (an earlier part), or -1 at the root
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();  ///< the node's origin in its parent's frame, m
  Eigen::Matrix3d linear = Eigen::Matrix3d::Identity();   ///< its rotation and scale there
  Eigen::MatrixX3d vertices;   ///< in the node's frame, m
  Eigen::MatrixX2d uvs;        ///< one per vertex, or none (glTF then has no TEXCOORD_0)
  Eigen::MatrixX3i triangles;  ///< counter-clockwise seen from outside
  std::vector<int> triangle_material;  ///< per triangle, an index into ExportScene::materials
  std::string extras_json = "{}";      ///< a JSON object: glTF node extras, OBJ comments
};

struct ExportMaterial {
  std::string name;
  Eigen::Vector3d colour = Eigen::Vector3d::Constant(0.8);  ///< linear RGB base colour
  /// The base-colour texture, a file reference as the scene gave it (relative to the file written);
  /// empty for none. glTF: an image by URI; MTL: map_Kd.
  std::string texture;
};

struct ExportScene {
  std::vector<ExportMaterial> materials;
  std::vector<ExportPart> parts;
  std::string extras_json = "{}";  ///< a JSON object: glTF scene extras (other formats drop it)
  /// The up axis of the parts' frame (unit). Each format is written in its own convention:
  /// glTF and OBJ +Y up (as Blender reads and writes them), PLY +Z up (as CAD and scanners
  /// write it, and as Fissure reads it). OBJ and PLY turn the positions they write by the
  /// shortest rotation from `up` to theirs; glTF keeps the parts as they are under one added
  /// root node, named `frame_name`, that holds the rotation, so node extras given in the parts'
  /// frame (a fragment's centre of mass) stay true in the frame of their parent.
  Eigen::Vector3d up = Eigen::Vector3d::UnitY();
  std::string frame_name = "body";
};

/// The shortest rotation taking the unit vector `from` to the unit vector `to` (a half turn about
/// an axis orthogonal to both when they are opposite); the identity exactly when they are equal.
Eigen::Matrix3d turn_between(const Eigen::Vector3d& from, const Eigen::Vector3d& to);

/// Part `k`'s frame → the scene's frame: the product of its ancestors' transforms and its own.
Eigen::Matrix4d part_to_scene(const ExportScene& scene, std::size_t k);

enum class SceneFormat { Glb, Gltf, Obj, Ply };

/// The formats write_scene() writes, for messages and help texts.
inline constexpr const char* kSceneFormats = ".glb, .gltf, .obj or .ply";

/// The format of `path` by its extension (case-insensitive), or nothing.
std::optional<SceneFormat> scene_format_of(const std::filesystem::path& path);

/// Throws IoError naming the file when `path` has no scene extension or could not be written
/// (check_output_path), for commands to call before a long computation.
void check_scene_output_path(const std::filesystem::path& path);

/// The files write_scene(path, …) writes: `path`, and for OBJ its .mtl beside it.
std::vector<std::filesystem::path> scene_output_files(const std::filesystem::path& path);

/// The bytes of `scene` in `format`, turned to the format's up axis (ExportScene::up). For OBJ,
/// the .obj file's; `mtl_name` is the name its `mtllib` line gives. Throws InvalidInput naming the part and triangle when a triangle indexes
/// a vertex or material that does not exist, or a value is not finite.
std::string encode_scene(const ExportScene& scene, SceneFormat format, const std::string& mtl_name = {});

/// The .mtl file of an OBJ export.
std::string encode_obj_materials(const ExportScene& scene);

/// Writes `scene` to `path` in the format of its extension (and, for OBJ, the .mtl beside it).
/// Throws IoError naming the file when it cannot be written; nothing is left half-written.
void write_scene(const std::filesystem::path& path, const ExportScene& scene);

}  // namespace fissure
