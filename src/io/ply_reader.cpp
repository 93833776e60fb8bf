// Stanford PLY 1.0 (Turk, "The PLY polygon file format"): a text header of elements and their
// properties, then the elements in header order, as text or as binary in either byte order.

#include "byte_cursor.hpp"
#include "polygon_soup.hpp"
#include "surface_readers.hpp"

#include "fissure/base/number_text.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <span>
#include <utility>
#include <vector>

namespace fissure::io_detail {
namespace {

enum class Scalar { Int8, Uint8, Int16, Uint16, Int32, Uint32, Float32, Float64 };

std::optional<Scalar> scalar_type(std::string_view word) {
  static const std::pair<std::string_view, Scalar> kNames[] = {
      {"char", Scalar::Int8},    {"int8", Scalar::Int8},       {"uchar", Scalar::Uint8},     {"uint8", Scalar::Uint8},
      {"short", Scalar::Int16},  {"int16", Scalar::Int16},     {"ushort", Scalar::Uint16},   {"uint16", Scalar::Uint16},
      {"int", Scalar::Int32},    {"int32", Scalar::Int32},     {"uint", Scalar::Uint32},     {"uint32", Scalar::Uint32},
      {"float", Scalar::Float32}, {"float32", Scalar::Float32}, {"double", Scalar::Float64}, {"float64", Scalar::Float64}};
  for (const auto& [name, type] : kNames) {
    if (word == name) return type;
  }
  return std::nullopt;
}

std::size_t size_of(Scalar type) {
  switch (type) {
    case Scalar::Int8:
    case Scalar::Uint8: return 1;
    case Scalar::Int16:
    case Scalar::Uint16: return 2;
    case Scalar::Int32:
    case Scalar::Uint32:
    case Scalar::Float32: return 4;
    case Scalar::Float64: return 8;
  }
  return 8;
}

bool is_integer(Scalar type) { return type != Scalar::Float32 && type != Scalar::Float64; }

struct Property {
  std::string name;
  Scalar type = Scalar::Float32;  // of the value, or of a list's items
  bool list = false;
  Scalar count_type = Scalar::Uint8;
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
};

enum class Encoding { Ascii, LittleEndian, BigEndian };

class ValueReader {
public:
  ValueReader(ByteCursor& c, Encoding encoding) : m_c(c), m_encoding(encoding) {}

  // Every PLY scalar is exact in a double (32-bit integers included).
  double read(Scalar type) {
    if (m_encoding == Encoding::Ascii) {
      const std::string_view w = m_c.word();
      if (w.empty()) m_c.fail("truncated: the file ends before the last element the header declares");
      if (is_integer(type)) {
        std::int64_t value;
        if (!parse_integer(w, value)) m_c.fail("'" + std::string(w.substr(0, 40)) + "' is not an integer");
        return static_cast<double>(value);
      }
      double value;
      if (!parse_double(w, value)) m_c.fail("'" + std::string(w.substr(0, 40)) + "' is not a number");
      return value;
    }
    const bool big = m_encoding == Encoding::BigEndian;
    switch (type) {
      case Scalar::Int8: return m_c.binary<std::int8_t>(big);
      case Scalar::Uint8: return m_c.binary<std::uint8_t>(big);
      case Scalar::Int16: return m_c.binary<std::int16_t>(big);
      case Scalar::Uint16: return m_c.binary<std::uint16_t>(big);
      case Scalar::Int32: return m_c.binary<std::int32_t>(big);
      case Scalar::Uint32: return m_c.binary<std::uint32_t>(big);
      case Scalar::Float32: return m_c.binary<float>(big);
      case Scalar::Float64: return m_c.binary<double>(big);
    }
    return 0.0;
  }

  // A list's length, checked against the bytes left before its items are read. `element` and
  // `item` (1-based) name it in the message.
  std::uint64_t list_length(Scalar count_type, Scalar item_type, const std::string& element, std::uint64_t item) {
    const double n = read(count_type);
    const bool ascii = m_encoding == Encoding::Ascii;
    if (n < 0 || !m_c.fits(static_cast<std::uint64_t>(n), ascii ? 2 : size_of(item_type), ascii ? 1 : 0)) {
      m_c.fail("truncated or corrupt: " + element + " " + std::to_string(item) + " has a list of " + format_number(n, 12) +
               " values, more than the " + std::to_string(m_c.remaining()) + " bytes left can hold");
    }
    return static_cast<std::uint64_t>(n);
  }

  // Minimum bytes of one item of `element`: a list takes at least its length, and a face's
  // vertex list at least three indices too (fewer are refused).
  std::uint64_t min_bytes(const Element& element) const {
    const bool ascii = m_encoding == Encoding::Ascii;
    std::uint64_t bytes = 0;
    for (const Property& p : element.properties) {
      bytes += ascii ? 2 : size_of(p.list ? p.count_type : p.type);
      if (element.name == "face" && p.list && (p.name == "vertex_indices" || p.name == "vertex_index")) {
        bytes += 3 * (ascii ? 2 : size_of(p.type));
      }
    }
    return bytes;
  }

private:
  ByteCursor& m_c;
  Encoding m_encoding;
};

struct Header {
  Encoding encoding = Encoding::Ascii;
  std::vector<Element> elements;
};

Header read_header(ByteCursor& c) {
  Header h;
  if (c.line_word() != "ply") c.fail("not a PLY file (no 'ply' on its first line)");
  c.next_line();
  bool have_format = false;
  while (true) {
    if (c.at_end()) c.fail("truncated: the header has no end_header");
    const std::string_view keyword = c.line_word();
    if (keyword == "end_header") {
      c.next_line();
      break;
    }
    if (keyword == "format") {
      const std::string_view encoding = c.line_word();
      if (encoding == "ascii") h.encoding = Encoding::Ascii;
      else if (encoding == "binary_little_endian") h.encoding = Encoding::LittleEndian;
      else if (encoding == "binary_big_endian") h.encoding = Encoding::BigEndian;
      else c.fail("unknown PLY format '" + std::string(encoding.substr(0, 40)) + "'");
      const std::string_view version = c.line_word();
      if (version != "1.0") c.fail("PLY version '" + std::string(version.substr(0, 20)) + "' (Fissure reads 1.0)");
      have_format = true;
    } else if (keyword == "element") {
      Element e;
      e.name = std::string(c.line_word());
      std::int64_t count;
      const std::string_view w = c.line_word();
      if (e.name.empty() || !parse_integer(w, count) || count < 0) c.fail("element '" + e.name.substr(0, 40) + "' has no valid count");
      e.count = static_cast<std::uint64_t>(count);
      h.elements.push_back(std::move(e));
    } else if (keyword == "property") {
      if (h.elements.empty()) c.fail("a property before any element");
      Property p;
      std::string_view type = c.line_word();
      if (type == "list") {
        p.list = true;
        const auto count_type = scalar_type(c.line_word());
        if (!count_type || !is_integer(*count_type)) c.fail("a list property needs an integer count type");
        p.count_type = *count_type;
        type = c.line_word();
      }
      const auto value_type = scalar_type(type);
      if (!value_type) c.fail("unknown property type '" + std::string(type.substr(0, 40)) + "'");
      p.type = *value_type;
      p.name = std::string(c.line_word());
      if (p.name.empty()) c.fail("a property without a name");
      h.elements.back().properties.push_back(std::move(p));
    } else if (keyword != "comment" && keyword != "obj_info" && !keyword.empty()) {
      c.fail("unknown header line '" + std::string(keyword.substr(0, 40)) + "'");
    }
    c.next_line();
  }
  if (!have_format) c.fail("the header has no format line");
  return h;
}

// Where x, y, z (and a texture coordinate pair) sit in the vertex element, and the face
// element's index list.
struct Layout {
  const Element* vertex = nullptr;
  const Element* face = nullptr;
  int xyz[3] = {-1, -1, -1};
  int uv[2] = {-1, -1};
  int indices = -1;
};

// The names exporters give a vertex's texture coordinates (Blender writes s, t; others u, v).
constexpr std::pair<const char*, const char*> kUvNames[] = {
    {"s", "t"}, {"u", "v"}, {"texture_u", "texture_v"}, {"texture_s", "texture_t"}};

Layout find_layout(const ByteCursor& c, const Header& h) {
  Layout layout;
  for (const Element& e : h.elements) {
    if (e.name == "vertex" || e.name == "face") {
      const Element*& slot = e.name == "vertex" ? layout.vertex : layout.face;
      if (slot) c.fail("a second '" + e.name + "' element");
      slot = &e;
    }
  }
  if (!layout.vertex) c.fail("no vertex element");
  if (!layout.face) throw InvalidInput(c.name() + ": has no face element (a point cloud bounds no volume)");
  for (std::size_t k = 0; k < layout.vertex->properties.size(); ++k) {
    const Property& p = layout.vertex->properties[k];
    for (int axis = 0; axis < 3; ++axis) {
      if (p.name == std::string(1, static_cast<char>('x' + axis)) && !p.list) layout.xyz[axis] = static_cast<int>(k);
    }
  }
  for (int axis = 0; axis < 3; ++axis) {
    if (layout.xyz[axis] < 0) c.fail(std::string("the vertex element has no property ") + static_cast<char>('x' + axis));
  }
  for (const auto& [u, v] : kUvNames) {
    int found[2] = {-1, -1};
    for (std::size_t k = 0; k < layout.vertex->properties.size(); ++k) {
      const Property& p = layout.vertex->properties[k];
      if (p.list) continue;
      if (p.name == u) found[0] = static_cast<int>(k);
      if (p.name == v) found[1] = static_cast<int>(k);
    }
    if (found[0] >= 0 && found[1] >= 0) {
      layout.uv[0] = found[0];
      layout.uv[1] = found[1];
      break;
    }
  }
  for (std::size_t k = 0; k < layout.face->properties.size(); ++k) {
    const Property& p = layout.face->properties[k];
    if ((p.name == "vertex_indices" || p.name == "vertex_index") && p.list) layout.indices = static_cast<int>(k);
  }
  if (layout.indices < 0) c.fail("the face element has no vertex_indices list");
  if (!is_integer(layout.face->properties[static_cast<std::size_t>(layout.indices)].type)) {
    c.fail("the face element's vertex_indices are not integers");
  }
  return layout;
}

}  // namespace

SurfaceMesh read_ply(std::string_view bytes, const std::string& name) {
  ByteCursor c(bytes, name);
  const Header h = read_header(c);
  if (h.encoding != Encoding::Ascii) c.enter_binary();
  ValueReader values(c, h.encoding);

  // Every element's count against the bytes left, before anything is allocated.
  std::uint64_t budget = c.remaining() + (h.encoding == Encoding::Ascii ? 1 : 0);
  for (const Element& e : h.elements) {
    const std::uint64_t each = values.min_bytes(e);
    if (each > 0 && e.count > budget / each) {
      c.fail("truncated or corrupt: the header declares " + std::to_string(e.count) + " " + e.name + " elements of at least " +
             std::to_string(each) + " bytes each, but only " + std::to_string(c.remaining()) + " bytes follow it");
    }
    budget -= e.count * each;
  }
  const Layout layout = find_layout(c, h);
  PolygonSoup soup(name, 0);
  soup.declare(layout.vertex->count, layout.face->count);

  std::vector<std::int64_t> face;
  for (const Element& e : h.elements) {
    if (e.properties.empty()) continue;  // nothing to read, however many
    for (std::uint64_t item = 0; item < e.count; ++item) {
      double xyz[3] = {0, 0, 0}, uv[2] = {0, 0};
      for (std::size_t k = 0; k < e.properties.size(); ++k) {
        const Property& p = e.properties[k];
        if (!p.list) {
          const double value = values.read(p.type);
          if (&e == layout.vertex) {
            for (int axis = 0; axis < 3; ++axis)
              if (layout.xyz[axis] == static_cast<int>(k)) xyz[axis] = value;
            for (int i = 0; i < 2; ++i)
              if (layout.uv[i] == static_cast<int>(k)) uv[i] = value;
          }
          continue;
        }
        const std::uint64_t length = values.list_length(p.count_type, p.type, e.name, item + 1);
        const bool indices = &e == layout.face && layout.indices == static_cast<int>(k);
        if (indices) face.resize(static_cast<std::size_t>(length));
        for (std::uint64_t i = 0; i < length; ++i) {
          const double value = values.read(p.type);
          // Clamped: beyond ±9e18 a cast to int64 would be undefined; any such index is refused.
        if (indices) face[static_cast<std::size_t>(i)] = static_cast<std::int64_t>(std::clamp(value, -9e18, 9e18));
        }
      }
      if (&e == layout.vertex) {
        soup.add_vertex(c, xyz[0], xyz[1], xyz[2]);
        if (layout.uv[0] >= 0) soup.add_uv(c, uv[0], uv[1]);
      }
      // Per-vertex texture coordinates: a corner's is its vertex's (faces read before the
      // vertices, which PLY allows, keep none).
      if (&e == layout.face) soup.add_face(c, face, layout.uv[0] >= 0 && soup.uv_count() > 0 ? std::span<const std::int64_t>(face) : std::span<const std::int64_t>());
    }
  }
  return soup.finish("a PLY file");
}

}  // namespace fissure::io_detail
