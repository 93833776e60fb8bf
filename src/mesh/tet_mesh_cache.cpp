#include "fissure/mesh/tet_mesh_cache.hpp"

#include "fissure/base/disk_cache.hpp"
#include "fissure/base/error.hpp"

#include <cstring>

namespace fissure {
namespace {

constexpr CacheEntryFormat kFormat{"FISSTETS", 1};

}  // namespace

Hash128 tet_mesh_cache_key(const SurfaceMesh& surface, const TetrahedralizeOptions& o) {
  ContentHasher h;
  h.add("fissure tet mesh").add(tetrahedralize_version());
  h.add(surface.vertices).add(surface.faces);
  h.add(static_cast<std::int64_t>(o.target_tets)).add(o.count_tolerance).add(o.facet_angle_deg);
  h.add(o.cell_radius_edge_ratio).add(o.feature_angle_deg).add(o.sliver_bound_deg);
  h.add(o.perturb_time_limit_s).add(o.exude_time_limit_s).add(o.refuse_below_dihedral_deg);
  h.add(static_cast<std::int64_t>(o.seed));
  return h.finish();
}

std::string encode_tet_mesh(const TetMesh& mesh) {
  const std::int64_t counts[2] = {mesh.node_count(), mesh.tet_count()};
  std::string out;
  out.append(reinterpret_cast<const char*>(counts), sizeof counts);
  out.append(reinterpret_cast<const char*>(mesh.nodes().data()), sizeof(double) * static_cast<std::size_t>(mesh.nodes().size()));
  out.append(reinterpret_cast<const char*>(mesh.tets().data()), sizeof(int) * static_cast<std::size_t>(mesh.tets().size()));
  return out;
}

TetMesh decode_tet_mesh(std::string_view payload, const std::string& source_name) {
  std::int64_t counts[2];
  if (payload.size() < sizeof counts) throw IoError(source_name + ": cached tet mesh is truncated");
  std::memcpy(counts, payload.data(), sizeof counts);
  const std::int64_t nodes = counts[0], tets = counts[1];
  if (nodes < 4 || tets < 1 || nodes > (1LL << 31) || tets > (1LL << 31) ||
      payload.size() != sizeof counts + static_cast<std::size_t>(nodes) * 3 * sizeof(double) +
                            static_cast<std::size_t>(tets) * 4 * sizeof(int)) {
    throw IoError(source_name + ": cached tet mesh has a corrupt header");
  }
  Eigen::MatrixX3d n(nodes, 3);
  Eigen::MatrixX4i t(tets, 4);
  std::memcpy(n.data(), payload.data() + sizeof counts, sizeof(double) * static_cast<std::size_t>(n.size()));
  std::memcpy(t.data(), payload.data() + sizeof counts + sizeof(double) * static_cast<std::size_t>(n.size()),
              sizeof(int) * static_cast<std::size_t>(t.size()));
  try {
    return TetMesh(std::move(n), std::move(t), source_name);
  } catch (const InvalidInput& e) {
    throw IoError(std::string("cached tet mesh is invalid: ") + e.what());
  }
}

TetMeshCacheResult cached_tetrahedralize(const SurfaceMesh& surface, const TetrahedralizeOptions& options,
                                         const std::filesystem::path& directory, std::uint64_t max_bytes,
                                         const CancelToken* cancel) {
  const Hash128 key = tet_mesh_cache_key(surface, options);
  const std::string name = "tets-" + key.hex() + ".bin";
  if (std::optional<std::string> payload = read_cache_entry(directory, name, kFormat, key)) {
    try {
      return {decode_tet_mesh(*payload, surface.source_name), true, {}};
    } catch (const IoError&) {
      // Checksummed yet invalid: written by a broken build. Made again and overwritten below.
    }
  }
  TetMeshCacheResult out{tetrahedralize(surface, options, nullptr, nullptr, cancel), false, {}};
  const std::string problem = write_cache_entry(directory, name, kFormat, key, encode_tet_mesh(out.mesh), max_bytes);
  if (!problem.empty()) out.warning = "tet mesh not cached (" + problem + "); it will be made again next time";
  return out;
}

}  // namespace fissure
