#pragma once
/// The direction a scene body's visible face looks: the `up` its default supports and load use
/// (fracture_scenario.hpp). Fracture materials are fitted on a tile struck on its face and held
/// under it, so a body is struck where an artist sees it:
///  - a plate standing on its edge (its bounding box's thinnest side at most a quarter of the
///    next, and across the scene's up: a wall tile, a mirror) looks along that thin axis, towards
///    the scene's centre (the room in front of the wall): it is struck on its open face and held
///    on the rim of the face behind it, as a floor tile is held on the rim of its underside;
///  - every other body looks along the scene's up (a floor tile, a slab, a basin).
/// A body's own "up" in a project (scene_project.hpp) overrides both.
#include "fissure/io/scene_import.hpp"

#include <Eigen/Core>

#include <vector>

namespace fissure {

/// The centre of the bounding box of every body's world vertices (scene units).
Eigen::Vector3d scene_centre(const ImportedScene& scene, const std::vector<SceneBody>& bodies);

/// The rule above for a body with world vertices `world` (scene units), the scene's `up` (a
/// coordinate axis) and its centre. Returns a coordinate axis.
Eigen::Vector3d body_facing(const Eigen::MatrixX3d& world, const Eigen::Vector3d& up, const Eigen::Vector3d& centre);

}  // namespace fissure
