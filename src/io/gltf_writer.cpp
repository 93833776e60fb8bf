// glTF 2.0 (https://registry.khronos.org/glTF/specs/2.0/glTF-2.0.html): a node per part with
// its extras, a mesh per part whose primitives (one per material) share one vertex array.
#include "scene_encoders.hpp"

#include <nlohmann/json.hpp>

#include "fissure/base/error.hpp"

#include <bit>
#include <cstdint>
#include <cstring>
#include <limits>

namespace fissure::io_detail {
namespace {

static_assert(std::endian::native == std::endian::little, "the buffer is copied as glTF's little-endian bytes");

constexpr int kFloat = 5126, kUnsignedInt = 5125;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;
constexpr int kTriangles = 4;

// The binary buffer and the views and accessors into it.
class BufferBuilder {
public:
  BufferBuilder(nlohmann::ordered_json& views, nlohmann::ordered_json& accessors) : m_views(views), m_accessors(accessors) {}

  template <class T>
  int add(const std::vector<T>& values, int component_type, const char* type, int count, int target,
          nlohmann::ordered_json extra = nlohmann::ordered_json::object()) {
    while (m_bytes.size() % 4 != 0) m_bytes.push_back('\0');  // every view 4-aligned
    const std::size_t offset = m_bytes.size(), length = values.size() * sizeof(T);
    m_bytes.resize(offset + length);
    if (length) std::memcpy(m_bytes.data() + offset, values.data(), length);
    m_views.push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", length}, {"target", target}});
    nlohmann::ordered_json accessor = {{"bufferView", m_views.size() - 1},
                                       {"componentType", component_type},
                                       {"count", count},
                                       {"type", type}};
    for (auto& [key, value] : extra.items()) accessor[key] = value;
    m_accessors.push_back(std::move(accessor));
    return static_cast<int>(m_accessors.size()) - 1;
  }

  std::string& bytes() { return m_bytes; }

private:
  nlohmann::ordered_json& m_views;
  nlohmann::ordered_json& m_accessors;
  std::string m_bytes;
};

std::string base64(const std::string& bytes) {
  static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::uint32_t n = static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i])) << 16 |
                            (i + 1 < bytes.size() ? static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i + 1])) << 8 : 0u) |
                            (i + 2 < bytes.size() ? static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i + 2])) : 0u);
    out += digits[n >> 18 & 63];
    out += digits[n >> 12 & 63];
    out += i + 1 < bytes.size() ? digits[n >> 6 & 63] : '=';
    out += i + 2 < bytes.size() ? digits[n & 63] : '=';
  }
  return out;
}

}  // namespace

std::string encode_gltf(const ExportScene& scene, bool binary) {
  nlohmann::ordered_json views = nlohmann::ordered_json::array(), accessors = nlohmann::ordered_json::array();
  nlohmann::ordered_json nodes = nlohmann::ordered_json::array(), meshes = nlohmann::ordered_json::array();
  BufferBuilder buffer(views, accessors);
  for (const ExportPart& part : scene.parts) {
    nlohmann::ordered_json node = {{"name", part.name}};
    if (part.triangles.rows() > 0) {
      const int n = static_cast<int>(part.vertices.rows());
      std::vector<float> positions(static_cast<std::size_t>(n) * 3), uvs(static_cast<std::size_t>(n) * 2);
      std::vector<float> low(3, std::numeric_limits<float>::infinity()), high(3, -std::numeric_limits<float>::infinity());
      for (int v = 0; v < n; ++v) {
        for (int i = 0; i < 3; ++i) {
          const float x = static_cast<float>(part.vertices(v, i));
          positions[static_cast<std::size_t>(3 * v + i)] = x;
          low[static_cast<std::size_t>(i)] = std::min(low[static_cast<std::size_t>(i)], x);
          high[static_cast<std::size_t>(i)] = std::max(high[static_cast<std::size_t>(i)], x);
        }
        if (part.uvs.rows() == 0) continue;
        // glTF's v runs down the image; the UVs given run up it.
        uvs[static_cast<std::size_t>(2 * v)] = static_cast<float>(part.uvs(v, 0));
        uvs[static_cast<std::size_t>(2 * v + 1)] = static_cast<float>(1.0 - part.uvs(v, 1));
      }
      nlohmann::ordered_json attributes = {{"POSITION", buffer.add(positions, kFloat, "VEC3", n, kArrayBuffer, {{"min", low}, {"max", high}})}};
      if (part.uvs.rows() > 0) attributes["TEXCOORD_0"] = buffer.add(uvs, kFloat, "VEC2", n, kArrayBuffer);
      nlohmann::ordered_json primitives = nlohmann::ordered_json::array();
      for (std::size_t m = 0; m < scene.materials.size(); ++m) {
        std::vector<std::uint32_t> indices;
        for (Eigen::Index t = 0; t < part.triangles.rows(); ++t)
          if (part.triangle_material[static_cast<std::size_t>(t)] == static_cast<int>(m))
            for (int i = 0; i < 3; ++i) indices.push_back(static_cast<std::uint32_t>(part.triangles(t, i)));
        if (indices.empty()) continue;
        const int index = buffer.add(indices, kUnsignedInt, "SCALAR", static_cast<int>(indices.size()), kElementArrayBuffer);
        primitives.push_back({{"attributes", attributes},
                              {"indices", index},
                              {"material", m},
                              {"mode", kTriangles}});
      }
      node["mesh"] = meshes.size();
      meshes.push_back({{"name", part.name}, {"primitives", primitives}});
    }
    if (part.linear.isIdentity(0.0)) {
      node["translation"] = {part.translation.x(), part.translation.y(), part.translation.z()};
    } else {
      // A rotation or scale: the node's matrix, column-major, as glTF stores it.
      nlohmann::ordered_json matrix = nlohmann::ordered_json::array();
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
          matrix.push_back(r == 3 ? (c == 3 ? 1.0 : 0.0) : c == 3 ? part.translation(r) : part.linear(r, c));
      node["matrix"] = matrix;
    }
    node["extras"] = nlohmann::ordered_json::parse(part.extras_json);
    nodes.push_back(std::move(node));
  }
  nlohmann::ordered_json root_nodes = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < scene.parts.size(); ++i) {
    const int parent = scene.parts[i].parent;
    if (parent < 0) {
      root_nodes.push_back(i);
    } else {
      nodes[static_cast<std::size_t>(parent)]["children"].push_back(i);
    }
  }
  nlohmann::ordered_json materials = nlohmann::ordered_json::array(), images = nlohmann::ordered_json::array(),
                        textures = nlohmann::ordered_json::array();
  for (const ExportMaterial& m : scene.materials) {
    nlohmann::ordered_json pbr = {{"baseColorFactor", {m.colour.x(), m.colour.y(), m.colour.z(), 1.0}},
                                  {"metallicFactor", 0.0},
                                  {"roughnessFactor", 0.9}};
    if (!m.texture.empty()) {
      pbr["baseColorTexture"] = {{"index", textures.size()}};
      textures.push_back({{"source", images.size()}});
      images.push_back({{"uri", m.texture}});
    }
    materials.push_back({{"name", m.name}, {"pbrMetallicRoughness", pbr}});
  }

  std::string& bytes = buffer.bytes();
  while (bytes.size() % 4 != 0) bytes.push_back('\0');
  nlohmann::ordered_json buffer_json = {{"byteLength", bytes.size()}};
  if (!binary) buffer_json["uri"] = "data:application/octet-stream;base64," + base64(bytes);
  nlohmann::ordered_json gltf = {{"asset", {{"version", "2.0"}, {"generator", "Fissure"}}},
                                 {"scene", 0},
                                 {"scenes", {{{"nodes", root_nodes}, {"extras", nlohmann::ordered_json::parse(scene.extras_json)}}}},
                                 {"nodes", nodes}};
  if (!meshes.empty()) gltf["meshes"] = meshes;
  if (!materials.empty()) gltf["materials"] = materials;
  if (!textures.empty()) {
    gltf["textures"] = textures;
    gltf["images"] = images;
  }
  if (!bytes.empty()) {
    gltf["buffers"] = {buffer_json};
    gltf["bufferViews"] = views;
    gltf["accessors"] = accessors;
  }
  std::string json = gltf.dump(binary ? -1 : 1);
  if (!binary) return json + "\n";

  // GLB: a 12-byte header, the JSON chunk padded with spaces, the BIN chunk padded with zeros.
  while (json.size() % 4 != 0) json += ' ';
  std::string out;
  const std::size_t total = 12 + 8 + json.size() + (bytes.empty() ? 0 : 8 + bytes.size());
  if (total > 0xffffffffu) throw InvalidInput("the scene needs " + std::to_string(total) + " bytes, more than a GLB holds (4 GiB)");
  append_bytes<std::uint32_t>(out, 0x46546C67u);  // "glTF"
  append_bytes<std::uint32_t>(out, 2);
  append_bytes<std::uint32_t>(out, static_cast<std::uint32_t>(total));
  append_bytes<std::uint32_t>(out, static_cast<std::uint32_t>(json.size()));
  append_bytes<std::uint32_t>(out, 0x4E4F534Au);  // "JSON"
  out += json;
  if (!bytes.empty()) {
    append_bytes<std::uint32_t>(out, static_cast<std::uint32_t>(bytes.size()));
    append_bytes<std::uint32_t>(out, 0x004E4942u);  // "BIN\0"
    out += bytes;
  }
  return out;
}

}  // namespace fissure::io_detail
