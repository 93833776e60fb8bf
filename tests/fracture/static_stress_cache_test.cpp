// Static stress fields cached by content (static_stress_cache.hpp): a warm read is bit for bit the
// field a PreparedBody solves and builds no FEM; every input the field depends on (mesh, E, ν, the
// density of a free body, supports, forces, recovery) misses when changed; a damaged entry is
// solved again and rewritten; an unwritable cache warns and still solves.

#include "fissure/fracture/static_stress_cache.hpp"

#include "fissure/base/atomic_file.hpp"
#include "fissure/base/error.hpp"

#include "fracture_test_bodies.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>

namespace fissure {
namespace {

namespace fs = std::filesystem;

std::shared_ptr<const TetMesh> plate() { return test::plate_mesh({0.5, 0.4, 0.02}, 10, 8, 2); }

// The default patch's forces for 1 N: what a run's σ⁰ is solved for, up to its factor.
Eigen::VectorXd unit_forces(const TetMesh& mesh, const FractureScenario& scenario = {}) {
  return scenario_loads(mesh, scenario).unit_forces;
}

std::vector<fs::path> entries(const fs::path& dir) {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(dir)) out.push_back(e.path());
  return out;
}

TEST(StaticStressCache, AWarmReadIsTheSolvedFieldAndBuildsNoFem) {
  const fs::path dir = test::fresh_temp_dir("static-stress-cache-warm");
  const auto mesh = plate();
  const ElasticMaterial material;
  const Eigen::VectorXd f = unit_forces(*mesh);
  const StressField direct = PreparedBody(mesh, material, FractureScenario{}).stress_of_forces(f);

  CachedStaticStress cold(mesh, material, FractureScenario{}, dir, 1 << 30);
  EXPECT_TRUE(cold.stress_of_forces(f) == direct);
  EXPECT_EQ(cold.solved(), 1);
  EXPECT_TRUE(cold.prepared());
  EXPECT_TRUE(cold.warning().empty()) << cold.warning();
  ASSERT_EQ(entries(dir).size(), 1U);

  CachedStaticStress warm(mesh, material, FractureScenario{}, dir, 1 << 30);
  EXPECT_TRUE(warm.stress_of_forces(f) == direct) << "the cached doubles differ from a fresh solve";
  EXPECT_EQ(warm.loaded(), 1);
  EXPECT_EQ(warm.solved(), 0);
  EXPECT_FALSE(warm.prepared()) << "a warm read built the FEM";
  // Its fracture body is made without the FEM, and is the one a PreparedBody holds.
  const FractureBody& body = warm.fracture_body();
  const PreparedBody prepared(mesh, material, FractureScenario{});
  EXPECT_TRUE(body.surface_normals() == prepared.fracture_body().surface_normals());
  EXPECT_FALSE(warm.prepared());

  // A raw (unrecovered) field is another entry.
  EXPECT_TRUE(warm.stress_of_forces(f, false) == prepared.stress_of_forces(f, false));
  EXPECT_EQ(warm.solved(), 1);
}

TEST(StaticStressCache, EveryInputOfTheFieldIsInItsKey) {
  const auto mesh = plate();
  const ElasticMaterial material;
  const Eigen::VectorXd f = unit_forces(*mesh);
  const std::vector<int> held = scenario_fixed_dofs(*mesh, FractureScenario{});
  const Hash128 base = static_stress_key(*mesh, material, held, f, true);
  EXPECT_EQ(static_stress_key(*mesh, material, held, f, true), base);

  ElasticMaterial stiffer = material;
  stiffer.youngs_modulus *= 1.0 + 1e-15;
  EXPECT_NE(static_stress_key(*mesh, stiffer, held, f, true), base);
  ElasticMaterial other_nu = material;
  other_nu.poisson_ratio = 0.25;
  EXPECT_NE(static_stress_key(*mesh, other_nu, held, f, true), base);
  ElasticMaterial heavier = material;
  heavier.density *= 2.0;
  EXPECT_NE(static_stress_key(*mesh, heavier, held, f, true), base);

  Eigen::VectorXd g = f;
  Eigen::Index loaded_dof = 0;
  f.cwiseAbs().maxCoeff(&loaded_dof);
  g[loaded_dof] = std::nextafter(g[loaded_dof], 0.0);  // one ulp on the largest force
  EXPECT_NE(static_stress_key(*mesh, material, held, g, true), base);
  EXPECT_NE(static_stress_key(*mesh, material, held, 2.0 * f, true), base);
  EXPECT_NE(static_stress_key(*mesh, material, held, f, false), base);
  std::vector<int> fewer(held.begin(), held.end() - 1);
  EXPECT_NE(static_stress_key(*mesh, material, fewer, f, true), base);
  EXPECT_NE(static_stress_key(*mesh, material, {}, f, true), base);

  Eigen::MatrixX3d moved = mesh->nodes();
  moved(0, 0) = std::nextafter(moved(0, 0), 1.0);
  const TetMesh nudged(moved, mesh->tets());
  EXPECT_NE(static_stress_key(nudged, material, held, f, true), base);
}

TEST(StaticStressCache, AFreeBodyAndOtherSupportsAreSolvedAnew) {
  const fs::path dir = test::fresh_temp_dir("static-stress-cache-scenarios");
  const auto mesh = plate();
  const ElasticMaterial material;
  const Eigen::VectorXd f = unit_forces(*mesh);
  CachedStaticStress(mesh, material, FractureScenario{}, dir, 1 << 30).stress_of_forces(f);

  FractureScenario free;
  free.free_body = true;
  CachedStaticStress free_run(mesh, material, free, dir, 1 << 30);
  const StressField relieved = free_run.stress_of_forces(f);
  EXPECT_EQ(free_run.solved(), 1) << "a free body read the supported body's field";
  EXPECT_TRUE(relieved == PreparedBody(mesh, material, free).stress_of_forces(f));
  // Inertia relief balances the load by the body's mass distribution: a heavier free body is
  // another entry, read back as its own field.
  ElasticMaterial heavier = material;
  heavier.density *= 3.0;
  CachedStaticStress heavy(mesh, heavier, free, dir, 1 << 30);
  heavy.stress_of_forces(f);
  EXPECT_EQ(heavy.solved(), 1);
  CachedStaticStress heavy_again(mesh, heavier, free, dir, 1 << 30);
  heavy_again.stress_of_forces(f);
  EXPECT_EQ(heavy_again.loaded(), 1);
  EXPECT_EQ(entries(dir).size(), 3U);
}

TEST(StaticStressCache, ADamagedEntryIsSolvedAgainAndRewritten) {
  const fs::path dir = test::fresh_temp_dir("static-stress-cache-damaged");
  const auto mesh = plate();
  const Eigen::VectorXd f = unit_forces(*mesh);
  const StressField direct = CachedStaticStress(mesh, {}, FractureScenario{}, dir, 1 << 30).stress_of_forces(f);
  const fs::path entry = entries(dir).front();
  const std::string bytes = read_file(entry);
  for (const std::size_t at : {std::size_t{3}, bytes.size() / 2, bytes.size() - 1}) {
    std::string damaged = bytes;
    damaged[at] = static_cast<char>(damaged[at] ^ 0x5a);
    write_file_atomically(entry, damaged);
    CachedStaticStress run(mesh, {}, FractureScenario{}, dir, 1 << 30);
    EXPECT_TRUE(run.stress_of_forces(f) == direct) << "byte " << at;
    EXPECT_EQ(run.solved(), 1) << "a damaged entry was read (byte " << at << ")";
    CachedStaticStress again(mesh, {}, FractureScenario{}, dir, 1 << 30);
    EXPECT_TRUE(again.stress_of_forces(f) == direct);
    EXPECT_EQ(again.loaded(), 1) << "the entry was not rewritten whole (byte " << at << ")";
  }
  write_file_atomically(entry, bytes.substr(0, bytes.size() / 3));  // truncated
  CachedStaticStress truncated(mesh, {}, FractureScenario{}, dir, 1 << 30);
  EXPECT_TRUE(truncated.stress_of_forces(f) == direct);
  EXPECT_EQ(truncated.solved(), 1);
}

TEST(StaticStressCache, AnUnwritableCacheWarnsAndStillSolves) {
  const fs::path dir = test::fresh_temp_dir("static-stress-cache-unwritable");
  const fs::path blocker = dir / "file";
  write_file_atomically(blocker, "not a directory");
  const auto mesh = plate();
  CachedStaticStress run(mesh, {}, FractureScenario{}, blocker / "cache", 1 << 30);
  const StressField s = run.stress_of_forces(unit_forces(*mesh));
  EXPECT_GT(s.cwiseAbs().maxCoeff(), 0.0);
  EXPECT_NE(run.warning().find("stress field not cached"), std::string::npos) << run.warning();
  // No directory at all caches nothing and says nothing.
  CachedStaticStress uncached(mesh, {}, FractureScenario{}, {}, 0);
  EXPECT_TRUE(uncached.stress_of_forces(unit_forces(*mesh)) == s);
  EXPECT_TRUE(uncached.warning().empty());
}

TEST(StaticStressCache, DecodingRefusesPayloadsThatAreNoField) {
  StressField s = StressField::Random(5, 6);
  const std::string bytes = encode_stress_field(s);
  EXPECT_TRUE(decode_stress_field(bytes, 5, "m") == s);
  EXPECT_THROW(decode_stress_field(bytes, 6, "m"), IoError);                       // another mesh
  EXPECT_THROW(decode_stress_field(bytes.substr(0, 7), 5, "m"), IoError);          // no header
  EXPECT_THROW(decode_stress_field(bytes.substr(0, bytes.size() - 8), 5, "m"), IoError);
  s(2, 3) = std::numeric_limits<double>::quiet_NaN();
  try {
    decode_stress_field(encode_stress_field(s), 5, "slab.glb");
    FAIL() << "a NaN field was read";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("slab.glb"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace fissure
