#include "assimp_precheck.hpp"

#include "byte_cursor.hpp"

#include "fissure/base/error.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

namespace fissure::io_detail {
namespace {

[[noreturn]] void too_deep(const std::string& name, const char* what, std::size_t at) {
  throw IoError(name + ": " + what + " nest deeper than " + std::to_string(kMaxAssimpNesting) + " levels (byte " +
                std::to_string(at) + "); refused, as assimp would overflow its stack");
}

// Brackets outside JSON strings.
void check_json_depth(std::string_view json, const std::string& name, std::size_t offset) {
  int depth = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < json.size(); ++i) {
    const char c = json[i];
    if (in_string) {
      if (c == '\\') ++i;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxAssimpNesting) too_deep(name, "JSON arrays and objects", offset + i);
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
}

void check_gltf_json(std::string_view json, const std::string& name, std::size_t offset, const std::filesystem::path& directory,
                     std::optional<std::uint64_t> glb_bin_length) {
  check_json_depth(json, name, offset);
  const nlohmann::json doc = nlohmann::json::parse(json.begin(), json.end(), nullptr, false);
  if (doc.is_discarded()) throw IoError(name + ": corrupt glTF: its JSON does not parse");
  const nlohmann::json* asset = doc.is_object() && doc.contains("asset") ? &doc["asset"] : nullptr;
  const nlohmann::json* version = asset && asset->is_object() && asset->contains("version") ? &(*asset)["version"] : nullptr;
  if (!version || !version->is_string()) throw IoError(name + ": corrupt glTF: no asset.version");
  const std::string text = version->get<std::string>();
  if (text.rfind("2.", 0) != 0) {
    throw IoError(name + ": glTF " + text.substr(0, 20) +
                  " is not supported (Fissure reads glTF 2.0; assimp's glTF 1.0 reader crashes on damaged files); "
                  "re-export the model as glTF 2.0");
  }
  check_gltf_bounds(doc, name, directory, glb_bin_length);
}

}  // namespace

void precheck_gltf(std::string_view bytes, const std::string& name, const std::filesystem::path& directory) {
  check_gltf_json(bytes, name, 0, directory, std::nullopt);
}

void precheck_glb(std::string_view bytes, const std::string& name, const std::filesystem::path& directory) {
  ByteCursor c(bytes, name);
  c.enter_binary();
  if (bytes.substr(0, 4) != "glTF") c.fail("not a GLB file (no 'glTF' magic)");
  c.skip(4);
  const std::uint32_t version = c.binary<std::uint32_t>(false);
  if (version != 2) {
    c.fail("GLB version " + std::to_string(version) +
           " is not supported (Fissure reads glTF 2.0; assimp's glTF 1.0 reader crashes on damaged files)");
  }
  c.skip(4);  // total length: assimp checks it
  const std::uint32_t length = c.binary<std::uint32_t>(false);
  const std::uint32_t type = c.binary<std::uint32_t>(false);
  if (type != 0x4E4F534Au) c.fail("corrupt GLB: the first chunk is not JSON");
  if (length > c.remaining()) c.fail("truncated GLB: the JSON chunk of " + std::to_string(length) + " bytes is cut off");
  const std::size_t json_at = c.position();
  // The BIN chunk follows the JSON chunk padded to 4 bytes (assimp's arithmetic); what it holds is
  // what is really in the file, whatever its header claims.
  std::uint64_t bin_length = 0;
  const std::size_t padded = (static_cast<std::size_t>(length) + 3) / 4 * 4;
  if (c.remaining() >= padded + 8) {
    c.skip(padded);
    const std::uint32_t stated = c.binary<std::uint32_t>(false);
    if (c.binary<std::uint32_t>(false) == 0x004E4942u) bin_length = std::min<std::uint64_t>(stated, c.remaining());
  }
  check_gltf_json(bytes.substr(json_at, length), name, json_at, directory, bin_length);
}

void precheck_fbx(std::string_view bytes, const std::string& name) {
  constexpr std::string_view kBinaryMagic("Kaydara FBX Binary  \0", 21);
  if (bytes.substr(0, kBinaryMagic.size()) != kBinaryMagic) {
    // ASCII: "Name: values { … }" scopes; strings in double quotes; ';' comments to the line end.
    int depth = 0;
    for (std::size_t i = 0; i < bytes.size(); ++i) {
      const char c = bytes[i];
      if (c == '"') {
        const std::size_t close = bytes.find('"', i + 1);
        i = close == std::string_view::npos ? bytes.size() : close;
      } else if (c == ';') {
        const std::size_t newline = bytes.find('\n', i);
        i = newline == std::string_view::npos ? bytes.size() : newline;
      } else if (c == '*') {
        // An array's element count ("Vertices: *180 {"): assimp reserves that many values up
        // front, so 2000000000 cost 3 GB and 23 s under AddressSanitizer (which touches the
        // shadow of each allocation). Each value takes at least 2 bytes ("0,") in the file.
        std::uint64_t count = 0;
        std::size_t end = i + 1;
        for (; end < bytes.size() && bytes[end] >= '0' && bytes[end] <= '9'; ++end) {
          count = count > std::numeric_limits<std::uint64_t>::max() / 10 ? std::numeric_limits<std::uint64_t>::max()
                                                                          : count * 10 + static_cast<std::uint64_t>(bytes[end] - '0');
        }
        const std::uint64_t room = (bytes.size() - end) / 2 + 1;
        if (count > room) {
          throw IoError(name + ": corrupt FBX: an array of " + std::string(bytes.substr(i + 1, std::min<std::size_t>(end - i - 1, 24))) +
                        " values at byte " + std::to_string(i) + " cannot fit in the " + std::to_string(bytes.size() - end) +
                        " bytes left in the file");
        }
        i = end - 1;
      } else if (c == '{') {
        if (++depth > kMaxAssimpNesting) too_deep(name, "FBX scopes", i);
      } else if (c == '}') {
        --depth;
      }
    }
    return;
  }

  // Binary (the layout Blender documents): after the 27-byte header, records of
  // [end offset, property count, property bytes] (uint32, or uint64 from version 7500), a name
  // length byte, the name, the properties, then nested records up to the end offset, closed by
  // an all-zero record. Walked iteratively with a stack of end offsets.
  ByteCursor c(bytes, name);
  c.enter_binary();
  c.skip(23);
  const std::uint32_t version = c.binary<std::uint32_t>(false);
  const bool wide = version >= 7500;
  const std::size_t header = wide ? 25 : 13;
  std::vector<std::uint64_t> ends;
  while (true) {
    if (!ends.empty() && c.position() >= ends.back()) {
      if (c.position() > ends.back()) c.fail("corrupt FBX: a record runs past its parent's end");
      ends.pop_back();
      continue;
    }
    if (c.remaining() < header) {
      if (!ends.empty()) c.fail("truncated FBX: the file ends inside a record");
      return;  // top level without its closing null record: assimp decides
    }
    const std::size_t start = c.position();
    const std::uint64_t end = wide ? c.binary<std::uint64_t>(false) : c.binary<std::uint32_t>(false);
    const std::uint64_t property_count = wide ? c.binary<std::uint64_t>(false) : c.binary<std::uint32_t>(false);
    const std::uint64_t property_bytes = wide ? c.binary<std::uint64_t>(false) : c.binary<std::uint32_t>(false);
    const std::uint8_t name_length = c.binary<std::uint8_t>(false);
    if (end == 0) {
      if (ends.empty()) return;  // the null record that ends the top level; the footer follows
      continue;                  // the null record that closes a nested list
    }
    const std::uint64_t limit = ends.empty() ? bytes.size() : ends.back();
    if (end <= start || end > limit) c.fail("corrupt FBX: a record's end offset " + std::to_string(end) + " lies outside its parent");
    // Overflow-safe: an end inside the record's own header, or 2^64 − 1 property bytes.
    const std::uint64_t room = end > c.position() ? end - c.position() : 0;
    if (name_length > room || property_bytes > room - name_length) {
      c.fail("corrupt FBX: a record's name and properties run past its end");
    }
    c.skip(name_length);
    check_fbx_properties(bytes, c.position(), c.position() + static_cast<std::size_t>(property_bytes), property_count, name);
    c.skip(static_cast<std::size_t>(property_bytes));
    if (c.position() < end) {
      ends.push_back(end);  // nested records follow
      if (ends.size() > static_cast<std::size_t>(kMaxAssimpNesting)) too_deep(name, "FBX records", start);
    } else {
      c.seek(end);
    }
  }
}

}  // namespace fissure::io_detail
