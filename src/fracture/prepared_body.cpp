#include "fissure/fracture/prepared_body.hpp"

#include "fissure/base/error.hpp"

namespace fissure {
PreparedBody::PreparedBody(std::shared_ptr<const TetMesh> mesh, const ElasticMaterial& material,
                           const FractureScenario& scenario, int threads)
    : m_scenario(scenario),
      m_body(std::make_shared<const ElasticBody>(mesh, material, threads)),
      m_recovery(*mesh),
      m_fracture_body(mesh) {
  if (!(m_scenario.up.norm() > 0.0)) throw InvalidInput("the up direction is zero");
  m_scenario.up.normalize();
  if (m_scenario.free_body && !m_scenario.supports.empty()) throw InvalidInput("--free and --fix exclude each other");
  m_solver = std::make_unique<StaticSolver>(m_body, scenario_fixed_dofs(*mesh, m_scenario));
  ScenarioLoads loads = scenario_loads(*mesh, m_scenario);
  m_loads = std::move(loads.loads);
  m_default_load = loads.default_load;
  m_unit_load = std::move(loads.unit_forces);
}

Eigen::VectorXd PreparedBody::load_vector(const FractureParams& params) const {
  if (!m_default_load) return m_unit_load;
  return (params.load_factor * m_fracture_body.mass(params.density) * kStandardGravity) * m_unit_load;
}

StressField PreparedBody::initial_stress(const FractureParams& params, bool recovered) const {
  return stress_of_forces(load_vector(params), recovered);
}

StressField PreparedBody::stress_of_forces(const Eigen::VectorXd& f, bool recovered) const {
  if (f.size() != 3 * mesh().node_count()) throw InvalidInput("the force vector has the wrong size for the body");
  if (f.isZero(0.0)) return StressField::Zero(mesh().tet_count(), 6);
  const StaticSolution solution = m_solver->solve(f);
  if (!recovered) return compute_stress(*m_body, solution.displacement);
  PrincipalStressField field;
  compute_principal_stress(*m_body, solution.displacement, m_recovery, field);
  return field.stress;
}

}  // namespace fissure
