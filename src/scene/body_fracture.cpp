#include "fissure/scene/body_fracture.hpp"

#include "fissure/base/error.hpp"
#include "fissure/fracture/fitted_transfer.hpp"
#include "fissure/fracture/material_fit.hpp"
#include "fissure/fracture/overload.hpp"
#include "fissure/fracture/static_stress_cache.hpp"
#include "fissure/fracture/resistance_field.hpp"
#include "fissure/fracture/simulation.hpp"

#include <chrono>
#include <memory>

namespace fissure {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

BodyFracture fracture_body_surface(const BodyFractureRequest& request, int threads, const Mesher& mesher,
                                   const CancelToken* cancel, const BodyFieldCache& field_cache) {
  BodyFracture out;
  const std::optional<MaterialFit>& fit = request.material.fit;
  FractureParams params = request.material.params;
  if (fit && !fit->samples.empty()) {
    params = draw_from_posterior(*fit, params, request.seed);
    out.posterior_draw = true;
  }
  if (request.age) params.age = *request.age;
  params.validate();

  auto clock = std::chrono::steady_clock::now();
  TetrahedralizeOptions mesh_options;
  mesh_options.target_tets = request.target_tets > 0 ? request.target_tets
                             : fit && fit->body_tets > 0 ? fit->body_tets
                                                         : kDefaultBodyTets;
  mesh_options.memory_limit_bytes = request.memory_limit_bytes;
  auto mesh = std::make_shared<const TetMesh>(mesher ? mesher(request.surface, mesh_options)
                                                     : tetrahedralize(request.surface, mesh_options, nullptr, nullptr, cancel));
  out.tets = mesh->tet_count();
  out.tets_asked = mesh_options.target_tets;
  out.seconds.meshing = seconds_since(clock);
  if (cancel) cancel->throw_if_cancelled();

  clock = std::chrono::steady_clock::now();
  if (fit) params = fitted_params_on(*fit, params, *mesh, request.up, &out.length_scale);
  FractureScenario scenario;
  scenario.up = request.up;
  scenario.free_body = request.free_body;
  scenario.supports = request.supports;
  scenario.loads = request.loads;
  for (const PatchLoad& p : request.patch_loads)
    scenario.loads.push_back(patch_load(*mesh, p.normal, p.position, p.magnitude, p.radius));
  // The fitted rule's patch pushes with 1 N until the body is prepared: the force that keeps the
  // fit's stress takes the prepared body to measure.
  const bool fitted_load_rule = fit && scenario.loads.empty();
  // An unfitted material's load is drawn too, per body: the default patch at a drawn point of
  // the top, pushing with l·m·g (1 N until the stress is scaled below).
  const bool drawn_load_rule = !fit && scenario.loads.empty();
  if (fitted_load_rule) scenario.loads = {fitted_load(*mesh, request.up, fit->load_grid, fit->load_inset, 1.0, request.seed)};
  if (drawn_load_rule) scenario.loads = {drawn_load(*mesh, request.up, 1.0, request.seed)};
  // σ⁰ solved on the body's supports, or read from the cache without building any FEM. The
  // forces are those PreparedBody::initial_stress() solves for, so a cached run, a cold one and
  // `fissure fracture` give the same field.
  CachedStaticStress statics(mesh, params.elastic(), scenario, field_cache.directory, field_cache.max_bytes, threads);
  const ScenarioLoads loads = scenario_loads(*mesh, scenario);
  const double default_force = params.load_factor * (params.density * mesh->total_volume()) * kStandardGravity;
  // Never the scenario's default load: with no loads given, one of the two rules above set one.
  StressField initial = statics.stress_of_forces(loads.unit_forces);
  out.loads = loads.loads;
  if (fitted_load_rule) {
    const double force = fitted_load_force(*fit, params, *mesh, scenario,
                                           [&statics](const Eigen::VectorXd& f) { return statics.stress_of_forces(f); });
    initial *= force;
    out.loads = {fitted_load(*mesh, request.up, fit->load_grid, fit->load_inset, force, request.seed)};
  } else if (drawn_load_rule) {
    initial *= default_force;
    out.loads = {drawn_load(*mesh, request.up, default_force, request.seed)};
  }
  const FractureBody& fracture_body = statics.fracture_body();
  out.stress_cached = statics.solved() == 0;
  out.cache_warning = statics.warning();
  if (const auto overload = overload_note(initial, params)) out.overload = *overload;
  const Eigen::VectorXd resistance = draw_resistance(mesh->centroids(), params, request.seed, threads);
  out.seconds.preparation = seconds_since(clock);
  if (cancel) cancel->throw_if_cancelled();

  clock = std::chrono::steady_clock::now();
  SimulationOptions options;
  options.cancel = cancel;
  out.result = simulate_fracture(fracture_body, params, initial, resistance, request.seed, options);
  out.seconds.simulation = seconds_since(clock);

  clock = std::chrono::steady_clock::now();
  out.fragments = mesh_fragments(*mesh, out.result.cracks, static_cast<int>(out.result.cracks.size()), threads);
  out.seconds.fragments = seconds_since(clock);
  out.params = params;
  if (request.keep_mesh) out.mesh = std::move(mesh);
  return out;
}

}  // namespace fissure
