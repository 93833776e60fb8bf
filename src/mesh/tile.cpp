#include "fissure/mesh/tile.hpp"

#include "fissure/base/error.hpp"
#include "fissure/base/number_text.hpp"

#include <string>
#include <vector>

namespace fissure {

bool is_tile_spec(std::string_view input) { return input.starts_with("tile:"); }

TileSpec parse_tile_spec(std::string_view spec) {
  const std::string text(spec);
  if (!is_tile_spec(spec)) throw InvalidInput("'" + text + "' is not a tile spec (tile:W,H,T in metres)");
  const std::vector<double> values =
      parse_number_list(spec.substr(5), "tile '" + text + "'", 3, "W,H,T (metres)");
  static constexpr const char* kNames[] = {"width W", "height H", "thickness T"};
  for (std::size_t i = 0; i < 3; ++i) {
    if (!(values[i] > 0.0)) {
      throw InvalidInput("tile '" + text + "': " + kNames[i] + " " + format_number(values[i]) + " must be positive");
    }
  }
  return TileSpec{values[0], values[1], values[2]};
}

SurfaceMesh make_tile_surface(const TileSpec& tile) {
  SurfaceMesh s;
  s.source_name = "tile:" + format_number(tile.width) + "," + format_number(tile.height) + "," +
                  format_number(tile.thickness);
  const double x = tile.width / 2, y = tile.height / 2, z = tile.thickness;
  s.vertices.resize(8, 3);
  // Vertex i has bit 0 → +x, bit 1 → +y, bit 2 → top.
  for (int i = 0; i < 8; ++i) s.vertices.row(i) << ((i & 1) ? x : -x), ((i & 2) ? y : -y), ((i & 4) ? z : 0.0);
  s.faces.resize(12, 3);
  s.faces << 0, 2, 1, 1, 2, 3,  // bottom, normal −z
      4, 5, 6, 5, 7, 6,         // top, +z
      0, 1, 4, 1, 5, 4,         // front y = −H/2, −y
      2, 6, 3, 3, 6, 7,         // back, +y
      0, 4, 2, 2, 4, 6,         // left x = −W/2, −x
      1, 3, 5, 3, 7, 5;         // right, +x
  return s;
}

}  // namespace fissure
