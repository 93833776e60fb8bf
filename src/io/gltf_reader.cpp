// The inverse of gltf_writer.cpp for the files it writes (include/fissure/io/gltf_reader.hpp).
// Every index and every byte range is checked before use; `where` names the element being read
// so a refusal says which one.
#include "fissure/io/gltf_reader.hpp"

#include "fissure/base/atomic_file.hpp"
#include "fissure/base/error.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace fissure {
namespace {

using Json = nlohmann::ordered_json;

constexpr int kFloat = 5126, kUnsignedInt = 5125, kTriangles = 4;

struct Refusal {
  std::string message;
};

[[noreturn]] void refuse(const std::string& message) { throw Refusal{message}; }

std::uint32_t read_u32(const std::string& bytes, std::size_t at) {
  std::uint32_t v = 0;
  std::memcpy(&v, bytes.data() + at, 4);  // little-endian host (gltf_writer.cpp asserts it)
  return v;
}

std::string decode_base64(const std::string& text, std::size_t from) {
  auto digit = [](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    return -1;
  };
  const std::size_t n = text.size() - from;
  if (n % 4 != 0) refuse("its buffer's base64 data is not a multiple of 4 characters");
  std::string out;
  out.reserve(n / 4 * 3);
  for (std::size_t i = from; i < text.size(); i += 4) {
    int d[4];
    int pad = 0;
    for (int k = 0; k < 4; ++k) {
      const char c = text[i + static_cast<std::size_t>(k)];
      if (c == '=' && i + 4 == text.size() && k >= 2) {
        d[k] = 0;
        ++pad;
        continue;
      }
      if (pad > 0 || (d[k] = digit(c)) < 0) refuse("its buffer's base64 data has a bad character at " + std::to_string(i + static_cast<std::size_t>(k)));
    }
    const std::uint32_t word = static_cast<std::uint32_t>(d[0]) << 18 | static_cast<std::uint32_t>(d[1]) << 12 |
                               static_cast<std::uint32_t>(d[2]) << 6 | static_cast<std::uint32_t>(d[3]);
    out += static_cast<char>(word >> 16 & 0xff);
    if (pad < 2) out += static_cast<char>(word >> 8 & 0xff);
    if (pad < 1) out += static_cast<char>(word & 0xff);
  }
  return out;
}

// Element `index` of the array `key`, or a refusal naming it.
const Json& element(const Json& gltf, const char* key, const Json& index_value, const std::string& who) {
  if (!index_value.is_number_unsigned()) refuse(who + ": its " + key + " index is not a non-negative integer");
  const std::uint64_t index = index_value.get<std::uint64_t>();
  if (!gltf.contains(key) || !gltf[key].is_array() || index >= gltf[key].size())
    refuse(who + ": " + key + " " + std::to_string(index) + " does not exist");
  return gltf[key][static_cast<std::size_t>(index)];
}

class Reader {
public:
  Reader(const Json& gltf, std::string bin) : m_gltf(gltf), m_bin(std::move(bin)) {}

  // The values of accessor `index`, which must hold `components` values of `component_type` each.
  template <class T>
  std::vector<T> accessor(const Json& index, int component_type, const char* type, int components, const std::string& who) {
    const Json& a = element(m_gltf, "accessors", index, who);
    const std::string name = "accessor " + index.dump();
    if (a.value("componentType", -1) != component_type || a.value("type", "") != type)
      refuse(name + ": expected " + type + " of component type " + std::to_string(component_type));
    const Json& count_value = a.contains("count") ? a["count"] : Json();
    if (!count_value.is_number_unsigned()) refuse(name + ": no count");
    const std::uint64_t count = count_value.get<std::uint64_t>();
    const Json& view = element(m_gltf, "bufferViews", a.contains("bufferView") ? a["bufferView"] : Json(), name);
    const std::string view_name = "bufferView " + a["bufferView"].dump();
    if (view.value("buffer", -1) != 0) refuse(view_name + ": not in buffer 0");
    const std::uint64_t offset = view.value("byteOffset", std::uint64_t{0}), length = view.value("byteLength", std::uint64_t{0});
    if (offset > m_bin.size() || length > m_bin.size() - offset)
      refuse(view_name + ": bytes " + std::to_string(offset) + " + " + std::to_string(length) + " run past the buffer's " +
             std::to_string(m_bin.size()));
    if (count > length / (sizeof(T) * static_cast<std::uint64_t>(components)) ||
        count * sizeof(T) * static_cast<std::uint64_t>(components) != length)
      refuse(name + ": " + std::to_string(count) + " values do not fill its view's " + std::to_string(length) + " bytes");
    std::vector<T> values(static_cast<std::size_t>(count) * static_cast<std::size_t>(components));
    if (length) std::memcpy(values.data(), m_bin.data() + offset, static_cast<std::size_t>(length));
    return values;
  }

  ExportScene scene() {
    ExportScene out;
    if (!m_gltf.is_object()) refuse("not a JSON object");
    const Json& asset = m_gltf.contains("asset") ? m_gltf["asset"] : Json();
    if (!asset.is_object() || asset.value("generator", "") != "Fissure")
      refuse("not written by Fissure (its asset.generator is not \"Fissure\"); only files Fissure wrote can be read back");
    read_materials(out);
    const Json& nodes = m_gltf.contains("nodes") ? m_gltf["nodes"] : Json();
    if (!nodes.is_array()) refuse("no nodes");
    out.parts.resize(nodes.size());
    std::vector<int> parent(nodes.size(), -1);
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      const std::string who = "node " + std::to_string(i);
      const Json& node = nodes[i];
      if (!node.is_object()) refuse(who + ": not an object");
      ExportPart& part = out.parts[i];
      part.name = node.value("name", "");
      if (node.contains("children")) {
        if (!node["children"].is_array()) refuse(who + ": its children are not an array");
        for (const Json& c : node["children"]) {
          if (!c.is_number_unsigned() || c.get<std::uint64_t>() >= nodes.size()) refuse(who + ": child " + c.dump() + " does not exist");
          const std::size_t child = c.get<std::size_t>();
          // The writer's order: a parent before its children, each child once.
          if (child <= i || parent[child] >= 0) refuse(who + ": child " + std::to_string(child) + " comes before it or has two parents");
          parent[child] = static_cast<int>(i);
        }
      }
      read_transform(node, part, who);
      if (node.contains("extras")) {
        if (!node["extras"].is_object()) refuse(who + ": its extras are not an object");
        part.extras_json = node["extras"].dump();
      }
      if (node.contains("mesh")) read_mesh(element(m_gltf, "meshes", node["mesh"], who), part, out, "mesh " + node["mesh"].dump());
    }
    for (std::size_t i = 0; i < nodes.size(); ++i) out.parts[i].parent = parent[i];
    const Json& scenes = m_gltf.contains("scenes") ? m_gltf["scenes"] : Json();
    if (scenes.is_array() && !scenes.empty() && scenes[0].is_object()) {
      const Json& s = scenes[0];
      if (s.contains("nodes")) {
        if (!s["nodes"].is_array()) refuse("scene 0: its nodes are not an array");
        for (const Json& n : s["nodes"])
          if (!n.is_number_unsigned() || n.get<std::uint64_t>() >= nodes.size() || parent[n.get<std::size_t>()] >= 0)
            refuse("scene 0: root node " + n.dump() + " does not exist or has a parent");
      }
      if (s.contains("extras")) {
        if (!s["extras"].is_object()) refuse("scene 0: its extras are not an object");
        out.extras_json = s["extras"].dump();
      }
    }
    return out;
  }

private:
  void read_materials(ExportScene& out) {
    if (!m_gltf.contains("materials")) return;
    if (!m_gltf["materials"].is_array()) refuse("its materials are not an array");
    for (std::size_t i = 0; i < m_gltf["materials"].size(); ++i) {
      const std::string who = "material " + std::to_string(i);
      const Json& m = m_gltf["materials"][i];
      if (!m.is_object()) refuse(who + ": not an object");
      ExportMaterial e;
      e.name = m.value("name", "");
      const Json& pbr = m.contains("pbrMetallicRoughness") ? m["pbrMetallicRoughness"] : Json::object();
      if (pbr.contains("baseColorFactor")) {
        const Json& c = pbr["baseColorFactor"];
        if (!c.is_array() || c.size() != 4) refuse(who + ": its baseColorFactor is not 4 numbers");
        for (int k = 0; k < 3; ++k) {
          if (!c[static_cast<std::size_t>(k)].is_number()) refuse(who + ": its baseColorFactor is not 4 numbers");
          e.colour(k) = c[static_cast<std::size_t>(k)].get<double>();
        }
      }
      if (pbr.contains("baseColorTexture")) {
        const Json& t = pbr["baseColorTexture"];
        const Json& texture = element(m_gltf, "textures", t.is_object() && t.contains("index") ? t["index"] : Json(), who);
        const Json& image = element(m_gltf, "images", texture.is_object() && texture.contains("source") ? texture["source"] : Json(),
                                    who + "'s texture");
        if (!image.is_object() || !image.contains("uri") || !image["uri"].is_string())
          refuse(who + ": its texture's image has no URI (an embedded image cannot be read back)");
        e.texture = image["uri"].get<std::string>();
      }
      out.materials.push_back(std::move(e));
    }
  }

  static void read_transform(const Json& node, ExportPart& part, const std::string& who) {
    if (node.contains("matrix")) {
      const Json& m = node["matrix"];
      if (!m.is_array() || m.size() != 16) refuse(who + ": its matrix is not 16 numbers");
      double v[16];
      for (std::size_t k = 0; k < 16; ++k) {
        if (!m[k].is_number()) refuse(who + ": its matrix is not 16 numbers");
        v[k] = m[k].get<double>();
      }
      // Column-major; the last row must be (0 0 0 1): an affine map.
      if (v[3] != 0.0 || v[7] != 0.0 || v[11] != 0.0 || v[15] != 1.0) refuse(who + ": its matrix is not affine");
      for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) part.linear(r, c) = v[4 * c + r];
      part.translation = Eigen::Vector3d(v[12], v[13], v[14]);
    } else if (node.contains("translation")) {
      const Json& t = node["translation"];
      if (!t.is_array() || t.size() != 3 || !t[0].is_number() || !t[1].is_number() || !t[2].is_number())
        refuse(who + ": its translation is not 3 numbers");
      part.translation = Eigen::Vector3d(t[0].get<double>(), t[1].get<double>(), t[2].get<double>());
    }
    if (node.contains("rotation") || node.contains("scale")) refuse(who + ": a rotation or scale Fissure does not write");
    if (!part.linear.allFinite() || !part.translation.allFinite()) refuse(who + ": its transform is not finite");
  }

  void read_mesh(const Json& mesh, ExportPart& part, const ExportScene& out, const std::string& who) {
    const Json& primitives = mesh.is_object() && mesh.contains("primitives") ? mesh["primitives"] : Json();
    if (!primitives.is_array() || primitives.empty()) refuse(who + ": no primitives");
    const Json& first = primitives[0];
    const Json& attributes = first.is_object() && first.contains("attributes") ? first["attributes"] : Json();
    if (!attributes.is_object() || !attributes.contains("POSITION")) refuse(who + ": primitive 0 has no POSITION");
    const std::vector<float> positions = accessor<float>(attributes["POSITION"], kFloat, "VEC3", 3, who);
    const Eigen::Index n = static_cast<Eigen::Index>(positions.size() / 3);
    part.vertices.resize(n, 3);
    for (Eigen::Index v = 0; v < n; ++v)
      for (int i = 0; i < 3; ++i) part.vertices(v, i) = positions[static_cast<std::size_t>(3 * v + i)];
    if (!part.vertices.allFinite()) refuse(who + ": a position is not finite");
    if (attributes.contains("TEXCOORD_0")) {
      const std::vector<float> uvs = accessor<float>(attributes["TEXCOORD_0"], kFloat, "VEC2", 2, who);
      if (static_cast<Eigen::Index>(uvs.size() / 2) != n) refuse(who + ": TEXCOORD_0 and POSITION differ in count");
      part.uvs.resize(n, 2);
      // glTF's v runs down the image; ExportPart's up it (gltf_writer.cpp).
      for (Eigen::Index v = 0; v < n; ++v) {
        part.uvs(v, 0) = uvs[static_cast<std::size_t>(2 * v)];
        part.uvs(v, 1) = 1.0 - static_cast<double>(uvs[static_cast<std::size_t>(2 * v + 1)]);
      }
      if (!part.uvs.allFinite()) refuse(who + ": a UV is not finite");
    }
    std::vector<std::uint32_t> all;
    for (std::size_t p = 0; p < primitives.size(); ++p) {
      const std::string prim = who + " primitive " + std::to_string(p);
      const Json& primitive = primitives[p];
      if (!primitive.is_object() || primitive.value("attributes", Json()) != attributes)
        refuse(prim + ": its attributes differ from primitive 0's (Fissure's primitives share one vertex array)");
      if (primitive.value("mode", kTriangles) != kTriangles) refuse(prim + ": not triangles");
      if (!primitive.contains("material") || !primitive["material"].is_number_unsigned() ||
          primitive["material"].get<std::uint64_t>() >= out.materials.size())
        refuse(prim + ": no material, or one that does not exist");
      const int material = primitive["material"].get<int>();
      if (!primitive.contains("indices")) refuse(prim + ": no indices");
      const std::vector<std::uint32_t> indices = accessor<std::uint32_t>(primitive["indices"], kUnsignedInt, "SCALAR", 1, prim);
      if (indices.size() % 3 != 0) refuse(prim + ": " + std::to_string(indices.size()) + " indices, not a multiple of 3");
      for (std::uint32_t i : indices)
        if (i >= static_cast<std::uint64_t>(n)) refuse(prim + ": index " + std::to_string(i) + " of " + std::to_string(n) + " vertices");
      all.insert(all.end(), indices.begin(), indices.end());
      part.triangle_material.insert(part.triangle_material.end(), indices.size() / 3, material);
    }
    part.triangles.resize(static_cast<Eigen::Index>(all.size() / 3), 3);
    for (Eigen::Index t = 0; t < part.triangles.rows(); ++t)
      for (int i = 0; i < 3; ++i) part.triangles(t, i) = static_cast<int>(all[static_cast<std::size_t>(3 * t + i)]);
  }

  const Json& m_gltf;
  std::string m_bin;
};

}  // namespace

ExportScene decode_fissure_gltf(const std::string& bytes, const std::string& name) {
  try {
    std::string json_text, bin;
    bool have_bin = false;
    if (bytes.size() >= 4 && bytes.compare(0, 4, "glTF") == 0) {
      if (bytes.size() < 20) refuse("a GLB shorter than its 20-byte header");
      if (read_u32(bytes, 4) != 2) refuse("GLB version " + std::to_string(read_u32(bytes, 4)) + ", not 2");
      if (read_u32(bytes, 8) != bytes.size())
        refuse("its GLB header gives " + std::to_string(read_u32(bytes, 8)) + " bytes, the file has " + std::to_string(bytes.size()));
      const std::size_t json_length = read_u32(bytes, 12);
      if (read_u32(bytes, 16) != 0x4E4F534Au || json_length > bytes.size() - 20) refuse("its first GLB chunk is not a JSON chunk inside the file");
      json_text = bytes.substr(20, json_length);
      std::size_t at = 20 + json_length;
      if (at < bytes.size()) {
        if (bytes.size() - at < 8) refuse("a GLB chunk header cut short at byte " + std::to_string(at));
        const std::size_t bin_length = read_u32(bytes, at);
        if (read_u32(bytes, at + 4) != 0x004E4942u || bin_length > bytes.size() - at - 8)
          refuse("its second GLB chunk is not a BIN chunk inside the file");
        bin = bytes.substr(at + 8, bin_length);
        have_bin = true;
      }
    } else {
      json_text = bytes;
    }
    const Json gltf = Json::parse(json_text, nullptr, false);
    if (gltf.is_discarded()) refuse("its JSON does not parse");
    if (gltf.is_object() && gltf.contains("buffers")) {
      const Json& buffers = gltf["buffers"];
      if (!buffers.is_array() || buffers.size() != 1 || !buffers[0].is_object()) refuse("not exactly one buffer");
      const Json& buffer = buffers[0];
      if (buffer.contains("uri")) {
        const std::string prefix = "data:application/octet-stream;base64,";
        if (have_bin || !buffer["uri"].is_string() || buffer["uri"].get<std::string>().rfind(prefix, 0) != 0)
          refuse("buffer 0 is not embedded as base64 data (Fissure embeds its buffer)");
        bin = decode_base64(buffer["uri"].get<std::string>(), prefix.size());
      } else if (!have_bin) {
        refuse("buffer 0 has neither a URI nor a GLB BIN chunk");
      }
      if (!buffer.contains("byteLength") || !buffer["byteLength"].is_number_unsigned() ||
          buffer["byteLength"].get<std::uint64_t>() != bin.size())
        refuse("buffer 0's byteLength is not its " + std::to_string(bin.size()) + " bytes");
    }
    Reader reader(gltf, std::move(bin));
    return reader.scene();
  } catch (const Refusal& r) {
    throw InvalidInput(name + ": " + r.message);
  } catch (const nlohmann::json::exception& e) {
    // A value of the wrong JSON type that the checks above did not foresee.
    throw InvalidInput(name + ": not a glTF Fissure wrote (" + e.what() + ")");
  }
}

ExportScene read_fissure_gltf(const std::filesystem::path& path) {
  return decode_fissure_gltf(read_file(path), path.string());
}

}  // namespace fissure
