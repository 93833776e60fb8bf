#include "fissure/fracture/static_stress_cache.hpp"

#include "fissure/base/disk_cache.hpp"
#include "fissure/base/error.hpp"
#include "fissure/fem/sparse_cholesky.hpp"

#include <Eigen/Core>

#include <cmath>
#include <cstring>
#include <utility>

namespace fissure {
namespace {

constexpr CacheEntryFormat kFormat{"FISSSTRS", 1};

}  // namespace

std::int64_t static_stress_version() {
  // Bump kAlgorithm when a change to the FEM (assembly, supports, inertia relief, the static
  // solve, stress recovery) changes the field some input gets: cached fields of the old code
  // then stop matching.
  constexpr std::int64_t kAlgorithm = 1;
  constexpr std::int64_t kEigen = 10000 * EIGEN_WORLD_VERSION + 100 * EIGEN_MAJOR_VERSION + EIGEN_MINOR_VERSION;
  return (kAlgorithm * 1000000 + kEigen) * 1000000000LL + sparse_cholesky_version();
}

Hash128 static_stress_key(const TetMesh& mesh, const ElasticMaterial& material, const std::vector<int>& fixed_dofs,
                          const Eigen::VectorXd& forces, bool recovered) {
  ContentHasher h;
  h.add("fissure static stress").add(static_stress_version());
  h.add(mesh.nodes()).add(mesh.tets());
  // Density matters only to a free body (inertia relief balances the loads by its mass); it is
  // keyed always, so the key needs no knowledge of the solver's cases.
  h.add(material.youngs_modulus).add(material.poisson_ratio).add(material.density);
  h.add(static_cast<std::int64_t>(fixed_dofs.size()));
  h.add_bytes(fixed_dofs.data(), fixed_dofs.size() * sizeof(int));
  h.add(forces);
  h.add(static_cast<std::int64_t>(recovered ? 1 : 0));
  return h.finish();
}

std::string encode_stress_field(const StressField& stress) {
  const std::int64_t rows = stress.rows();
  std::string out;
  out.append(reinterpret_cast<const char*>(&rows), sizeof rows);
  out.append(reinterpret_cast<const char*>(stress.data()), sizeof(double) * static_cast<std::size_t>(stress.size()));
  return out;
}

StressField decode_stress_field(std::string_view payload, Eigen::Index tets, const std::string& source_name) {
  std::int64_t rows = 0;
  if (payload.size() < sizeof rows) throw IoError(source_name + ": cached stress field is truncated");
  std::memcpy(&rows, payload.data(), sizeof rows);
  if (rows != tets || payload.size() != sizeof rows + static_cast<std::size_t>(rows) * 6 * sizeof(double)) {
    throw IoError(source_name + ": cached stress field has " + std::to_string(rows) + " rows for a mesh of " +
                  std::to_string(tets) + " tets");
  }
  StressField stress(rows, 6);
  std::memcpy(stress.data(), payload.data() + sizeof rows, sizeof(double) * static_cast<std::size_t>(stress.size()));
  if (!stress.allFinite()) throw IoError(source_name + ": cached stress field is not finite");
  return stress;
}

CachedStaticStress::CachedStaticStress(std::shared_ptr<const TetMesh> mesh, const ElasticMaterial& material,
                                       FractureScenario scenario, std::filesystem::path directory,
                                       std::uint64_t max_bytes, int threads)
    : m_mesh(std::move(mesh)),
      m_material(material),
      m_scenario(std::move(scenario)),
      m_directory(std::move(directory)),
      m_max_bytes(max_bytes),
      m_threads(threads) {
  if (!(m_scenario.up.norm() > 0.0)) throw InvalidInput("the up direction is zero");
  m_scenario.up.normalize();  // as PreparedBody does, so both resolve the same supports
  m_fixed_dofs = scenario_fixed_dofs(*m_mesh, m_scenario);
}

const FractureBody& CachedStaticStress::fracture_body() {
  if (m_prepared) return m_prepared->fracture_body();
  if (!m_fracture_body) m_fracture_body = std::make_unique<FractureBody>(m_mesh);
  return *m_fracture_body;
}

StressField CachedStaticStress::stress_of_forces(const Eigen::VectorXd& forces, bool recovered) {
  Hash128 key;
  std::string name;
  if (!m_directory.empty()) {
    key = static_stress_key(*m_mesh, m_material, m_fixed_dofs, forces, recovered);
    name = "stress-" + key.hex() + ".bin";
    if (std::optional<std::string> payload = read_cache_entry(m_directory, name, kFormat, key)) {
      try {
        StressField stress = decode_stress_field(*payload, m_mesh->tet_count(), m_mesh->source_name());
        ++m_loaded;
        return stress;
      } catch (const IoError&) {
        // Checksummed yet invalid: written by a broken build. Solved again and overwritten below.
      }
    }
  }
  if (!m_prepared) m_prepared = std::make_unique<PreparedBody>(m_mesh, m_material, m_scenario, m_threads);
  StressField stress = m_prepared->stress_of_forces(forces, recovered);
  ++m_solved;
  if (!m_directory.empty()) {
    const std::string problem = write_cache_entry(m_directory, name, kFormat, key, encode_stress_field(stress), m_max_bytes);
    if (!problem.empty()) m_warning = "stress field not cached (" + problem + "); it will be solved again next time";
  }
  return stress;
}

}  // namespace fissure
