#pragma once
/// A body made ready to fracture, once per (mesh, elastic material, scenario), and shared by every
/// run on it: its FEM (K, a CHOLMOD factorisation with its supports), the stress-recovery
/// operator, the fracture-side data (FractureBody) and the unit load. A run then costs one pair
/// of triangular solves for σ⁰ plus the simulation. Immutable after construction: runs on one
/// PreparedBody may go on in several threads at once.
#include "fissure/fem/elastic_body.hpp"
#include "fissure/fem/static_solver.hpp"
#include "fissure/fem/stress.hpp"
#include "fissure/fem/stress_recovery.hpp"
#include "fissure/fracture/fracture_body.hpp"
#include "fissure/fracture/fracture_params.hpp"
#include "fissure/fracture/fracture_scenario.hpp"

#include <memory>
#include <vector>

namespace fissure {

class PreparedBody {
public:
  /// Builds everything. Throws InvalidInput for a scenario the body cannot take (no face to rest
  /// on, a load that touches nothing, supports that leave a mechanism), naming the culprit.
  PreparedBody(std::shared_ptr<const TetMesh> mesh, const ElasticMaterial& material, const FractureScenario& scenario,
               int threads = 1);

  const TetMesh& mesh() const { return m_body->mesh(); }
  const ElasticBody& elastic_body() const { return *m_body; }
  const FractureBody& fracture_body() const { return m_fracture_body; }
  const FractureScenario& scenario() const { return m_scenario; }
  const std::vector<int>& fixed_dofs() const { return m_solver->fixed_dofs(); }
  /// The loads applied: the scenario's, or the default patch (its force for l = 1).
  const std::vector<LoadSpec>& loads() const { return m_loads; }
  /// Whether the loads are the default patch, which scales with l·m·g.
  bool default_load() const { return m_default_load; }

  /// The nodal forces for `params`: the default patch scaled to l·m_body·g (m_body from
  /// params.density), or the scenario's loads as given.
  Eigen::VectorXd load_vector(const FractureParams& params) const;
  /// σ⁰ of the loads for `params` (#tets × 6, Pa): the direct static solve, then the recovered
  /// (smoothed) tet stress when `recovered` — the raw constant tet stress of a linear tet
  /// scatters 62 % at element scale, the recovered one 7 % (stress_recovery.hpp).
  StressField initial_stress(const FractureParams& params, bool recovered = true) const;
  /// σ⁰ of any nodal force vector (3 per node, N) on this body's supports: the fit tabulates the
  /// fields of loads at many positions with it (fit_body.hpp).
  StressField stress_of_forces(const Eigen::VectorXd& forces, bool recovered = true) const;

private:
  FractureScenario m_scenario;
  std::shared_ptr<const ElasticBody> m_body;
  std::unique_ptr<StaticSolver> m_solver;
  StressRecovery m_recovery;
  FractureBody m_fracture_body;
  std::vector<LoadSpec> m_loads;
  Eigen::VectorXd m_unit_load;  ///< the sum of the loads (default patch: 1 N)
  bool m_default_load = false;
};

}  // namespace fissure
