#pragma once
/// Tet meshes cached on disk by content (issue 13: "meshes are computed at first need and cached on
/// disk by content hash"). A body's mesh is keyed by its surface (vertices and faces, bit for
/// bit), every option that shapes the mesh and tetrahedralize_version(), so a warm run gets the
/// very mesh a cold run makes (the same bytes downstream) and an edited body misses only its own
/// entry. Entries live in a disk_cache.hpp directory: safe under concurrent runs, size-capped,
/// a damaged entry recomputed.

#include "fissure/base/content_hash.hpp"
#include "fissure/base/progress.hpp"
#include "fissure/mesh/tetrahedralize.hpp"

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace fissure {

/// The key of the mesh tetrahedralize(surface, options) makes. The surface's name and look and
/// options.memory_limit_bytes (which only refuses) are not part of it.
Hash128 tet_mesh_cache_key(const SurfaceMesh& surface, const TetrahedralizeOptions& options);

/// The mesh's nodes and tets as bytes, and back: decode_tet_mesh() throws IoError naming
/// `source_name` for a payload that is truncated or not a valid mesh (TetMesh's own checks).
std::string encode_tet_mesh(const TetMesh& mesh);
TetMesh decode_tet_mesh(std::string_view payload, const std::string& source_name);

struct TetMeshCacheResult {
  TetMesh mesh;
  bool loaded = false;        ///< read from the cache rather than made
  std::string warning;        ///< set when the new mesh could not be cached (why; the run goes on)
};

/// tetrahedralize(surface, options), read from `directory` when an entry with its key is there,
/// else made and stored (the directory then pruned to `max_bytes`). The mesh names
/// `surface.source_name` in its messages whichever way it came.
TetMeshCacheResult cached_tetrahedralize(const SurfaceMesh& surface, const TetrahedralizeOptions& options,
                                         const std::filesystem::path& directory, std::uint64_t max_bytes,
                                         const CancelToken* cancel = nullptr);

}  // namespace fissure
