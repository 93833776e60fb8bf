// Wavefront OBJ, the strict way: only `v` and `f` lines build the surface; every other statement
// (vt, vn, vp, l, p, o, g, s, usemtl, mtllib, …) is read past, as assimp did.

#include "byte_cursor.hpp"
#include "polygon_soup.hpp"
#include "surface_readers.hpp"

#include <vector>

namespace fissure::io_detail {

SurfaceMesh read_obj(std::string_view bytes, const std::string& name) {
  ByteCursor c(bytes, name);
  PolygonSoup soup(name, 1);
  std::vector<std::int64_t> face;
  while (!c.at_end()) {
    const std::string_view keyword = c.line_word();
    if (keyword == "v") {
      double xyz[3];
      for (double& value : xyz) {
        const std::string_view w = c.line_word();
        if (w.empty()) c.fail("vertex " + std::to_string(soup.vertex_count() + 1) + " has fewer than 3 coordinates");
        if (!parse_double(w, value)) {
          c.fail("vertex " + std::to_string(soup.vertex_count() + 1) + ": '" + std::string(w.substr(0, 40)) + "' is not a number");
        }
      }
      soup.add_vertex(c, xyz[0], xyz[1], xyz[2]);
    } else if (keyword == "f") {
      face.clear();
      for (std::string_view w = c.line_word(); !w.empty(); w = c.line_word()) {
        if (w[0] == '#') break;
        // "v", "v/vt", "v//vn" or "v/vt/vn": the vertex comes first.
        const std::string_view vertex = w.substr(0, w.find('/'));
        std::int64_t index;
        if (!parse_integer(vertex, index) || index == 0) {
          c.fail("face " + std::to_string(soup.face_count() + 1) + ": '" + std::string(w.substr(0, 40)) + "' is not a vertex reference");
        }
        if (index < 0) {
          // Relative: −1 is the last vertex defined so far.
          const std::int64_t absolute = static_cast<std::int64_t>(soup.vertex_count()) + 1 + index;
          if (absolute < 1) {
            c.fail("face " + std::to_string(soup.face_count() + 1) + " references vertex " + std::to_string(index) + ", but only " +
                   std::to_string(soup.vertex_count()) + " vertices come before it");
          }
          index = absolute;
        }
        face.push_back(index);
      }
      soup.add_face(c, face);
    }
    c.next_line();
  }
  return soup.finish("an OBJ file");
}

}  // namespace fissure::io_detail
