#include "fissure/scene/scene_body_check.hpp"

#include "fissure/base/error.hpp"
#include "fissure/mesh/surface_repair.hpp"

#include <cmath>

namespace fissure {

SceneBodyCheck check_scene_body(const ImportedScene& scene, const SceneBody& body) {
  if (body.mesh < 0 || static_cast<std::size_t>(body.mesh) >= scene.meshes.size()) {
    throw InvalidInput(scene.source + ": body " + body.path + " names mesh " + std::to_string(body.mesh) +
                       ", which the scene does not have");
  }
  const SceneMesh& mesh = scene.meshes[static_cast<std::size_t>(body.mesh)];
  SceneBodyCheck check;
  SurfaceMesh& world = check.world;
  world.source_name = scene.source + ":" + body.path;
  world.faces = mesh.triangles;
  world.vertices.resize(mesh.vertices.rows(), 3);
  const Eigen::Matrix3d linear = body.world.topLeftCorner<3, 3>();
  const Eigen::Vector3d offset = body.world.topRightCorner<3, 1>();
  for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v) {
    world.vertices.row(v) = (linear * mesh.vertices.row(v).transpose() + offset).transpose();
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
    check.repairs = report.actions;
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
