#pragma once
/// The demo scenes Fissure ships in assets/scenes/ (issue 13), made by this code rather than
/// drawn by hand, so `scripts/make-demo-scenes.sh` regenerates them byte for byte and tests can
/// build smaller ones. glTF conventions: +Y up, metres. Every mesh is closed and outward-wound,
/// with UVs in metres; scene material names are those of the bundled fracture materials where
/// one applies (assets/materials/), so `--assign concrete=concrete` and the like just work.
///
/// - Street: a group "street" holding "sidewalk" (a grid of slabs "slab_01"…, material
///   concrete, each its own node at its place), "curb" (material curb) and "road" (material
///   asphalt).
/// - Bathroom: "bathroom" holding "floor" (a grid of floor tiles, material ceramic-tile),
///   "wall" (a grid of wall tiles standing in the x–y plane, material ceramic-tile), "basin" (a
///   bowl made as a surface of revolution of a closed profile around a drain hole, material
///   porcelain) and "mirror" (a thin box, material glass).
#include "fissure/io/scene_export.hpp"

namespace fissure {

struct DemoStreetOptions {
  int slabs_along = 12;          ///< along x
  int slabs_across = 2;          ///< along z
  double slab_size = 0.6;        ///< m, square
  double slab_thickness = 0.05;  ///< m
  double joint = 0.008;          ///< m between slabs
  bool curb_and_road = true;
};

ExportScene demo_street(const DemoStreetOptions& options = {});

struct DemoBathroomOptions {
  int floor_tiles = 4;           ///< per side
  int wall_tiles_wide = 4, wall_tiles_high = 3;
  double tile_size = 0.3;        ///< m
  double tile_thickness = 0.01;  ///< m
  int basin_segments = 48;       ///< around the axis
};

ExportScene demo_bathroom(const DemoBathroomOptions& options = {});

/// A closed box of `size` centred on the origin, four vertices per face (UVs in metres on each
/// face's plane), outward-wound, every triangle of material `material`.
ExportPart box_part(const std::string& name, const Eigen::Vector3d& size, int material);

}  // namespace fissure
