#include "assimp_precheck.hpp"

#include "fissure/base/error.hpp"

#include <nlohmann/json.hpp>

#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <system_error>
#include <tuple>
#include <vector>

// assimp 5.2.5's glTF 2.0 reader checks buffer views and accessors in size_t arithmetic that
// wraps (an accessor byteOffset of 2^64 - 1 passes "byteOffset + length <= view length" and then
// reads one byte before the buffer), checks an accessor against count × component size instead
// of count × stride, ignores the accessor's byteOffset in its extraction check, and copies sparse
// indices and values without any bound. So every range it will read is checked here first, with
// arithmetic that cannot overflow, against the bytes that really exist.

namespace fissure::io_detail {
namespace {

using Json = nlohmann::json;

struct View {
  std::uint64_t length = 0;
  std::uint64_t stride = 0;  // 0: tightly packed
};

class GltfBounds {
 public:
  GltfBounds(const Json& doc, const std::string& name, const std::filesystem::path& directory, std::optional<std::uint64_t> glb_bin)
      : m_doc(doc), m_name(name), m_directory(directory), m_glb_bin(glb_bin) {}

  void check() {
    const Json& buffers = array("buffers");
    for (std::size_t i = 0; i < buffers.size(); ++i) check_buffer(buffers[i], "buffers[" + std::to_string(i) + "]");
    const Json& views = array("bufferViews");
    for (std::size_t i = 0; i < views.size(); ++i) check_view(views[i], "bufferViews[" + std::to_string(i) + "]");
    const Json& accessors = array("accessors");
    for (std::size_t i = 0; i < accessors.size(); ++i) check_accessor(accessors[i], "accessors[" + std::to_string(i) + "]");
    const Json& meshes = array("meshes");
    for (std::size_t m = 0; m < meshes.size(); ++m) {
      const std::string mesh = "meshes[" + std::to_string(m) + "]";
      const Json& primitives = member_array(object(meshes[m], mesh), "primitives", mesh);
      for (std::size_t p = 0; p < primitives.size(); ++p) check_primitive(primitives[p], mesh + ".primitives[" + std::to_string(p) + "]");
    }
    // Embedded images: assimp copies their buffer view (checked above) whether or not a
    // material uses them.
    const Json& images = array("images");
    for (std::size_t i = 0; i < images.size(); ++i) {
      const std::string where = "images[" + std::to_string(i) + "]";
      const Json& image = object(images[i], where);
      if (image.contains("bufferView")) reference(image, "bufferView", m_views.size(), "bufferViews", where);
    }
  }

 private:
  [[noreturn]] void fail(const std::string& what) const { throw IoError(m_name + ": corrupt glTF: " + what); }

  const Json& array(const char* key) const {
    static const Json empty = Json::array();
    if (!m_doc.contains(key)) return empty;
    if (!m_doc[key].is_array()) fail(std::string(key) + " is not an array");
    return m_doc[key];
  }
  const Json& member_array(const Json& obj, const char* key, const std::string& where) const {
    if (!obj.contains(key) || !obj[key].is_array()) fail(where + " has no " + key + " array");
    return obj[key];
  }
  const Json& object(const Json& value, const std::string& where) const {
    if (!value.is_object()) fail(where + " is not an object");
    return value;
  }

  // A non-negative integer member (glTF's counts, offsets and indices), or `fallback` when absent;
  // fractions, negatives and numbers beyond 64 bits are refused, as assimp would read them as 0
  // or wrap them.
  std::uint64_t integer(const Json& obj, const char* key, std::optional<std::uint64_t> fallback, const std::string& where) const {
    if (!obj.contains(key)) {
      if (!fallback) fail(where + " has no " + key);
      return *fallback;
    }
    const Json& value = obj[key];
    if (value.is_number_unsigned()) return value.get<std::uint64_t>();
    if (value.is_number_integer() && value.get<std::int64_t>() >= 0) return static_cast<std::uint64_t>(value.get<std::int64_t>());
    fail(where + "." + key + " is not a non-negative integer");
  }
  std::size_t reference(const Json& obj, const char* key, std::size_t count, const char* section, const std::string& where) const {
    const std::uint64_t index = integer(obj, key, std::nullopt, where);
    if (index >= count) {
      fail(where + "." + key + " refers to " + section + "[" + std::to_string(index) + "], but there are " + std::to_string(count));
    }
    return static_cast<std::size_t>(index);
  }
  // [offset, offset + length) inside `limit` bytes, in arithmetic that cannot wrap.
  void within(std::uint64_t offset, std::uint64_t length, std::uint64_t limit, const std::string& what, const std::string& container) const {
    if (offset > limit || length > limit - offset) {
      const std::uint64_t max = std::numeric_limits<std::uint64_t>::max();
      const std::string end = length > max - offset ? "beyond 2^64" : std::to_string(offset + length);
      fail(what + " reaches byte " + end + " of " + container + ", which holds " + std::to_string(limit));
    }
  }

  void check_buffer(const Json& value, const std::string& where) {
    const Json& buffer = object(value, where);
    const std::uint64_t stated = integer(buffer, "byteLength", std::nullopt, where);
    std::uint64_t real = 0;
    std::string source;
    if (!buffer.contains("uri")) {
      // GLB: the first buffer without a URI is the BIN chunk.
      if (m_glb_bin && m_buffers.empty()) real = *m_glb_bin;
      source = m_glb_bin && m_buffers.empty() ? "the GLB BIN chunk" : "no data (it has no uri)";
    } else if (!buffer["uri"].is_string()) {
      fail(where + ".uri is not a string");
    } else {
      const std::string uri = buffer["uri"].get<std::string>();
      if (uri.rfind("data:", 0) == 0) {
        real = base64_length(uri, where);
        source = "its data URI";
      } else {
        check_beside_scene(uri, where);
        std::error_code error;
        if (!std::filesystem::is_regular_file(m_directory / uri, error) && !error)
          throw IoError(m_name + ": " + where + ": its file '" + uri.substr(0, 200) + "' is not a regular file");
        const std::uintmax_t size = std::filesystem::file_size(m_directory / uri, error);
        if (error) throw IoError(m_name + ": " + where + ": cannot read its file '" + uri.substr(0, 200) + "': " + error.message());
        real = size;
        source = "'" + uri.substr(0, 200) + "'";
      }
    }
    if (stated > real) {
      fail(where + " claims " + std::to_string(stated) + " bytes, but " + source + " holds " + std::to_string(real));
    }
    m_buffers.push_back(stated);
  }

  // A buffer file must lie in the scene's folder or below it. A scene from elsewhere could
  // otherwise name /etc/passwd or ../../.ssh/id_rsa as a buffer, and the export would carry those
  // bytes on into a file the user shares. (glTF asks for relative URIs; absolute ones and other
  // schemes such as http: are not read.)
  void check_beside_scene(const std::string& uri, const std::string& where) const {
    const std::string shown = "'" + uri.substr(0, 200) + "'";
    const std::size_t colon = uri.find(':'), slash = uri.find('/');
    if (colon != std::string::npos && (slash == std::string::npos || colon < slash))
      throw IoError(m_name + ": " + where + ": its URI " + shown + " has a scheme; only relative file URIs and data: URIs are read");
    const std::filesystem::path path = std::filesystem::path(uri).lexically_normal();
    if (path.is_absolute() || path.has_root_name() || (!path.empty() && *path.begin() == ".."))
      throw IoError(m_name + ": " + where + ": its file " + shown +
                    " is outside the scene's folder; move it beside the scene and name it relatively");
  }

  // Decoded length of a base64 data URI; anything but clean base64 is refused.
  std::uint64_t base64_length(const std::string& uri, const std::string& where) const {
    const std::size_t comma = uri.find(',');
    if (comma == std::string::npos || uri.rfind(";base64", comma) != comma - 7) fail(where + ".uri is a data URI without base64 data");
    const std::string_view data = std::string_view(uri).substr(comma + 1);
    if (data.size() % 4 != 0) fail(where + ".uri: its base64 data has " + std::to_string(data.size()) + " characters, not a multiple of 4");
    std::size_t padding = 0;
    for (std::size_t i = 0; i < data.size(); ++i) {
      const char c = data[i];
      const bool digit = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '+' || c == '/';
      if (c == '=' && i + 2 >= data.size()) ++padding;
      else if (!digit || padding > 0) fail(where + ".uri: invalid base64 at character " + std::to_string(comma + 2 + i));
    }
    return data.size() / 4 * 3 - padding;
  }

  void check_view(const Json& value, const std::string& where) {
    const Json& view = object(value, where);
    const std::size_t buffer = reference(view, "buffer", m_buffers.size(), "buffers", where);
    const std::uint64_t offset = integer(view, "byteOffset", 0, where);
    const std::uint64_t length = integer(view, "byteLength", std::nullopt, where);
    within(offset, length, m_buffers[buffer], where, "buffers[" + std::to_string(buffer) + "]");
    const std::uint64_t stride = integer(view, "byteStride", 0, where);
    if (view.contains("byteStride") && (stride < 4 || stride > 252 || stride % 4 != 0)) {
      fail(where + ".byteStride " + std::to_string(stride) + " is not a multiple of 4 from 4 to 252");
    }
    m_views.push_back({length, stride});
  }

  static std::uint64_t component_size(std::uint64_t type) {
    switch (type) {
      case 5120: case 5121: return 1;  // (UNSIGNED_)BYTE
      case 5122: case 5123: return 2;  // (UNSIGNED_)SHORT
      case 5125: case 5126: return 4;  // UNSIGNED_INT, FLOAT
      default: return 0;
    }
  }

  // Element size per the glTF 2.0 spec ("Data Alignment"): matrix columns start on 4-byte
  // boundaries, which pads MAT2 of bytes and MAT3 of bytes and shorts.
  std::uint64_t element_size(const Json& accessor, std::uint64_t component, const std::string& where) const {
    if (!accessor.contains("type") || !accessor["type"].is_string()) fail(where + " has no type");
    const std::string type = accessor["type"].get<std::string>();
    constexpr std::array<std::pair<std::string_view, std::uint64_t>, 7> kTypes = {
        {{"SCALAR", 1}, {"VEC2", 2}, {"VEC3", 3}, {"VEC4", 4}, {"MAT2", 2}, {"MAT3", 3}, {"MAT4", 4}}};
    for (const auto& [label, n] : kTypes) {
      if (type != label) continue;
      if (label.rfind("MAT", 0) != 0) return n * component;
      const std::uint64_t column = (n * component + 3) / 4 * 4;
      return n * column;
    }
    fail(where + ".type '" + type.substr(0, 20) + "' is not a glTF accessor type");
  }

  void check_accessor(const Json& value, const std::string& where) {
    const Json& accessor = object(value, where);
    const std::uint64_t component = component_size(integer(accessor, "componentType", std::nullopt, where));
    if (component == 0) fail(where + ".componentType " + accessor["componentType"].dump() + " is not a glTF component type");
    const std::uint64_t element = element_size(accessor, component, where);
    const std::uint64_t count = integer(accessor, "count", std::nullopt, where);
    if (count == 0 || count > std::numeric_limits<std::uint32_t>::max()) fail(where + ".count " + std::to_string(count) + " is not from 1 to 2^32 - 1");
    if (accessor.contains("bufferView")) {
      const std::size_t v = reference(accessor, "bufferView", m_views.size(), "bufferViews", where);
      const View& view = m_views[v];
      const std::uint64_t stride = view.stride != 0 ? view.stride : element;
      if (stride < element) {
        fail(where + ": its elements of " + std::to_string(element) + " bytes overlap at bufferViews[" + std::to_string(v) + "].byteStride " +
             std::to_string(stride));
      }
      // count ≤ 2^32 and stride ≤ 252: the product cannot wrap.
      within(integer(accessor, "byteOffset", 0, where), (count - 1) * stride + element, view.length, where, "bufferViews[" + std::to_string(v) + "]");
    }
    if (accessor.contains("sparse")) check_sparse(object(accessor["sparse"], where + ".sparse"), count, element, where + ".sparse");
    m_accessor_counts.push_back(count);
  }

  // assimp copies sparse.count indices and values with no bound at all.
  void check_sparse(const Json& sparse, std::uint64_t accessor_count, std::uint64_t element, const std::string& where) const {
    const std::uint64_t count = integer(sparse, "count", std::nullopt, where);
    if (count == 0 || count > accessor_count) fail(where + ".count " + std::to_string(count) + " is not from 1 to the accessor's " + std::to_string(accessor_count));
    if (!sparse.contains("indices") || !sparse.contains("values")) fail(where + " lacks its indices or values");
    const std::string indices_where = where + ".indices";
    const Json& indices = object(sparse["indices"], indices_where);
    const std::uint64_t index_type = integer(indices, "componentType", std::nullopt, indices_where);
    if (index_type != 5121 && index_type != 5123 && index_type != 5125) fail(indices_where + ".componentType " + std::to_string(index_type) + " is not an unsigned integer type");
    for (const auto& [part, part_where, size] : {std::tuple{&indices, indices_where, component_size(index_type)},
                                                 std::tuple{&object(sparse["values"], where + ".values"), where + ".values", element}}) {
      const std::size_t v = reference(*part, "bufferView", m_views.size(), "bufferViews", part_where);
      within(integer(*part, "byteOffset", 0, part_where), count * size, m_views[v].length, part_where, "bufferViews[" + std::to_string(v) + "]");
    }
  }

  void check_primitive(const Json& value, const std::string& where) const {
    const Json& primitive = object(value, where);
    if (!primitive.contains("attributes")) fail(where + " has no attributes");
    const Json& attributes = object(primitive["attributes"], where + ".attributes");
    std::uint64_t vertices = 0;
    for (const auto& [semantic, unused] : attributes.items()) {
      const std::size_t a = reference(attributes, semantic.c_str(), m_accessor_counts.size(), "accessors", where + ".attributes");
      if (semantic == "POSITION") vertices = m_accessor_counts[a];
    }
    if (primitive.contains("targets")) {
      const Json& targets = member_array(primitive, "targets", where);
      for (std::size_t t = 0; t < targets.size(); ++t) {
        const std::string target_where = where + ".targets[" + std::to_string(t) + "]";
        const Json& target = object(targets[t], target_where);
        for (const auto& [semantic, unused] : target.items()) reference(target, semantic.c_str(), m_accessor_counts.size(), "accessors", target_where);
      }
    }
    std::uint64_t corners = vertices;
    if (primitive.contains("indices")) corners = m_accessor_counts[reference(primitive, "indices", m_accessor_counts.size(), "accessors", where)];
    // assimp allocates count - 2 faces for strips and fans (count - 1 for line strips) in
    // unsigned arithmetic: too few corners wrap to an allocation of 2^64 faces.
    const std::uint64_t mode = integer(primitive, "mode", 4, where);
    const std::uint64_t needed = mode == 5 || mode == 6 ? 3 : mode == 2 || mode == 3 ? 2 : 0;
    if (corners < needed) fail(where + ": mode " + std::to_string(mode) + " needs " + std::to_string(needed) + " vertices, it has " + std::to_string(corners));
  }

  const Json& m_doc;
  const std::string& m_name;
  std::filesystem::path m_directory;
  std::optional<std::uint64_t> m_glb_bin;
  std::vector<std::uint64_t> m_buffers;  // stated byteLength, checked against the data
  std::vector<View> m_views;
  std::vector<std::uint64_t> m_accessor_counts;
};

}  // namespace

void check_gltf_bounds(const nlohmann::json& doc, const std::string& name, const std::filesystem::path& directory,
                       std::optional<std::uint64_t> glb_bin_length) {
  GltfBounds(doc, name, directory, glb_bin_length).check();
}

}  // namespace fissure::io_detail
