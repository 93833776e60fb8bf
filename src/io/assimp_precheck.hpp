#pragma once
// Private to io: what Fissure checks in a glTF, GLB or FBX file before assimp 5.2.5 sees it.
//
// Fuzzing found two ways to crash that assimp which its own checks (ValidateDataStructure
// included) do not catch: its parsers recurse once per nesting level, so a file nested 200,000
// levels deep ("extras": [[[[…]]]] in glTF, "A: { A: { …" in FBX) overflows the stack (SIGSEGV);
// and its glTF 1.0 reader aborts or segfaults on 1–3 % of corrupted files, against none of the
// same corruptions for glTF 2.0. So nesting is bounded and only glTF 2.0 is accepted; the rest
// (accessor and buffer bounds, FBX semantics) assimp refuses cleanly by itself (measured:
// docs/architecture.md, "Surface import").

#include <string>
#include <string_view>

namespace fissure::io_detail {

/// Deepest nesting accepted: real glTF and FBX files nest less than 16 levels.
inline constexpr int kMaxAssimpNesting = 64;

/// Throws IoError naming `name` when `bytes` (the whole .gltf file) is not JSON, nests deeper
/// than kMaxAssimpNesting, or is not glTF 2.x.
void precheck_gltf(std::string_view bytes, const std::string& name);
/// The same for a .glb file: its header must be GLB version 2 with a JSON chunk inside the file.
void precheck_glb(std::string_view bytes, const std::string& name);
/// ASCII or binary FBX: nesting of scopes (ASCII) or records (binary) bounded; the binary
/// record offsets must lie inside the file and inside their parent record.
void precheck_fbx(std::string_view bytes, const std::string& name);

}  // namespace fissure::io_detail
