#pragma once
/// How a fitted material moves from its fit body to another body (a 0.3 m or a 3 m tile, a
/// basin) so that the patterns keep their normalised statistics: Table 3 makes the fitted
/// parameters relative (dσ_e, v_relax and R_cvar to R_cm; r_relax to √(fragment area); l to the
/// body's weight), and this is the map that honours it on a body of another size or shape.
///
///  - Lengths follow the visible face: with s = √(A_body / A_fit) (A the area the pattern is seen
///    on), r_relax, the resistance correlation and the noise amplitudes scale by s, the noise
///    frequencies by 1/s, and K_IC by √s (a crack's energy release rate G ∝ σ²·length at equal
///    stress, so G_c scales by s and K_IC = √(G_c·E) by √s). The fragments' areas as fractions of
///    the face then stay the fit's.
///  - The load keeps the fit's stress, not its force. l·m·g grows with the body's mass, but a
///    plate's bending stress under a patch is F/T² times a shape factor: a 3 m tile pushed with
///    l·m·g would carry 9 times the fit's stress and shatter. So the fit records the reference
///    stress of its body (below) for l = 1, and another body is pushed with
///    l · σ_ref,fit / σ_ref,body newtons; on the fit body itself that is l·m·g again.
///  - Stresses against resistance (R_cm, dσ_e, v_relax, R_cvar) and the age are unchanged.
#include "fissure/fracture/fracture_params.hpp"
#include "fissure/fracture/material_fit.hpp"
#include "fissure/fracture/prepared_body.hpp"

#include <functional>

namespace fissure {

/// How a caller solves for the stress of nodal forces on a body's supports: a PreparedBody's
/// stress_of_forces (recovered), or a cache in front of one (static_stress_cache.hpp).
using StressOfForces = std::function<StressField(const Eigen::VectorXd& forces)>;

/// The reference stress of a body per newton of load (Pa/N): the volume-weighted mean of the
/// positive max principal stress (recovered) under the default patch at the centre of the top
/// face pushing with 1 N, on the body's supports. A mean, not a peak: the peak under a patch
/// grows as the mesh refines; the mean converges. One static solve on the prepared factor.
double reference_stress_per_newton(const PreparedBody& body);
/// The same, solving through `solve` on `mesh` with `scenario`'s up and patch radius.
double reference_stress_per_newton(const TetMesh& mesh, const FractureScenario& scenario, const StressOfForces& solve);

/// s = √(visible_area / fit visible area), 1 when the two agree to 1e-9 (the fit body itself).
/// Throws InvalidInput when either area is not positive.
double fitted_length_scale(const MaterialFit& fit, double visible_area);

/// `params` with its lengths scaled by `s` as above (s > 0).
FractureParams scale_lengths(const FractureParams& params, double s);

/// `params` moved to `mesh` seen along `view`: its lengths scaled by fitted_length_scale of the
/// mesh's visible face (unchanged when it has none). `scale`, when given, receives s.
FractureParams fitted_params_on(const MaterialFit& fit, const FractureParams& params, const TetMesh& mesh,
                                const Eigen::Vector3d& view, double* scale = nullptr);

/// The force (N) of the fitted load rule on `body`: l · σ_ref,fit / σ_ref,body, or l·m·g (m from
/// params.density) when the fit predates the reference stress (fit.load_reference_stress = 0).
double fitted_load_force(const MaterialFit& fit, const FractureParams& params, const PreparedBody& body);
/// The same, solving through `solve` (only when the fit records a reference stress).
double fitted_load_force(const MaterialFit& fit, const FractureParams& params, const TetMesh& mesh,
                         const FractureScenario& scenario, const StressOfForces& solve);

}  // namespace fissure
