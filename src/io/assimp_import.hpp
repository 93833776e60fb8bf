#pragma once
// Private to io: the formats Fissure reads through assimp 5.2.5 (glTF, GLB, FBX), with what
// assimp returns checked before it is trusted.
//
// assimp runs aiProcess_ValidateDataStructure, and then every mesh is checked again here: null
// arrays, indices out of range, non-finite vertices and counts that overflow an int are refused
// with IoError naming the file and the mesh, so a corrupt file can never become an out-of-bounds
// read in Fissure.

#include "fissure/mesh/surface_mesh.hpp"

#include <assimp/Importer.hpp>
#include <assimp/scene.h>

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <string>

namespace fissure::io_detail {

/// Every mesh of the file's scene, the file first checked by assimp_precheck.hpp, with node
/// transforms applied, triangulated (points and lines dropped); FBX converted to metres. Not yet
/// repaired. Throws IoError naming `name` when the file is corrupt, InvalidInput when it holds
/// no triangles.
/// The file's scene read by assimp, after the prechecks, with every triangle mesh's arrays
/// checked: vertices finite, indices in range, a root node. `flatten`: node transforms applied to
/// the vertices (one mesh list, no hierarchy).
struct CheckedAssimpScene {
  std::unique_ptr<Assimp::Importer> importer;  ///< owns the scene
  std::uint64_t vertices = 0, triangles = 0;   ///< over the triangle meshes
  /// COLLADA: each <node>'s name attribute by its id, where they differ (assimp names nodes by
  /// id, a modeller shows the name).
  std::map<std::string, std::string> collada_node_names;
  const aiScene& scene() const { return *importer->GetScene(); }
};
/// Throws IoError naming `name` when the file is corrupt, InvalidInput when it holds no triangles.
CheckedAssimpScene read_checked_assimp_scene(const std::filesystem::path& path, const std::string& name, bool flatten);

SurfaceMesh import_with_assimp(const std::filesystem::path& path, const std::string& name);

}  // namespace fissure::io_detail
