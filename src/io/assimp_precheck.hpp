#pragma once
// Private to io: what Fissure checks in a glTF, GLB, FBX or COLLADA file before assimp 5.2.5 sees it.
//
// Fuzzing found two ways to crash that assimp which its own checks (ValidateDataStructure
// included) do not catch: its parsers recurse once per nesting level, so a file nested 200,000
// levels deep ("extras": [[[[…]]]] in glTF, "A: { A: { …" in FBX) overflows the stack (SIGSEGV);
// and its glTF 1.0 reader aborts or segfaults on 1–3 % of corrupted files, against none of the
// same corruptions for glTF 2.0. So nesting is bounded and only glTF 2.0 is accepted. Under
// AddressSanitizer a third showed: assimp's glTF 2.0 bounds checks wrap and miss strides and
// sparse data, so it reads outside its buffers (silently in a release build); every byte range
// it will read is checked here (gltf_bounds.cpp). In binary FBX, assimp allocates and zeroes
// a compressed array's claimed size before inflating it (4.2 GB for a 2.5 kB file), so each one
// is inflated here first (fbx_arrays.cpp). Other FBX semantics assimp refuses cleanly by itself
// (measured: docs/architecture.md, "Surface import"; the binary FBX fuzz test).

#include <nlohmann/json_fwd.hpp>

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>

namespace fissure::io_detail {

/// Deepest nesting accepted: real glTF and FBX files nest less than 16 levels.
inline constexpr int kMaxAssimpNesting = 64;

/// Throws IoError naming `name` when `bytes` (the whole .gltf file, whose external buffers lie in
/// `directory`) is not JSON, nests deeper than kMaxAssimpNesting, is not glTF 2.x, or has a
/// buffer, buffer view or accessor reaching past its data (check_gltf_bounds).
void precheck_gltf(std::string_view bytes, const std::string& name, const std::filesystem::path& directory);
/// The same for a .glb file: its header must be GLB version 2 with a JSON chunk inside the file;
/// the first buffer without a URI is its BIN chunk.
void precheck_glb(std::string_view bytes, const std::string& name, const std::filesystem::path& directory);
/// Every range assimp reads: each buffer's byteLength within its real data (external file size,
/// decoded data: URI, or `glb_bin_length`); each buffer view within its buffer; each accessor's
/// byteOffset + (count - 1) * stride + element size within its buffer view, sparse indices and
/// values within theirs; mesh primitives and images referring to existing accessors and views.
void check_gltf_bounds(const nlohmann::json& doc, const std::string& name, const std::filesystem::path& directory,
                       std::optional<std::uint64_t> glb_bin_length);
/// ASCII or binary FBX: nesting of scopes (ASCII) or records (binary) bounded; array counts
/// within what the file can hold (ASCII: 2 bytes a value; binary, zlib-compressed: what the
/// stored bytes can inflate to); the binary record offsets must lie inside the file and inside
/// their parent record.
void precheck_fbx(std::string_view bytes, const std::string& name);
/// COLLADA (.dae): UTF-8 XML that parses, nests at most 512 elements deep, holds no skins, morphs,
/// animations or embedded <hex> images; every accessor an input reads stays inside its float
/// array for every index below its count, every <p> holds only indices (below their sources'
/// counts) in the number its primitive type, count, <vcount> and inputs call for, with one
/// VERTEX and one POSITION input; <instance_node>s form no cycle and expand to a bounded
/// hierarchy (collada_bounds.cpp). Returns the name attribute of each <node> by its id (only
/// where the two differ): assimp names nodes by id.
std::map<std::string, std::string> precheck_collada(std::string_view bytes, const std::string& name);
/// The `count` properties of one binary FBX record, bytes [at, end) of the file, walked as
/// assimp's tokenizer walks them: each array stored zlib-compressed must inflate to exactly its
/// count × element size bytes (fbx_arrays.cpp). What assimp checks itself stops the walk.
void check_fbx_properties(std::string_view bytes, std::size_t at, std::size_t end, std::uint64_t count,
                          const std::string& name);

}  // namespace fissure::io_detail
