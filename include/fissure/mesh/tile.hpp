#pragma once
/// The procedural tile `tile:W,H,T` (metres): a box centred on the origin in x and y, resting on
/// z = 0. x ∈ [−W/2, W/2], y ∈ [−H/2, H/2], z ∈ [0, T]; the top face is z = T and "down" is −z.
/// Selections for supports and loads (box:…, ball:…) use these coordinates.

#include "fissure/mesh/surface_mesh.hpp"

#include <string_view>

namespace fissure {

struct TileSpec {
  double width = 1.0;      ///< W, along x, m
  double height = 1.0;     ///< H, along y, m
  double thickness = 0.05; ///< T, along z, m
};

/// True when `input` starts with "tile:".
bool is_tile_spec(std::string_view input);

/// Parses `tile:W,H,T`. Throws InvalidInput naming the spec when it is malformed or a size is not
/// positive and finite.
TileSpec parse_tile_spec(std::string_view spec);

/// The closed, outward-oriented box surface of a tile: 8 vertices, 12 triangles.
SurfaceMesh make_tile_surface(const TileSpec& tile);

}  // namespace fissure
