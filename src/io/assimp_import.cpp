#include "assimp_import.hpp"

#include "assimp_precheck.hpp"
#include "byte_cursor.hpp"

#include "fissure/base/atomic_file.hpp"

#include "fissure/base/error.hpp"

#include <assimp/Importer.hpp>
#include <assimp/material.h>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <cmath>
#include <limits>
#include <memory>

namespace fissure::io_detail {
namespace {

// "mesh 2 ('Cube')" for messages: 1-based, with the name the modeller gave it.
std::string mesh_label(const aiMesh& mesh, unsigned index) {
  std::string label = "mesh " + std::to_string(index + 1);
  if (mesh.mName.length > 0) label += " ('" + std::string(mesh.mName.C_Str()).substr(0, 60) + "')";
  return label;
}

// The materials and first UV channel of the triangle meshes, as SurfaceAppearance's soup, or
// nothing when the file has neither UVs nor a named material (assimp names the material it adds
// to a file without one "DefaultMaterial").
SurfaceAppearance appearance_of(const aiScene& scene, const SurfaceMesh& surface) {
  SurfaceAppearance a;
  bool has_uvs = false, named = false;
  std::vector<int> material_of_scene_material(scene.mNumMaterials, -1);
  std::vector<int> mesh_material(scene.mNumMeshes, 0);
  a.materials.push_back({"surface"});
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[m];
    if (!(mesh.mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
    has_uvs = has_uvs || (mesh.mTextureCoords[0] != nullptr && mesh.mNumVertices > 0);
    if (mesh.mMaterialIndex >= scene.mNumMaterials || !scene.mMaterials || !scene.mMaterials[mesh.mMaterialIndex]) continue;
    int& index = material_of_scene_material[mesh.mMaterialIndex];
    if (index < 0) {
      const aiMaterial& material = *scene.mMaterials[mesh.mMaterialIndex];
      aiString name;
      std::string text = material.Get(AI_MATKEY_NAME, name) == AI_SUCCESS ? std::string(name.C_Str()) : std::string();
      if (text.empty() || text == AI_DEFAULT_MATERIAL_NAME) {
        index = 0;
      } else {
        named = true;
        SurfaceAppearance::Material entry{text.substr(0, 200)};
        aiColor4D colour;
        if (material.Get(AI_MATKEY_BASE_COLOR, colour) == AI_SUCCESS || material.Get(AI_MATKEY_COLOR_DIFFUSE, colour) == AI_SUCCESS) {
          const Eigen::Vector3d c(colour.r, colour.g, colour.b);
          if (c.allFinite()) entry.colour = c.cwiseMax(0.0).cwiseMin(1.0);
        }
        index = static_cast<int>(a.materials.size());
        a.materials.push_back(entry);
      }
    }
    mesh_material[m] = index;
  }
  if (!has_uvs && !named) return {};
  const Eigen::Index n = surface.faces.rows();
  a.corners.resize(n, 9);
  if (has_uvs) a.uvs.setZero(n, 6);
  a.material.reserve(static_cast<std::size_t>(n));
  Eigen::Index f = 0;
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[m];
    if (!(mesh.mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
    for (unsigned k = 0; k < mesh.mNumFaces; ++k) {
      const aiFace& face = mesh.mFaces[k];
      if (face.mNumIndices != 3) continue;
      for (int i = 0; i < 3; ++i) {
        const unsigned v = face.mIndices[i];
        const aiVector3D& p = mesh.mVertices[v];
        a.corners.row(f).segment<3>(3 * i) << p.x, p.y, p.z;
        if (has_uvs && mesh.mTextureCoords[0]) {
          const aiVector3D& t = mesh.mTextureCoords[0][v];
          // A non-finite UV carries nothing to transfer: 0, as for a mesh without UVs.
          if (std::isfinite(t.x) && std::isfinite(t.y)) a.uvs.row(f).segment<2>(2 * i) << t.x, t.y;
        }
      }
      a.material.push_back(mesh_material[m]);
      ++f;
    }
  }
  a.drop_unused_materials();
  return a;
}

}  // namespace

CheckedAssimpScene read_checked_assimp_scene(const std::filesystem::path& path, const std::string& name, bool flatten) {
  std::map<std::string, std::string> collada_node_names;
  {
    const std::string bytes = read_file(path);
    const std::string ext = lower_ascii(path.extension().string());
    if (ext == ".gltf") precheck_gltf(bytes, name, path.parent_path());
    else if (ext == ".glb") precheck_glb(bytes, name, path.parent_path());
    else if (ext == ".fbx") precheck_fbx(bytes, name);
    else if (ext == ".dae") collada_node_names = precheck_collada(bytes, name);
    else throw IoError(name + ": '" + ext + "' is not read through assimp");
  }
  auto importer = std::make_unique<Assimp::Importer>();
  // Keep triangles only (points and lines bound no volume), and let FBX convert to metres.
  importer->SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  importer->SetPropertyBool(AI_CONFIG_FBX_CONVERT_TO_M, true);
  // No aiProcess_JoinIdenticalVertices: it joins vertices closer than an absolute 1e-5 (in the
  // file's units), which collapses the short, real edges of a fracture surface (a fragment with a
  // 0.5 µm edge came back open) and anything modelled in millimetres. Surface repair welds exact
  // duplicates instead (mesh/surface_repair.hpp).
  unsigned steps = aiProcess_ValidateDataStructure | aiProcess_Triangulate | aiProcess_SortByPType;
  if (flatten) steps |= aiProcess_PreTransformVertices;
  const aiScene* scene = importer->ReadFile(name, steps);
  if (!scene) throw IoError(name + ": cannot import: " + std::string(importer->GetErrorString()));
  if (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) throw IoError(name + ": the file is incomplete or corrupt");
  if (scene->mNumMeshes > 0 && !scene->mMeshes) throw IoError(name + ": corrupt: the scene lists meshes it does not hold");
  if (!scene->mRootNode) throw IoError(name + ": corrupt: the scene has no root node");

  // Check every triangle mesh before anything is copied.
  constexpr auto kMaxIndex = static_cast<std::uint64_t>(std::numeric_limits<int>::max());
  std::uint64_t vertex_count = 0, face_count = 0;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    if (!mesh) throw IoError(name + ": corrupt: mesh " + std::to_string(m + 1) + " is missing");
    if (!(mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
    const std::string label = mesh_label(*mesh, m);
    if ((mesh->mNumVertices > 0 && !mesh->mVertices) || (mesh->mNumFaces > 0 && !mesh->mFaces)) {
      throw IoError(name + ": corrupt: " + label + " has no vertex or face data");
    }
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D& p = mesh->mVertices[v];
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
        throw IoError(name + ": " + label + ": vertex " + std::to_string(v + 1) + " has a non-finite coordinate");
      }
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;
      if (!face.mIndices) throw IoError(name + ": corrupt: " + label + ": face " + std::to_string(f + 1) + " has no indices");
      for (unsigned k = 0; k < 3; ++k) {
        if (face.mIndices[k] >= mesh->mNumVertices) {
          throw IoError(name + ": corrupt: " + label + ": face " + std::to_string(f + 1) + " references vertex " +
                        std::to_string(face.mIndices[k] + 1ull) + ", but the mesh has " + std::to_string(mesh->mNumVertices));
        }
      }
      ++face_count;
    }
    vertex_count += mesh->mNumVertices;
    if (vertex_count > kMaxIndex) throw IoError(name + ": more than " + std::to_string(kMaxIndex) + " vertices");
  }
  if (face_count == 0) throw InvalidInput(name + ": holds no triangles");
  return {std::move(importer), vertex_count, face_count, std::move(collada_node_names)};
}

SurfaceMesh import_with_assimp(const std::filesystem::path& path, const std::string& name) {
  const CheckedAssimpScene checked = read_checked_assimp_scene(path, name, true);
  const aiScene* scene = &checked.scene();
  const std::uint64_t vertex_count = checked.vertices, face_count = checked.triangles;

  SurfaceMesh surface;
  surface.source_name = name;
  surface.vertices.resize(static_cast<Eigen::Index>(vertex_count), 3);
  surface.faces.resize(static_cast<Eigen::Index>(face_count), 3);
  Eigen::Index v0 = 0, fi = 0;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    if (!(mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D& p = mesh->mVertices[v];
      surface.vertices.row(v0 + v) << p.x, p.y, p.z;
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;
      surface.faces.row(fi++) << static_cast<int>(v0 + face.mIndices[0]), static_cast<int>(v0 + face.mIndices[1]),
          static_cast<int>(v0 + face.mIndices[2]);
    }
    v0 += mesh->mNumVertices;
  }
  surface.appearance = appearance_of(*scene, surface);
  return surface;
}

}  // namespace fissure::io_detail
