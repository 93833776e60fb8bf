// Tet meshes cached by content (tet_mesh_cache.hpp): the cached mesh is bit for bit the one
// tetrahedralize() makes, a changed surface or option misses, a damaged entry is made again.

#include "fissure/mesh/tet_mesh_cache.hpp"

#include "fissure/base/atomic_file.hpp"
#include "fissure/base/error.hpp"
#include "fissure/mesh/tile.hpp"

#include "test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

namespace fissure {
namespace {

namespace fs = std::filesystem;

SurfaceMesh slab() {
  SurfaceMesh s = make_tile_surface({0.6, 0.4, 0.05});
  s.source_name = "slab";
  return s;
}

TetrahedralizeOptions small() {
  TetrahedralizeOptions o;
  o.target_tets = 600;
  return o;
}

TEST(TetMeshCache, AWarmReadIsTheMeshACleanRunMakes) {
  const fs::path dir = test::fresh_temp_dir("tet-cache-same");
  const TetMesh fresh = tetrahedralize(slab(), small());
  const TetMeshCacheResult cold = cached_tetrahedralize(slab(), small(), dir, 1 << 30);
  EXPECT_FALSE(cold.loaded);
  EXPECT_EQ(cold.warning, "");
  SurfaceMesh renamed = slab();
  renamed.source_name = "another name";  // names messages; not part of the key
  const TetMeshCacheResult warm = cached_tetrahedralize(renamed, small(), dir, 1 << 30);
  EXPECT_TRUE(warm.loaded);
  EXPECT_EQ(warm.mesh.source_name(), "another name");
  for (const TetMesh* m : {&cold.mesh, &warm.mesh}) {
    ASSERT_EQ(m->nodes().rows(), fresh.nodes().rows());
    EXPECT_TRUE((m->nodes().array() == fresh.nodes().array()).all());  // bit for bit, not to a tolerance
    EXPECT_TRUE((m->tets().array() == fresh.tets().array()).all());
  }
}

TEST(TetMeshCache, AChangedSurfaceOrOptionMisses) {
  const Hash128 base = tet_mesh_cache_key(slab(), small());
  SurfaceMesh moved = slab();
  moved.vertices(3, 0) = std::nextafter(moved.vertices(3, 0), 1.0);  // one ulp
  EXPECT_FALSE(tet_mesh_cache_key(moved, small()) == base);
  TetrahedralizeOptions finer = small();
  finer.target_tets = 601;
  EXPECT_FALSE(tet_mesh_cache_key(slab(), finer) == base);
  TetrahedralizeOptions seeded = small();
  seeded.seed = 1;
  EXPECT_FALSE(tet_mesh_cache_key(slab(), seeded) == base);
  TetrahedralizeOptions limited = small();
  limited.memory_limit_bytes = 123;  // only refuses; the mesh is the same
  EXPECT_TRUE(tet_mesh_cache_key(slab(), limited) == base);
}

TEST(TetMeshCache, ADamagedEntryIsMadeAgainAndRewritten) {
  const fs::path dir = test::fresh_temp_dir("tet-cache-damaged");
  const TetMeshCacheResult cold = cached_tetrahedralize(slab(), small(), dir, 1 << 30);
  const fs::path entry = dir / ("tets-" + tet_mesh_cache_key(slab(), small()).hex() + ".bin");
  ASSERT_TRUE(fs::exists(entry));
  std::string bytes = read_file(entry);
  bytes[bytes.size() / 2] = static_cast<char>(bytes[bytes.size() / 2] ^ 1);
  write_file_atomically(entry, bytes);
  const TetMeshCacheResult again = cached_tetrahedralize(slab(), small(), dir, 1 << 30);
  EXPECT_FALSE(again.loaded);
  EXPECT_TRUE((again.mesh.nodes().array() == cold.mesh.nodes().array()).all());
  EXPECT_TRUE(cached_tetrahedralize(slab(), small(), dir, 1 << 30).loaded);  // rewritten whole
}

TEST(TetMeshCache, AnUnwritableCacheWarnsAndStillMeshes) {
  const fs::path dir = test::fresh_temp_dir("tet-cache-unwritable");
  write_file_atomically(dir / "file", "x");
  const TetMeshCacheResult r = cached_tetrahedralize(slab(), small(), dir / "file" / "cache", 1 << 30);
  EXPECT_GT(r.mesh.tet_count(), 0);
  EXPECT_NE(r.warning.find("tet mesh not cached"), std::string::npos) << r.warning;
}

TEST(TetMeshCache, DecodingRefusesPayloadsThatAreNoMesh) {
  const TetMesh mesh = tetrahedralize(slab(), small());
  const std::string good = encode_tet_mesh(mesh);
  EXPECT_EQ(decode_tet_mesh(good, "x").tet_count(), mesh.tet_count());
  EXPECT_THROW(decode_tet_mesh(good.substr(0, good.size() - 1), "x"), IoError);
  EXPECT_THROW(decode_tet_mesh(good.substr(0, 8), "x"), IoError);
  std::string inverted = good;  // tet 0 with two nodes swapped: TetMesh's own check refuses it
  const std::size_t tets_at = 16 + sizeof(double) * 3 * static_cast<std::size_t>(mesh.node_count());
  int a = 0, b = 0;
  const std::size_t rows = static_cast<std::size_t>(mesh.tet_count());
  std::memcpy(&a, inverted.data() + tets_at, 4);             // tets(0, 0), column-major
  std::memcpy(&b, inverted.data() + tets_at + 4 * rows, 4);  // tets(0, 1)
  std::memcpy(inverted.data() + tets_at, &b, 4);
  std::memcpy(inverted.data() + tets_at + 4 * rows, &a, 4);
  EXPECT_THROW(decode_tet_mesh(inverted, "x"), IoError);
}

}  // namespace
}  // namespace fissure
