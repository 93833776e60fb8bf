// STL, binary or ASCII. Binary: an 80-byte header, a little-endian uint32 facet count, then 50
// bytes per facet (normal, three vertices as float32, a 16-bit attribute). ASCII: "solid name",
// then "facet normal … outer loop vertex x y z ×3 endloop endfacet" per facet, "endsolid";
// several solids may follow one another. Normals are ignored: the vertex order defines the face.

#include "byte_cursor.hpp"
#include "polygon_soup.hpp"
#include "surface_readers.hpp"

#include <array>
#include <cmath>

namespace fissure::io_detail {
namespace {

constexpr std::size_t kHeaderBytes = 84;  // 80-byte header and the uint32 count
constexpr std::size_t kFacetBytes = 50;

void add_facet(ByteCursor& c, PolygonSoup& soup, std::uint64_t facet, const std::array<double, 9>& xyz) {
  for (const double value : xyz) {
    if (!std::isfinite(value)) throw IoError(c.where() + "facet " + std::to_string(facet) + " has a non-finite coordinate");
  }
  const auto first = static_cast<std::int64_t>(soup.vertex_count());
  for (int k = 0; k < 3; ++k) soup.add_vertex(c, xyz[3 * k], xyz[3 * k + 1], xyz[3 * k + 2]);
  const std::array<std::int64_t, 3> face{first, first + 1, first + 2};
  soup.add_face(c, face);
}

SurfaceMesh read_binary(std::string_view bytes, const std::string& name) {
  ByteCursor c(bytes, name);
  c.enter_binary();
  if (bytes.size() < kHeaderBytes) c.fail("truncated: a binary STL file has an 84-byte header");
  c.skip(80);
  const std::uint32_t facets = c.binary<std::uint32_t>(false);
  c.check_count(facets, kFacetBytes, "facet");
  PolygonSoup soup(name, 0);
  soup.declare(3ull * facets, facets);
  for (std::uint32_t f = 0; f < facets; ++f) {
    c.skip(12);  // normal
    std::array<double, 9> xyz;
    for (double& value : xyz) value = c.binary<float>(false);
    c.skip(2);  // attribute byte count
    add_facet(c, soup, f + 1ull, xyz);
  }
  return soup.finish("a binary STL file");
}

SurfaceMesh read_ascii(std::string_view bytes, const std::string& name) {
  ByteCursor c(bytes, name);
  PolygonSoup soup(name, 0);
  std::uint64_t facet = 0;
  auto expect = [&](std::string_view keyword) {
    const std::string_view w = c.word();
    if (w.empty()) c.fail("truncated: the file ends where '" + std::string(keyword) + "' should be (facet " + std::to_string(facet) + ")");
    if (lower_ascii(w) != keyword) {
      c.fail("expected '" + std::string(keyword) + "', found '" + std::string(w.substr(0, 40)) + "' (facet " + std::to_string(facet) + ")");
    }
  };
  while (true) {
    c.skip_whitespace();
    if (c.at_end()) break;
    expect("solid");
    c.line();  // the solid's name
    while (true) {
      const std::string w = lower_ascii(c.word());
      if (w.empty()) c.fail("truncated: no 'endsolid'");
      if (w == "endsolid") {
        c.line();
        break;
      }
      ++facet;
      if (w != "facet") c.fail("expected 'facet' or 'endsolid', found '" + w.substr(0, 40) + "' (facet " + std::to_string(facet) + ")");
      c.line();  // "normal nx ny nz": ignored, as the vertex order defines the face
      expect("outer");
      expect("loop");
      std::array<double, 9> xyz;
      for (int k = 0; k < 3; ++k) {
        expect("vertex");
        for (int axis = 0; axis < 3; ++axis) xyz[static_cast<std::size_t>(3 * k + axis)] = c.number("a vertex coordinate");
      }
      add_facet(c, soup, facet, xyz);
      expect("endloop");
      expect("endfacet");
    }
  }
  return soup.finish("an STL file");
}

}  // namespace

SurfaceMesh read_stl(std::string_view bytes, const std::string& name) {
  // A binary file may begin with "solid" too (several exporters write it into the header), so
  // a size that matches the binary layout exactly decides first.
  if (bytes.size() >= kHeaderBytes) {
    ByteCursor count(bytes, name);
    count.skip(80);
    const std::uint32_t facets = count.binary<std::uint32_t>(false);
    if (bytes.size() == kHeaderBytes + kFacetBytes * static_cast<std::uint64_t>(facets)) return read_binary(bytes, name);
  }
  std::size_t start = 0;
  while (start < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[start]))) ++start;
  if (lower_ascii(bytes.substr(start, 5)) == "solid") return read_ascii(bytes, name);
  return read_binary(bytes, name);
}

}  // namespace fissure::io_detail
