#include "fissure/scene/demo_scenes.hpp"

#include "fissure/base/error.hpp"

#include <cmath>
#include <numbers>
#include <string>

namespace fissure {
namespace {

std::string numbered(const std::string& base, int k, int count) {
  std::string digits = std::to_string(k);
  const std::size_t width = std::to_string(count).size() < 2 ? 2 : std::to_string(count).size();
  if (digits.size() < width) digits.insert(0, width - digits.size(), '0');
  return base + "_" + digits;
}

ExportPart group(const std::string& name, int parent, const Eigen::Vector3d& at = Eigen::Vector3d::Zero()) {
  ExportPart g;
  g.name = name;
  g.parent = parent;
  g.translation = at;
  return g;
}

int add(ExportScene& scene, ExportPart part) {
  scene.parts.push_back(std::move(part));
  return static_cast<int>(scene.parts.size()) - 1;
}

int add_material(ExportScene& scene, const std::string& name, const Eigen::Vector3d& colour) {
  scene.materials.push_back({name, colour, {}});
  return static_cast<int>(scene.materials.size()) - 1;
}

// A grid of tiles in the plane of axes (a, b), the tile's thickness along the third axis.
void add_tile_grid(ExportScene& scene, int parent, const std::string& base, int na, int nb, double size, double thickness,
                   double joint, int a, int b, int material) {
  const int normal = 3 - a - b;
  Eigen::Vector3d extent;
  extent(a) = size;
  extent(b) = size;
  extent(normal) = thickness;
  const double pitch = size + joint;
  for (int j = 0; j < nb; ++j) {
    for (int i = 0; i < na; ++i) {
      ExportPart tile = box_part(numbered(base, j * na + i + 1, na * nb), extent, material);
      tile.parent = parent;
      tile.translation(a) = (i + 0.5) * pitch;
      tile.translation(b) = (j + 0.5) * pitch;
      tile.translation(normal) = 0.5 * thickness;
      add(scene, std::move(tile));
    }
  }
}

// The basin: a closed profile (r, y) revolved about +y. The profile runs outward along the
// inside of the bowl from the drain, over the rim, and back down the outside, then closes across
// the bottom ring: a closed, torus-like surface with the drain as its hole.
ExportPart basin_part(int segments, int material) {
  const double r_drain = 0.025, r_rim = 0.22, depth = 0.15, wall = 0.015;
  std::vector<Eigen::Vector2d> profile;  // counter-clockwise in the (r, y) half-plane
  const int arc = 10;
  // The outside from the bottom outward and up, then the rim, then the inside back down.
  for (int k = 0; k <= arc; ++k) {
    const double t = static_cast<double>(k) / arc;
    profile.emplace_back(r_drain + wall + (r_rim - r_drain) * std::sin(0.5 * std::numbers::pi * t),
                         depth * (1.0 - std::cos(0.5 * std::numbers::pi * t)));
  }
  for (int k = arc; k >= 0; --k) {
    const double t = static_cast<double>(k) / arc;
    profile.emplace_back(r_drain + (r_rim - r_drain - wall) * std::sin(0.5 * std::numbers::pi * t),
                         wall + (depth - wall) * (1.0 - std::cos(0.5 * std::numbers::pi * t)) + (k == arc ? wall : 0.0));
  }
  const int p = static_cast<int>(profile.size());
  ExportPart part;
  part.name = "basin";
  part.vertices.resize(static_cast<Eigen::Index>(p) * segments, 3);
  part.uvs.resize(part.vertices.rows(), 2);
  for (int s = 0; s < segments; ++s) {
    const double phi = 2.0 * std::numbers::pi * s / segments;
    for (int k = 0; k < p; ++k) {
      const Eigen::Index v = static_cast<Eigen::Index>(s) * p + k;
      part.vertices.row(v) << profile[k](0) * std::cos(phi), profile[k](1), -profile[k](0) * std::sin(phi);
      part.uvs.row(v) << phi * r_rim, static_cast<double>(k) / p;
    }
  }
  part.triangles.resize(static_cast<Eigen::Index>(2) * p * segments, 3);
  Eigen::Index t = 0;
  for (int s = 0; s < segments; ++s) {
    const int s1 = (s + 1) % segments;
    for (int k = 0; k < p; ++k) {
      const int k1 = (k + 1) % p;
      const int a = s * p + k, b = s * p + k1, c = s1 * p + k1, d = s1 * p + k;
      // The profile runs counter-clockwise in (r, y) and φ turns counter-clockwise about +y, so
      // (a, d, c), (a, c, b) face outward.
      part.triangles.row(t++) << a, d, c;
      part.triangles.row(t++) << a, c, b;
    }
  }
  part.triangle_material.assign(static_cast<std::size_t>(part.triangles.rows()), material);
  return part;
}

}  // namespace

ExportPart box_part(const std::string& name, const Eigen::Vector3d& size, int material) {
  if (!(size.minCoeff() > 0.0) || !size.allFinite()) throw InvalidInput("box " + name + ": its size must be positive");
  ExportPart part;
  part.name = name;
  part.vertices.resize(24, 3);
  part.uvs.resize(24, 2);
  part.triangles.resize(12, 3);
  const Eigen::Vector3d h = 0.5 * size;
  int v = 0, t = 0;
  for (int axis = 0; axis < 3; ++axis) {
    for (int sign : {-1, 1}) {
      const int u = (axis + 1) % 3, w = (axis + 2) % 3;  // (u, w, axis) right-handed
      for (int corner = 0; corner < 4; ++corner) {
        const double su = corner == 1 || corner == 2 ? 1.0 : -1.0, sw = corner >= 2 ? 1.0 : -1.0;
        Eigen::Vector3d x;
        x(axis) = sign * h(axis);
        x(u) = su * h(u);
        x(w) = sw * h(w) * sign;  // mirrored on the − face, so every face winds outward
        part.vertices.row(v + corner) = x.transpose();
        part.uvs.row(v + corner) << x(u) + h(u), sign * x(w) + h(w);
      }
      part.triangles.row(t++) << v, v + 1, v + 2;
      part.triangles.row(t++) << v, v + 2, v + 3;
      v += 4;
    }
  }
  part.triangle_material.assign(12, material);
  return part;
}

ExportScene demo_street(const DemoStreetOptions& o) {
  if (o.slabs_along < 1 || o.slabs_across < 1) throw InvalidInput("the street needs at least one slab");
  ExportScene scene;
  const int concrete = add_material(scene, "concrete", {0.55, 0.54, 0.50});
  const int street = add(scene, group("street", -1));
  const int sidewalk = add(scene, group("sidewalk", street));
  add_tile_grid(scene, sidewalk, "slab", o.slabs_along, o.slabs_across, o.slab_size, o.slab_thickness, o.joint, 0, 2, concrete);
  if (o.curb_and_road) {
    const int curb_material = add_material(scene, "curb", {0.45, 0.45, 0.47});
    const int asphalt = add_material(scene, "asphalt", {0.12, 0.12, 0.13});
    const double length = o.slabs_along * (o.slab_size + o.joint), depth = o.slabs_across * (o.slab_size + o.joint);
    ExportPart curb = box_part("curb", {length, 0.25, 0.15}, curb_material);
    curb.parent = street;
    curb.translation = {0.5 * length, o.slab_thickness - 0.125, depth + 0.075};
    add(scene, std::move(curb));
    ExportPart road = box_part("road", {length, 0.12, 3.0}, asphalt);
    road.parent = street;
    road.translation = {0.5 * length, o.slab_thickness - 0.15 - 0.06, depth + 0.15 + 1.5};
    add(scene, std::move(road));
  }
  return scene;
}

ExportScene demo_bathroom(const DemoBathroomOptions& o) {
  ExportScene scene;
  const int tile = add_material(scene, "ceramic-tile", {0.85, 0.86, 0.84});
  const int porcelain = add_material(scene, "porcelain", {0.93, 0.93, 0.92});
  const int glass = add_material(scene, "glass", {0.75, 0.82, 0.85});
  const int bathroom = add(scene, group("bathroom", -1));
  const int floor = add(scene, group("floor", bathroom));
  add_tile_grid(scene, floor, "floor_tile", o.floor_tiles, o.floor_tiles, o.tile_size, o.tile_thickness, 0.003, 0, 2, tile);
  // The wall stands at z = 0 behind the floor, its tiles in the x–y plane, faces along +z.
  const int wall = add(scene, group("wall", bathroom, {0.0, o.tile_thickness, -o.tile_thickness}));
  add_tile_grid(scene, wall, "wall_tile", o.wall_tiles_wide, o.wall_tiles_high, o.tile_size, o.tile_thickness, 0.003, 0, 1, tile);
  const double width = o.wall_tiles_wide * (o.tile_size + 0.003);
  ExportPart basin = basin_part(o.basin_segments, porcelain);
  basin.parent = bathroom;
  basin.translation = {0.5 * width, 0.75, 0.28};
  add(scene, std::move(basin));
  ExportPart mirror = box_part("mirror", {0.5, 0.6, 0.006}, glass);
  mirror.parent = bathroom;
  mirror.translation = {0.5 * width, 1.35, 0.003};
  add(scene, std::move(mirror));
  return scene;
}

}  // namespace fissure
