#include "assimp_import.hpp"

#include "assimp_precheck.hpp"
#include "byte_cursor.hpp"

#include "fissure/base/atomic_file.hpp"

#include "fissure/base/error.hpp"

#include <assimp/Importer.hpp>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <cmath>
#include <limits>

namespace fissure::io_detail {
namespace {

// "mesh 2 ('Cube')" for messages: 1-based, with the name the modeller gave it.
std::string mesh_label(const aiMesh& mesh, unsigned index) {
  std::string label = "mesh " + std::to_string(index + 1);
  if (mesh.mName.length > 0) label += " ('" + std::string(mesh.mName.C_Str()).substr(0, 60) + "')";
  return label;
}

}  // namespace

SurfaceMesh import_with_assimp(const std::filesystem::path& path, const std::string& name) {
  {
    const std::string bytes = read_file(path);
    const std::string ext = lower_ascii(path.extension().string());
    if (ext == ".gltf") precheck_gltf(bytes, name, path.parent_path());
    else if (ext == ".glb") precheck_glb(bytes, name, path.parent_path());
    else if (ext == ".fbx") precheck_fbx(bytes, name);
    else throw IoError(name + ": '" + ext + "' is not read through assimp");
  }
  Assimp::Importer importer;
  // Keep triangles only (points and lines bound no volume), and let FBX convert to metres.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  importer.SetPropertyBool(AI_CONFIG_FBX_CONVERT_TO_M, true);
  const aiScene* scene = importer.ReadFile(name, aiProcess_ValidateDataStructure | aiProcess_Triangulate |
                                                     aiProcess_JoinIdenticalVertices | aiProcess_PreTransformVertices |
                                                     aiProcess_SortByPType);
  if (!scene) throw IoError(name + ": cannot import: " + std::string(importer.GetErrorString()));
  if (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) throw IoError(name + ": the file is incomplete or corrupt");
  if (scene->mNumMeshes > 0 && !scene->mMeshes) throw IoError(name + ": corrupt: the scene lists meshes it does not hold");

  // Check every triangle mesh before copying anything.
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
  return surface;
}

}  // namespace fissure::io_detail
