#pragma once
/// Whether a scene's body can be fractured (issue 13): a body is fracturable when its mesh is
/// closed, or safely repaired (duplicate vertices merged, degenerate faces dropped, orientation
/// made consistent: mesh/surface_repair.hpp); one that is not (open, non-manifold,
/// self-intersecting) is reported with the reason and left untouched by a scene fracture.
#include "fissure/io/scene_import.hpp"
#include "fissure/mesh/surface_mesh.hpp"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace fissure {

struct SceneBodyCheck {
  bool fracturable = false;
  std::string reason;                ///< why not, when not fracturable ("open: 12 border edges")
  /// What was repaired, when fracturable. Vertices welded where a file splits them at UV and
  /// material seams are not listed: that is how textured meshes are stored, not a defect.
  std::vector<std::string> repairs;
  /// The body in world coordinates (its node's world transform applied), its meshes joined,
  /// repaired when fracturable, as read otherwise. source_name: "SCENE:/node/path". Its
  /// appearance holds the meshes' materials and UVs per triangle, for the fragments' outer faces.
  SurfaceMesh world;
  /// Per material of world.appearance, the scene material's index (-1: the mesh named none).
  std::vector<int> scene_materials;
  Eigen::Vector3d extent = Eigen::Vector3d::Zero();  ///< world bounding-box size, m
  double volume = 0.0;               ///< enclosed volume, m³ (0 when not fracturable)
};

/// Checks body `body` of `scene`. Never throws for a bad mesh (that is the reason); throws
/// InvalidInput only for a body that does not belong to the scene.
SceneBodyCheck check_scene_body(const ImportedScene& scene, const SceneBody& body);

}  // namespace fissure
