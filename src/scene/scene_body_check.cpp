#include "fissure/scene/scene_body_check.hpp"

#include "fissure/base/error.hpp"
#include "fissure/mesh/surface_repair.hpp"

#include <algorithm>
#include <cmath>

namespace fissure {

SceneBodyCheck check_scene_body(const ImportedScene& scene, const SceneBody& body) {
  Eigen::Index vertices = 0, triangles = 0;
  for (int m : body.meshes) {
    if (m < 0 || static_cast<std::size_t>(m) >= scene.meshes.size()) {
      throw InvalidInput(scene.source + ": body " + body.path + " names mesh " + std::to_string(m) +
                         ", which the scene does not have");
    }
    vertices += scene.meshes[static_cast<std::size_t>(m)].vertices.rows();
    triangles += scene.meshes[static_cast<std::size_t>(m)].triangles.rows();
  }
  SceneBodyCheck check;
  SurfaceMesh& world = check.world;
  world.source_name = scene.source + ":" + body.path;
  world.vertices.resize(vertices, 3);
  world.faces.resize(triangles, 3);
  SurfaceAppearance& look = world.appearance;
  look.corners.resize(triangles, 9);
  bool any_uvs = false;
  for (int m : body.meshes) any_uvs = any_uvs || scene.meshes[static_cast<std::size_t>(m)].uvs.rows() > 0;
  if (any_uvs) look.uvs.setZero(triangles, 6);
  const Eigen::Matrix3d linear = body.world.topLeftCorner<3, 3>();
  const Eigen::Vector3d offset = body.world.topRightCorner<3, 1>();
  Eigen::Index v0 = 0, t0 = 0;
  for (int m : body.meshes) {
    const SceneMesh& mesh = scene.meshes[static_cast<std::size_t>(m)];
    // The mesh's material in the appearance's own list, added at first use.
    const auto known = std::find(check.scene_materials.begin(), check.scene_materials.end(), mesh.material);
    const int material = static_cast<int>(known - check.scene_materials.begin());
    if (known == check.scene_materials.end()) {
      check.scene_materials.push_back(mesh.material);
      SurfaceAppearance::Material entry;
      if (mesh.material >= 0) {
        entry.name = scene.materials[static_cast<std::size_t>(mesh.material)].name;
        entry.colour = scene.materials[static_cast<std::size_t>(mesh.material)].colour;
      }
      look.materials.push_back(entry);
    }
    for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v) {
      world.vertices.row(v0 + v) = (linear * mesh.vertices.row(v).transpose() + offset).transpose();
    }
    for (Eigen::Index t = 0; t < mesh.triangles.rows(); ++t) {
      for (int i = 0; i < 3; ++i) {
        const int v = mesh.triangles(t, i);
        world.faces(t0 + t, i) = static_cast<int>(v0) + v;
        look.corners.row(t0 + t).segment<3>(3 * i) = world.vertices.row(v0 + v);
        if (mesh.uvs.rows() > 0) look.uvs.row(t0 + t).segment<2>(2 * i) = mesh.uvs.row(v);
      }
      look.material.push_back(material);
    }
    v0 += mesh.vertices.rows();
    t0 += mesh.triangles.rows();
  }
  if (world.vertices.rows() > 0) {
    check.extent = world.vertices.colwise().maxCoeff() - world.vertices.colwise().minCoeff();
  }
  if (!world.vertices.allFinite()) {
    check.reason = "its world transform makes a coordinate non-finite";
    return check;
  }
  try {
    // A mirroring transform (det < 0) turns an outward surface inside out; repair re-orients it.
    SurfaceRepairReport report;
    world = repair_surface(world, report);
    // Files split vertices where UVs or materials change (every textured box has 24 corners for
    // 8 positions); welding them back is reading the surface, not repairing it.
    for (const std::string& action : report.actions)
      if (action.find("duplicate vertices") == std::string::npos) check.repairs.push_back(action);
    check.volume = signed_volume(world);
    check.fracturable = check.volume > 0.0;
    if (!check.fracturable) check.reason = "it encloses no volume";
  } catch (const InvalidInput& e) {
    // The message starts with the surface's name; the reason is what follows it.
    std::string reason = e.what();
    const std::string prefix = world.source_name + ": ";
    if (reason.rfind(prefix, 0) == 0) reason = reason.substr(prefix.size());
    check.reason = reason;
  }
  return check;
}

}  // namespace fissure
