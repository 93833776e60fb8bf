#include "fissure/fracture/fitted_transfer.hpp"

#include "fissure/base/error.hpp"
#include "fissure/base/number_text.hpp"
#include "fissure/fem/load.hpp"
#include "fissure/fem/stress.hpp"
#include "fissure/fracture/visible_pattern.hpp"

#include <algorithm>
#include <cmath>

namespace fissure {

double reference_stress_per_newton(const PreparedBody& body) {
  return reference_stress_per_newton(body.mesh(), body.scenario(),
                                     [&body](const Eigen::VectorXd& f) { return body.stress_of_forces(f); });
}

double reference_stress_per_newton(const TetMesh& mesh, const FractureScenario& scenario, const StressOfForces& solve) {
  const LoadSpec patch = default_load(mesh, scenario.up.normalized(), 1.0, scenario.patch_radius);
  const StressField stress = solve(assemble_load(mesh, patch));
  Eigen::VectorXd lambda;
  max_principal_of(stress, lambda);
  const Eigen::VectorXd& volumes = mesh.volumes();
  double sum = 0.0;
  for (Eigen::Index t = 0; t < lambda.size(); ++t) sum += volumes[t] * std::max(lambda[t], 0.0);
  const double mean = sum / mesh.total_volume();
  if (!(mean > 0.0) || !std::isfinite(mean)) {
    throw InvalidInput("the body's reference load puts no tension in it (reference stress " + format_number(mean) +
                       " Pa/N), so a fitted load cannot be matched to it");
  }
  return mean;
}

double fitted_length_scale(const MaterialFit& fit, double visible_area) {
  const double fit_area = fit.body_width * fit.body_height;
  if (!(fit_area > 0.0) || !(visible_area > 0.0) || !std::isfinite(visible_area)) {
    throw InvalidInput("a fitted material moves to a body by its visible area: the fit body's is " + format_number(fit_area) +
                       " m², the body's " + format_number(visible_area) + " m²");
  }
  const double s = std::sqrt(visible_area / fit_area);
  // The fit body itself, meshed again: its area differs by round-off only, and a material on
  // its own fit body must be the fitted one exactly.
  return std::abs(s - 1.0) <= 1e-9 ? 1.0 : s;
}

FractureParams scale_lengths(const FractureParams& params, double s) {
  if (!(s > 0.0) || !std::isfinite(s)) throw InvalidInput("the length scale " + format_number(s) + " is not positive");
  if (s == 1.0) return params;
  FractureParams p = params;
  p.relax_radius *= s;
  p.resistance_correlation *= s;
  for (NoiseOctave& octave : p.noise) {
    octave.amplitude *= s;
    octave.frequency /= s;
  }
  p.fracture_toughness *= std::sqrt(s);
  return p;
}

double fitted_load_force(const MaterialFit& fit, const FractureParams& params, const PreparedBody& body) {
  return fitted_load_force(fit, params, body.mesh(), body.scenario(),
                           [&body](const Eigen::VectorXd& f) { return body.stress_of_forces(f); });
}

double fitted_load_force(const MaterialFit& fit, const FractureParams& params, const TetMesh& mesh,
                         const FractureScenario& scenario, const StressOfForces& solve) {
  if (fit.load_reference_stress > 0.0) {
    return params.load_factor * fit.load_reference_stress / reference_stress_per_newton(mesh, scenario, solve);
  }
  return params.load_factor * params.density * mesh.total_volume() * kStandardGravity;
}

FractureParams fitted_params_on(const MaterialFit& fit, const FractureParams& params, const TetMesh& mesh,
                                const Eigen::Vector3d& view, double* scale) {
  const VisiblePattern face = extract_visible_pattern(mesh, {}, 0, view);
  const double s = face.has_visible_face ? fitted_length_scale(fit, face.graph.total_area) : 1.0;
  if (scale) *scale = s;
  return scale_lengths(params, s);
}

}  // namespace fissure
