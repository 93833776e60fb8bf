#pragma once
/// Static stress fields cached on disk by content (issue 13: "a second run with a warm cache skips
/// all preparation"). A body's run starts from σ⁰, the recovered stress of its loads on its
/// supports; getting it the first time costs the FEM (assembly, the CHOLMOD factorisation, the
/// stress-recovery operator: a PreparedBody) and a solve. The field is keyed by what it depends on,
/// bit for bit: the mesh's nodes and tets, E and ν, the fixed dofs and the nodal forces (the
/// scenario already resolved on the mesh, so no option of it can be left out of the key), whether
/// it is recovered, and the versions of the code and of CHOLMOD that computed it. A warm run reads
/// the very doubles a cold run computed, so the fragments come out as the same bytes.
///
/// Entries share a disk_cache.hpp directory with the tet meshes: safe under concurrent runs,
/// size-capped, a damaged entry recomputed and overwritten.

#include "fissure/base/content_hash.hpp"
#include "fissure/fem/elastic_material.hpp"
#include "fissure/fem/stress.hpp"
#include "fissure/fracture/fracture_body.hpp"
#include "fissure/fracture/fracture_scenario.hpp"
#include "fissure/fracture/prepared_body.hpp"
#include "fissure/mesh/tet_mesh.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace fissure {

/// Identifies the code that computes a static stress field: Fissure's own version of assembly,
/// solve and recovery (bumped whenever a change alters a field some input gets) with CHOLMOD's
/// and Eigen's versions.
std::int64_t static_stress_version();

/// The key of the field of `forces` (3 per node, N) on `mesh` held at `fixed_dofs`.
Hash128 static_stress_key(const TetMesh& mesh, const ElasticMaterial& material, const std::vector<int>& fixed_dofs,
                          const Eigen::VectorXd& forces, bool recovered);

/// A field as bytes, and back: decode_stress_field() throws IoError naming `source_name` for a
/// payload that is truncated, of another size than `tets` rows, or not finite.
std::string encode_stress_field(const StressField& stress);
StressField decode_stress_field(std::string_view payload, Eigen::Index tets, const std::string& source_name);

/// σ of nodal forces on one body and scenario, each read from the cache when it is there, else
/// solved by a PreparedBody made at the first miss (so a warm run builds no FEM at all) and
/// stored. Not thread-safe: one per body and thread.
class CachedStaticStress {
public:
  /// An empty `directory` caches nothing: every field is solved.
  CachedStaticStress(std::shared_ptr<const TetMesh> mesh, const ElasticMaterial& material, FractureScenario scenario,
                     std::filesystem::path directory, std::uint64_t max_bytes, int threads = 1);

  /// PreparedBody::stress_of_forces(forces, recovered), through the cache. Throws InvalidInput
  /// as PreparedBody's constructor does (supports that leave a mechanism, …) when it has to solve.
  StressField stress_of_forces(const Eigen::VectorXd& forces, bool recovered = true);

  /// The body's fracture-side data: the PreparedBody's when one was made, else made here (ask
  /// after the fields, so a cold run does not make it twice).
  const FractureBody& fracture_body();

  /// Fields read from the cache and fields solved, so far.
  int loaded() const { return m_loaded; }
  int solved() const { return m_solved; }
  /// Whether a PreparedBody was made (some field missed the cache).
  bool prepared() const { return m_prepared != nullptr; }
  /// Why the last field solved could not be stored (the run goes on); empty otherwise.
  const std::string& warning() const { return m_warning; }

private:
  std::shared_ptr<const TetMesh> m_mesh;
  ElasticMaterial m_material;
  FractureScenario m_scenario;
  std::filesystem::path m_directory;
  std::uint64_t m_max_bytes = 0;
  int m_threads = 1;
  std::vector<int> m_fixed_dofs;
  std::unique_ptr<PreparedBody> m_prepared;
  std::unique_ptr<FractureBody> m_fracture_body;
  int m_loaded = 0, m_solved = 0;
  std::string m_warning;
};

}  // namespace fissure
