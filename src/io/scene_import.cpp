#include "fissure/io/scene_import.hpp"

#include "assimp_import.hpp"
#include "byte_cursor.hpp"
#include "surface_readers.hpp"

#include "fissure/base/atomic_file.hpp"
#include "fissure/base/error.hpp"
#include "fissure/base/memory.hpp"

#include <assimp/material.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>
#include <utility>

namespace fissure {
namespace fs = std::filesystem;

namespace {

std::string clipped(const aiString& s) { return std::string(s.C_Str()).substr(0, 200); }

SceneMaterial material_of(const aiMaterial& material) {
  SceneMaterial m;
  aiString name;
  m.name = material.Get(AI_MATKEY_NAME, name) == AI_SUCCESS ? clipped(name) : std::string();
  aiColor4D colour;
  if (material.Get(AI_MATKEY_BASE_COLOR, colour) == AI_SUCCESS || material.Get(AI_MATKEY_COLOR_DIFFUSE, colour) == AI_SUCCESS) {
    const Eigen::Vector3d c(colour.r, colour.g, colour.b);
    if (c.allFinite()) m.colour = c.cwiseMax(0.0).cwiseMin(1.0);
  }
  // The references a re-export must keep, as written (a glTF's embedded image is "*N").
  for (const aiTextureType type : {aiTextureType_BASE_COLOR, aiTextureType_DIFFUSE, aiTextureType_NORMALS,
                                   aiTextureType_METALNESS, aiTextureType_DIFFUSE_ROUGHNESS, aiTextureType_AMBIENT_OCCLUSION,
                                   aiTextureType_EMISSIVE}) {
    for (unsigned i = 0; i < material.GetTextureCount(type); ++i) {
      aiString path;
      if (material.GetTexture(type, i, &path) != AI_SUCCESS) continue;
      const std::string text = std::string(path.C_Str()).substr(0, 4096);
      bool seen = false;
      for (const std::string& t : m.textures) seen = seen || t == text;
      if (!seen && !text.empty()) m.textures.push_back(text);
    }
  }
  return m;
}

SceneMesh mesh_of(const aiMesh& mesh, unsigned index) {
  SceneMesh out;
  out.name = mesh.mName.length > 0 ? clipped(mesh.mName) : "mesh " + std::to_string(index + 1);
  out.vertices.resize(mesh.mNumVertices, 3);
  for (unsigned v = 0; v < mesh.mNumVertices; ++v) out.vertices.row(v) << mesh.mVertices[v].x, mesh.mVertices[v].y, mesh.mVertices[v].z;
  if (mesh.mTextureCoords[0]) {
    out.uvs.resize(mesh.mNumVertices, 2);
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D& t = mesh.mTextureCoords[0][v];
      // A non-finite UV carries nothing: 0, as for a mesh without UVs (surface import does the same).
      out.uvs.row(v) << (std::isfinite(t.x) ? t.x : 0.0), (std::isfinite(t.y) ? t.y : 0.0);
    }
  }
  Eigen::Index triangles = 0;
  for (unsigned f = 0; f < mesh.mNumFaces; ++f) triangles += mesh.mFaces[f].mNumIndices == 3 ? 1 : 0;
  out.triangles.resize(triangles, 3);
  Eigen::Index t = 0;
  for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
    const aiFace& face = mesh.mFaces[f];
    if (face.mNumIndices != 3) continue;
    out.triangles.row(t++) << static_cast<int>(face.mIndices[0]), static_cast<int>(face.mIndices[1]), static_cast<int>(face.mIndices[2]);
  }
  out.material = static_cast<int>(mesh.mMaterialIndex);
  return out;
}

// FBX names its up axis in the scene's metadata (0 x, 1 y, 2 z, and a sign); glTF is +Y.
Eigen::Vector3d up_of(const aiScene& scene, const std::string& format) {
  if (format != "fbx" || !scene.mMetaData) return Eigen::Vector3d::UnitY();
  int axis = 1, sign = 1;
  scene.mMetaData->Get("UpAxis", axis);
  scene.mMetaData->Get("UpAxisSign", sign);
  if (axis < 0 || axis > 2) axis = 1;
  Eigen::Vector3d up = Eigen::Vector3d::Zero();
  up[axis] = sign < 0 ? -1.0 : 1.0;
  return up;
}

// Depth first, parents before children; sibling names made unique for paths.
void add_nodes(const aiNode& node, int parent, const std::vector<int>& mesh_index, ImportedScene& scene,
               const std::string& name, int depth) {
  // assimp's own importers bound nesting (assimp_precheck.hpp); a scene graph deeper than this
  // is not a scene an artist made.
  if (depth > 1000) throw IoError(name + ": the node hierarchy is more than 1000 levels deep");
  SceneNode out;
  out.name = node.mName.length > 0 ? clipped(node.mName) : "node";
  out.parent = parent;
  const aiMatrix4x4& m = node.mTransformation;
  for (unsigned r = 0; r < 4; ++r)
    for (unsigned c = 0; c < 4; ++c) out.local(r, c) = m[r][c];
  if (!out.local.allFinite()) throw IoError(name + ": node '" + out.name + "' has a non-finite transform");
  for (unsigned k = 0; k < node.mNumMeshes; ++k) {
    if (!node.mMeshes) throw IoError(name + ": corrupt: node '" + out.name + "' lists meshes it does not hold");
    const unsigned mesh = node.mMeshes[k];
    if (mesh >= mesh_index.size()) {
      throw IoError(name + ": corrupt: node '" + out.name + "' references mesh " + std::to_string(mesh + 1ull) + " of " +
                    std::to_string(mesh_index.size()));
    }
    if (mesh_index[mesh] >= 0) out.meshes.push_back(mesh_index[mesh]);
  }
  const int self = static_cast<int>(scene.nodes.size());
  scene.nodes.push_back(std::move(out));
  if (node.mNumChildren > 0 && !node.mChildren) throw IoError(name + ": corrupt: a node lists children it does not hold");
  for (unsigned c = 0; c < node.mNumChildren; ++c) {
    if (!node.mChildren[c]) throw IoError(name + ": corrupt: a child node is missing");
    add_nodes(*node.mChildren[c], self, mesh_index, scene, name, depth + 1);
  }
}

void assign_paths(ImportedScene& scene) {
  std::vector<std::map<std::string, int>> seen(scene.nodes.size());
  for (std::size_t i = 0; i < scene.nodes.size(); ++i) {
    SceneNode& n = scene.nodes[i];
    const std::string parent_path = n.parent < 0 ? std::string() : scene.nodes[static_cast<std::size_t>(n.parent)].path;
    std::string leaf = n.name;
    if (n.parent >= 0) {
      const int count = ++seen[static_cast<std::size_t>(n.parent)][n.name];
      if (count > 1) leaf += "#" + std::to_string(count);
    }
    n.path = parent_path + "/" + leaf;
  }
}

// assimp adds a material to every glTF (for primitives without one), unnamed or named
// "DefaultMaterial": it is not the file's, so it goes unless a mesh uses it. Other unnamed
// materials are named by their place ("material 2").
void drop_assimp_default_material(ImportedScene& scene) {
  std::vector<int> used(scene.materials.size(), 0);
  for (const SceneMesh& m : scene.meshes)
    if (m.material >= 0) used[static_cast<std::size_t>(m.material)] = 1;
  std::vector<int> remap(scene.materials.size(), -1);
  std::vector<SceneMaterial> kept;
  for (std::size_t i = 0; i < scene.materials.size(); ++i) {
    const std::string& name = scene.materials[i].name;
    if (!used[i] && (name.empty() || name == AI_DEFAULT_MATERIAL_NAME)) continue;
    remap[i] = static_cast<int>(kept.size());
    kept.push_back(std::move(scene.materials[i]));
    if (kept.back().name.empty()) kept.back().name = "material " + std::to_string(kept.size());
  }
  scene.materials = std::move(kept);
  for (SceneMesh& m : scene.meshes)
    if (m.material >= 0) m.material = remap[static_cast<std::size_t>(m.material)];
}

ImportedScene import_with_assimp(const fs::path& path, const std::string& format) {
  const std::string name = path.string();
  const io_detail::CheckedAssimpScene checked = io_detail::read_checked_assimp_scene(path, name, false);
  const aiScene& scene = checked.scene();
  ImportedScene out;
  out.source = name;
  out.format = format;
  out.up = up_of(scene, format);
  for (unsigned m = 0; m < scene.mNumMaterials; ++m) {
    if (!scene.mMaterials || !scene.mMaterials[m]) throw IoError(name + ": corrupt: material " + std::to_string(m + 1) + " is missing");
    out.materials.push_back(material_of(*scene.mMaterials[m]));
  }
  std::vector<int> mesh_index(scene.mNumMeshes, -1);
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[m];
    if (!(mesh.mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;  // points and lines bound no volume
    SceneMesh converted = mesh_of(mesh, m);
    if (converted.material >= static_cast<int>(out.materials.size())) converted.material = -1;
    mesh_index[m] = static_cast<int>(out.meshes.size());
    out.meshes.push_back(std::move(converted));
  }
  drop_assimp_default_material(out);
  add_nodes(*scene.mRootNode, -1, mesh_index, out, name, 0);
  // COLLADA nodes by the name a modeller shows (Blender's outliner), not assimp's id.
  for (SceneNode& node : out.nodes) {
    const auto named = checked.collada_node_names.find(node.name);
    if (named != checked.collada_node_names.end()) node.name = named->second;
  }
  assign_paths(out);
  return out;
}

// The simple formats: one node (named after the file) holding the whole surface as one mesh.
ImportedScene import_simple(const fs::path& path, const std::string& format) {
  const SurfaceMesh surface = io_detail::read_surface_file(path);
  ImportedScene out;
  out.source = path.string();
  out.format = format;
  // STL, PLY and OFF come mostly from CAD and scanners, +Z up.
  out.up = Eigen::Vector3d::UnitZ();
  SceneMesh mesh;
  mesh.name = path.stem().string();
  mesh.vertices = surface.vertices;
  mesh.triangles = surface.faces;
  for (const SurfaceAppearance::Material& m : surface.appearance.materials) {
    if (m.name.empty()) continue;
    SceneMaterial material;
    material.name = m.name;
    material.colour = m.colour;
    out.materials.push_back(material);
  }
  if (!out.materials.empty()) mesh.material = 0;
  out.meshes.push_back(std::move(mesh));
  SceneNode node;
  node.name = path.stem().string();
  node.meshes = {0};
  out.nodes.push_back(std::move(node));
  assign_paths(out);
  return out;
}

// OBJ: a node per object (`o NAME`, in the order of their first faces) under a root named after
// the file, each holding one mesh per material its faces use (as assimp splits glTF and FBX
// meshes), with per-vertex texture coordinates when the file has them. A file with no `o`
// names is one node named after the file, as the other simple formats; a file of one named object
// keeps the name (Blender writes `o Cube` for a lone cube: the body is /file/Cube). OBJ has no
// hierarchy and no transforms: every node's transform is the identity.
ImportedScene import_obj(const fs::path& path) {
  const std::string name = path.string();
  io_detail::check_input_file(path);
  io_detail::ObjObjects objects;
  const std::string bytes = io_detail::read_input_bytes(path, name);
  SurfaceMesh surface = io_detail::read_obj(bytes, name, &objects);
  ImportedScene out;
  const std::map<std::string, std::string> textures = io_detail::apply_material_libraries(path, bytes, surface.appearance, &out.warnings);
  const SurfaceAppearance& look = surface.appearance;
  out.source = name;
  out.format = "obj";
  out.up = Eigen::Vector3d::UnitY();  // as Blender writes OBJ
  std::vector<int> scene_material(look.materials.size(), -1);
  for (std::size_t m = 0; m < look.materials.size(); ++m) {
    if (look.materials[m].name.empty()) continue;
    scene_material[m] = static_cast<int>(out.materials.size());
    const auto texture = textures.find(look.materials[m].name);
    out.materials.push_back({look.materials[m].name, look.materials[m].colour,
                             texture == textures.end() ? std::vector<std::string>{} : std::vector<std::string>{texture->second}});
  }
  const Eigen::Index triangles = surface.faces.rows();
  const auto material_of = [&](Eigen::Index t) {
    return look.material.empty() ? -1 : scene_material[static_cast<std::size_t>(look.material[static_cast<std::size_t>(t)])];
  };
  // Objects in the order of their first faces; per object, its materials in the order of first use.
  std::vector<int> object_order;
  std::map<int, std::vector<int>> materials_of;
  for (Eigen::Index t = 0; t < triangles; ++t) {
    const int o = objects.triangle_object[static_cast<std::size_t>(t)];
    if (!materials_of.count(o)) object_order.push_back(o);
    std::vector<int>& used = materials_of[o];
    if (std::find(used.begin(), used.end(), material_of(t)) == used.end()) used.push_back(material_of(t));
  }
  const bool one_node = object_order.size() == 1 && objects.names[static_cast<std::size_t>(object_order[0])].empty();
  const std::string stem = path.stem().string();
  SceneNode root;
  root.name = stem;
  out.nodes.push_back(root);
  const bool has_uvs = look.uvs.rows() > 0;
  // An object named a/b/c (as Fissure writes the fragments of a scene) is node c under b under
  // a, the intermediate nodes shared; empty segments are dropped.
  std::map<std::string, int> node_of_path{{"", 0}};
  const auto node_for = [&](const std::string& name) {
    std::string path;
    int node = 0;
    for (std::size_t begin = 0; begin <= name.size();) {
      const std::size_t end = std::min(name.find('/', begin), name.size());
      if (end > begin) {
        const std::string segment = name.substr(begin, end - begin);
        path += "/" + segment;
        const auto [it, inserted] = node_of_path.try_emplace(path, static_cast<int>(out.nodes.size()));
        if (inserted) {
          SceneNode child;
          child.name = segment;
          child.parent = node;
          out.nodes.push_back(child);
        }
        node = it->second;
      }
      begin = end + 1;
    }
    if (node == 0) {  // a name of slashes only, or none: a node named after the file
      SceneNode child;
      child.name = stem;
      child.parent = 0;
      node = static_cast<int>(out.nodes.size());
      out.nodes.push_back(child);
    }
    return node;
  };
  for (const int o : object_order) {
    const int node = one_node ? 0 : node_for(objects.names[static_cast<std::size_t>(o)]);
    const std::vector<int>& used = materials_of[o];
    for (const int material : used) {
      // The mesh: this object's triangles of this material, its vertices renumbered; a vertex
      // used with two texture coordinates becomes two vertices.
      SceneMesh mesh;
      mesh.name = out.nodes[static_cast<std::size_t>(node)].name;
      if (used.size() > 1 && material >= 0) mesh.name += "-" + out.materials[static_cast<std::size_t>(material)].name;
      mesh.material = material;
      std::map<std::tuple<int, double, double>, int> index;
      std::vector<Eigen::Vector3d> vertices;
      std::vector<Eigen::Vector2d> uvs;
      std::vector<Eigen::Vector3i> faces;
      for (Eigen::Index t = 0; t < triangles; ++t) {
        if (objects.triangle_object[static_cast<std::size_t>(t)] != o || material_of(t) != material) continue;
        Eigen::Vector3i face;
        for (int k = 0; k < 3; ++k) {
          const int v = surface.faces(t, k);
          const Eigen::Vector2d uv = has_uvs ? Eigen::Vector2d(look.uvs(t, 2 * k), look.uvs(t, 2 * k + 1)) : Eigen::Vector2d::Zero();
          const auto [it, inserted] = index.try_emplace({v, uv.x(), uv.y()}, static_cast<int>(vertices.size()));
          if (inserted) {
            vertices.push_back(surface.vertices.row(v).transpose());
            uvs.push_back(uv);
          }
          face[k] = it->second;
        }
        faces.push_back(face);
      }
      mesh.vertices.resize(static_cast<Eigen::Index>(vertices.size()), 3);
      for (std::size_t v = 0; v < vertices.size(); ++v) mesh.vertices.row(static_cast<Eigen::Index>(v)) = vertices[v].transpose();
      if (has_uvs) {
        mesh.uvs.resize(static_cast<Eigen::Index>(uvs.size()), 2);
        for (std::size_t v = 0; v < uvs.size(); ++v) mesh.uvs.row(static_cast<Eigen::Index>(v)) = uvs[v].transpose();
      }
      mesh.triangles.resize(static_cast<Eigen::Index>(faces.size()), 3);
      for (std::size_t f = 0; f < faces.size(); ++f) mesh.triangles.row(static_cast<Eigen::Index>(f)) = faces[f].transpose();
      out.nodes[static_cast<std::size_t>(node)].meshes.push_back(static_cast<int>(out.meshes.size()));
      out.meshes.push_back(std::move(mesh));
    }
  }
  assign_paths(out);
  return out;
}

}  // namespace

ImportedScene import_scene(const fs::path& path) {
  io_detail::check_input_file(path);
  const std::string ext = io_detail::lower_ascii(path.extension().string());
  const std::string format = ext.empty() ? std::string() : ext.substr(1);
  if (format == "gltf" || format == "glb" || format == "fbx" || format == "dae") return import_with_assimp(path, format);
  if (format == "obj") return import_obj(path);
  if (format == "ply" || format == "stl" || format == "off") return import_simple(path, format);
  throw IoError(path.string() + ": unsupported scene format '" + ext.substr(0, 20) +
                "' (Fissure reads glTF, GLB, FBX, COLLADA (.dae), OBJ, PLY, STL and OFF scenes)");
}

std::vector<fs::path> scene_input_files(const fs::path& path) {
  std::vector<fs::path> files{path};
  std::error_code ec;
  if (io_detail::lower_ascii(path.extension().string()) != ".obj" || !fs::is_regular_file(path, ec)) return files;
  try {
    for (const std::string& library : io_detail::obj_material_libraries(io_detail::read_input_bytes(path, path.string()), path.string())) {
      const fs::path file = path.parent_path() / library;
      if (fs::exists(file, ec)) files.push_back(file);
    }
  } catch (const Error&) {
    // An unreadable scene is reported by import_scene, with its reason.
  }
  return files;
}

std::vector<SceneBody> scene_bodies(const ImportedScene& scene) {
  std::vector<Eigen::Matrix4d> world(scene.nodes.size());
  std::vector<SceneBody> bodies;
  for (std::size_t i = 0; i < scene.nodes.size(); ++i) {
    const SceneNode& n = scene.nodes[i];
    world[i] = n.parent < 0 ? n.local : Eigen::Matrix4d(world[static_cast<std::size_t>(n.parent)] * n.local);
    if (n.meshes.empty()) continue;
    SceneBody b;
    b.node = static_cast<int>(i);
    b.meshes = n.meshes;
    b.world = world[i];
    b.path = n.path;
    bodies.push_back(std::move(b));
  }
  return bodies;
}

}  // namespace fissure
