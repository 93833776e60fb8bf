// Wavefront OBJ, the strict way: `v` and `f` lines build the surface, `vt` and `usemtl` give its
// appearance (SurfaceAppearance), `o` the object each face belongs to (for scenes); every other
// statement (vn, vp, l, p, g, s, mtllib, …) is read past, as assimp did.

#include "byte_cursor.hpp"
#include "polygon_soup.hpp"
#include "surface_readers.hpp"

#include <algorithm>
#include <vector>

namespace fissure::io_detail {

SurfaceMesh read_obj(std::string_view bytes, const std::string& name, ObjObjects* objects) {
  ByteCursor c(bytes, name);
  PolygonSoup soup(name, 1);
  std::vector<std::int64_t> face, face_uvs;
  // An index as written (1-based, or negative counting back from the last one defined so far)
  // → 0-based; `what` names the kind in messages ("vertex", "texture coordinate").
  const auto resolve = [&](std::int64_t index, std::uint64_t defined, const char* what) {
    const std::int64_t absolute = index < 0 ? static_cast<std::int64_t>(defined) + 1 + index : index;
    if (absolute < 1 || static_cast<std::uint64_t>(absolute) > defined) {
      c.fail("face " + std::to_string(soup.face_count() + 1) + " references " + what + " " + std::to_string(index) +
             ", but only " + std::to_string(defined) + " come before it");
    }
    return absolute;
  };
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
    } else if (keyword == "vt") {
      // "vt u [v [w]]": v defaults to 0, w is not used.
      double uv[2] = {0.0, 0.0};
      for (int k = 0; k < 2; ++k) {
        const std::string_view w = c.line_word();
        if (w.empty()) {
          if (k == 0) c.fail("texture coordinate " + std::to_string(soup.uv_count() + 1) + " has no value");
          break;
        }
        if (!parse_double(w, uv[k])) {
          c.fail("texture coordinate " + std::to_string(soup.uv_count() + 1) + ": '" + std::string(w.substr(0, 40)) + "' is not a number");
        }
      }
      soup.add_uv(c, uv[0], uv[1]);
    } else if (keyword == "o") {
      // Its first word names the object (Fissure and Blender write names without blanks).
      const std::string_view first = c.line_word();
      soup.use_object(first.substr(0, 200));
    } else if (keyword == "usemtl") {
      const std::string_view name = c.line_word();
      if (name.empty()) c.fail("usemtl names no material");
      soup.use_material(name.substr(0, 200));
    } else if (keyword == "f") {
      face.clear();
      face_uvs.clear();
      for (std::string_view w = c.line_word(); !w.empty(); w = c.line_word()) {
        if (w[0] == '#') break;
        // "v", "v/vt", "v//vn" or "v/vt/vn": the vertex comes first.
        const std::size_t slash = w.find('/');
        const std::string_view vertex = w.substr(0, slash);
        const std::string_view uv = slash == std::string_view::npos ? std::string_view() : w.substr(slash + 1, w.find('/', slash + 1) - slash - 1);
        if (uv.empty()) {
          face_uvs.push_back(-1);
        } else {
          std::int64_t uv_index;
          if (!parse_integer(uv, uv_index) || uv_index == 0) {
            c.fail("face " + std::to_string(soup.face_count() + 1) + ": '" + std::string(w.substr(0, 40)) + "' is not a texture coordinate reference");
          }
          face_uvs.push_back(resolve(uv_index, soup.uv_count(), "texture coordinate") - 1);
        }
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
      const bool any_uv = std::any_of(face_uvs.begin(), face_uvs.end(), [](std::int64_t k) { return k >= 0; });
      soup.add_face(c, face, any_uv ? std::span<const std::int64_t>(face_uvs) : std::span<const std::int64_t>());
    }
    c.next_line();
  }
  SurfaceMesh surface = soup.finish("an OBJ file");
  if (objects) *objects = {soup.objects(), soup.triangle_objects()};
  return surface;
}

}  // namespace fissure::io_detail
