// Object File Format: an optional keyword, the counts, one vertex per line (its first three
// numbers; colours, normals and texture coordinates that follow are ignored), one face per line.

#include "byte_cursor.hpp"
#include "polygon_soup.hpp"
#include "surface_readers.hpp"

#include <vector>

namespace fissure::io_detail {
namespace {

// The next word on the current line, with '#' comments removed.
std::string_view off_word(ByteCursor& c) {
  const std::string_view w = c.line_word();
  if (!w.empty() && w[0] == '#') {
    c.next_line();
    return {};
  }
  return w.substr(0, w.find('#'));
}

// Moves to the next line that holds something other than blanks and comments.
void next_content(ByteCursor& c) {
  while (!c.at_end()) {
    c.skip_blanks();
    if (c.at_end()) return;
    const char next = c.bytes()[c.position()];
    if (next != '\n' && next != '#') return;
    c.next_line();
  }
}

std::int64_t off_integer(ByteCursor& c, const std::string& what) {
  const std::string_view w = off_word(c);
  std::int64_t value;
  if (w.empty()) c.fail("truncated: " + what + " is missing");
  if (!parse_integer(w, value) || value < 0) c.fail(what + ": '" + std::string(w.substr(0, 40)) + "' is not a count");
  return value;
}

}  // namespace

SurfaceMesh read_off(std::string_view bytes, const std::string& name) {
  ByteCursor c(bytes, name);
  PolygonSoup soup(name, 0);

  // Header: "[ST][C][N][4][n]OFF [BINARY]", then the vertex, face and (optional) edge counts,
  // on the keyword's line or the next ones.
  next_content(c);
  const std::size_t header = c.position();
  const std::string_view keyword = off_word(c);
  if (keyword.size() >= 3 && keyword.substr(keyword.size() - 3) == "OFF") {
    const std::string_view prefix = keyword.substr(0, keyword.size() - 3);
    if (prefix.find_first_of("4n") != std::string_view::npos) {
      c.fail("'" + std::string(keyword) + "' (4-D or n-D OFF) is not supported; Fissure reads 3-D OFF");
    }
    if (prefix.find_first_not_of("STCN") != std::string_view::npos) c.fail("'" + std::string(keyword.substr(0, 40)) + "' is not an OFF keyword");
    next_content(c);
    if (c.bytes().substr(c.position(), 6) == "BINARY") c.fail("binary OFF is not supported; save the file as ASCII OFF");
  } else {
    std::int64_t probe;
    if (!parse_integer(keyword, probe)) c.fail("not an OFF file (no OFF keyword and no vertex count)");
    c.seek(header);  // no keyword: that was the vertex count
  }
  const std::int64_t vertices = off_integer(c, "the vertex count");
  next_content(c);
  const std::int64_t faces = off_integer(c, "the face count");
  off_word(c);  // the edge count, unused (and optional)
  c.next_line();
  // A vertex takes at least "0 0 0\n" (6 bytes), a face "3 0 1 2\n" (8); the last newline may be
  // missing.
  c.check_count(static_cast<std::uint64_t>(vertices), 6, "vertex", 1);
  const std::uint64_t after_vertices = c.remaining() + 1 - 6 * static_cast<std::uint64_t>(vertices);
  if (static_cast<std::uint64_t>(faces) > after_vertices / 8) {
    c.fail("truncated or corrupt: the header's " + std::to_string(vertices) + " vertices and " + std::to_string(faces) +
           " faces need more than the " + std::to_string(c.remaining()) + " bytes left in the file");
  }
  soup.declare(static_cast<std::uint64_t>(vertices), static_cast<std::uint64_t>(faces));

  for (std::int64_t v = 0; v < vertices; ++v) {
    next_content(c);
    double xyz[3];
    for (double& value : xyz) {
      const std::string_view w = off_word(c);
      if (w.empty()) c.fail("vertex " + std::to_string(v + 1) + " has fewer than 3 coordinates");
      if (!parse_double(w, value)) c.fail("vertex " + std::to_string(v + 1) + ": '" + std::string(w.substr(0, 40)) + "' is not a number");
    }
    soup.add_vertex(c, xyz[0], xyz[1], xyz[2]);
    c.next_line();
  }
  std::vector<std::int64_t> face;
  for (std::int64_t f = 0; f < faces; ++f) {
    next_content(c);
    const std::int64_t n = off_integer(c, "the vertex count of face " + std::to_string(f + 1));
    c.check_count(static_cast<std::uint64_t>(n), 2, "face vertex", 1);
    face.resize(static_cast<std::size_t>(n));
    for (auto& index : face) {
      const std::string_view w = off_word(c);
      if (w.empty()) c.fail("face " + std::to_string(f + 1) + " has fewer than the " + std::to_string(n) + " vertices it announces");
      if (!parse_integer(w, index)) c.fail("face " + std::to_string(f + 1) + ": '" + std::string(w.substr(0, 40)) + "' is not a vertex index");
    }
    soup.add_face(c, face);
    c.next_line();
  }
  return soup.finish("an OFF file");
}

}  // namespace fissure::io_detail
