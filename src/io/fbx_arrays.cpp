// The typed properties of a binary FBX record, checked before assimp 5.2.5 reads them.
//
// assimp inflates a zlib-compressed array (encoding 1) into a buffer of count × element size
// bytes that it allocates and zeroes first (FBXParser.cpp, ReadBinaryDataArray), whatever the
// stream holds: PolygonVertexIndex claiming 2^31 − 1 ints in a 2.5 kB file took 4.2 GB and 14 s
// (`assimp info`; 10 GB in the fuzz test, BinaryFbxNeverCrashes). A stream shorter than its
// count is silently padded with zeros, vertices at the origin or index 0. So every compressed
// array is inflated here, through a fixed 64 kB buffer, and must give exactly its count's
// bytes. Plain arrays (encoding 0) assimp checks itself against their stored length.

#include "assimp_precheck.hpp"

#include "fissure/base/error.hpp"

#include <zlib.h>

#include <array>
#include <cstring>

namespace fissure::io_detail {
namespace {

std::uint32_t word_at(std::string_view bytes, std::size_t pos) {
  std::uint32_t w;
  std::memcpy(&w, bytes.data() + pos, 4);
  return w;  // FBX is little-endian, as is every machine Fissure is built for
}

// The size `stream` inflates to, up to `limit` + 1 bytes (more is not counted), or -1 when it is
// not a complete zlib stream.
std::int64_t inflated_size(std::string_view stream, std::uint64_t limit) {
  z_stream z{};
  if (inflateInit(&z) != Z_OK) throw std::bad_alloc();
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(stream.data()));
  z.avail_in = static_cast<uInt>(stream.size());
  std::array<Bytef, 1 << 16> scratch;
  std::uint64_t total = 0;
  int status = Z_OK;
  while (status == Z_OK && total <= limit) {
    z.next_out = scratch.data();
    z.avail_out = scratch.size();
    status = inflate(&z, Z_NO_FLUSH);
    total += scratch.size() - z.avail_out;
    if (status == Z_BUF_ERROR && z.avail_in == 0) break;  // the stream ends early
  }
  inflateEnd(&z);
  if (total > limit) return static_cast<std::int64_t>(total);
  return status == Z_STREAM_END ? static_cast<std::int64_t>(total) : -1;
}

}  // namespace

void check_fbx_properties(std::string_view bytes, std::size_t at, std::size_t end, std::uint64_t count,
                          const std::string& name) {
  for (std::uint64_t k = 0; k < count && at < end; ++k) {
    const std::size_t type_at = at;
    const char type = bytes[at++];
    std::uint64_t size = 0;
    switch (type) {
      case 'C': size = 1; break;
      case 'Y': size = 2; break;
      case 'I': case 'F': size = 4; break;
      case 'D': case 'L': size = 8; break;
      case 'R': case 'S':
        if (end - at < 4) return;
        size = 4 + std::uint64_t{word_at(bytes, at)};
        break;
      case 'f': case 'd': case 'l': case 'i': case 'c': {
        if (end - at < 12) return;
        const std::uint64_t elements = word_at(bytes, at), encoding = word_at(bytes, at + 4), stored = word_at(bytes, at + 8);
        size = 12 + stored;
        if (encoding != 1 || size > end - at) break;
        const std::uint64_t needed = elements * (type == 'c' ? 1 : type == 'f' || type == 'i' ? 4 : 8);
        const std::int64_t inflated = inflated_size(bytes.substr(at + 12, stored), needed);
        const std::string array = "an array of " + std::to_string(elements) + " values ('" + type + "', byte " +
                                  std::to_string(type_at) + ") stored compressed in " + std::to_string(stored) + " bytes";
        if (inflated < 0) throw IoError(name + ": corrupt FBX: " + array + " is not a complete zlib stream");
        if (static_cast<std::uint64_t>(inflated) != needed) {
          throw IoError(name + ": corrupt FBX: " + array + " inflates to " +
                        (static_cast<std::uint64_t>(inflated) > needed ? "at least " : "") + std::to_string(inflated) +
                        " bytes, not the " + std::to_string(needed) + " its count needs");
        }
        break;
      }
      default: return;  // 'b' (assimp takes the rest of the list) or unknown: assimp refuses it
    }
    if (size > end - at) return;
    at += static_cast<std::size_t>(size);
  }
}

}  // namespace fissure::io_detail
