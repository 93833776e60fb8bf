#include "fissure/io/surface_import.hpp"

#include "fissure/base/atomic_file.hpp"
#include "fissure/base/error.hpp"
#include "fissure/mesh/tile.hpp"

#include <assimp/Importer.hpp>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

namespace fissure {
namespace fs = std::filesystem;

SurfaceMesh import_surface(const fs::path& path, SurfaceRepairReport& report, const SurfaceRepairOptions& options) {
  const std::string name = path.string();
  require_nonempty_file(path);

  Assimp::Importer importer;
  // Keep triangles only (points and lines bound no volume), and let FBX convert to metres.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  importer.SetPropertyBool(AI_CONFIG_FBX_CONVERT_TO_M, true);
  const aiScene* scene = importer.ReadFile(
      name, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_PreTransformVertices |
                aiProcess_SortByPType);
  if (!scene) {
    throw IoError(name + ": cannot import: " + std::string(importer.GetErrorString()));
  }
  if (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) throw IoError(name + ": the file is incomplete or corrupt");

  SurfaceMesh surface;
  surface.source_name = name;
  Eigen::Index vertex_count = 0, face_count = 0;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    if (!(mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
    vertex_count += mesh->mNumVertices;
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) face_count += mesh->mFaces[f].mNumIndices == 3;
  }
  if (face_count == 0) throw InvalidInput(name + ": holds no triangles");
  surface.vertices.resize(vertex_count, 3);
  surface.faces.resize(face_count, 3);
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
  return repair_surface(surface, report, options);
}

SurfaceMesh load_surface_input(const std::string& input, SurfaceRepairReport& report) {
  if (is_tile_spec(input)) return make_tile_surface(parse_tile_spec(input));
  return import_surface(input, report);
}

}  // namespace fissure
