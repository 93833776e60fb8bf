#pragma once
/// The fracture simulation of paper §5: the stress map of Algorithm 1 evolving against per-element
/// resistance, each crack a noisy implicit surface flooding the tets it crosses until an energy
/// criterion stops it (after [GMD12]), and the stress relaxation of Eqs. 2–4 around each new
/// crack. Decisions where the paper is silent are in docs/architecture.md ("Fracture simulation").
///
/// Algorithm 1 runs event-driven: every element's next threshold crossing is found in closed
/// form (λ_max of σ + τ·dσ·P is non-decreasing and convex in τ), kept in a heap, and re-checked
/// when popped. Relaxation never raises λ_max (the tensile-only clamp), so a crossing time can only
/// move later and a stale heap entry is merely early: re-checking it on pop is exact (the lazy
/// queue of performance.md §4.3). The result equals the fixed-Δt loop as Δt → 0 (tested).
#include "fissure/base/progress.hpp"
#include "fissure/fem/stress.hpp"
#include "fissure/fracture/fracture_body.hpp"
#include "fissure/fracture/fracture_params.hpp"
#include "fissure/fracture/fracture_result.hpp"

#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

namespace fissure {

struct SimulationOptions {
  /// Stop after this many cracks (FractureResult::crack_limit_reached says so).
  int max_cracks = 100000;
  /// The exemplar's mean junction angle, degrees, for RelaxationChoice::FromExemplar (Eq. 3 in
  /// [75°, 90°], else Eq. 4); NaN when there is no exemplar (FromExemplar is then refused).
  double exemplar_mean_junction_angle_deg = std::numeric_limits<double>::quiet_NaN();
  /// > 0: run Algorithm 1 literally, in fixed steps of this many age units (each step cracks,
  /// one after another, every element over its resistance, largest stress-to-resistance ratio
  /// first). The reference the event-driven run is tested against; O(#tets) per step.
  double fixed_time_step = 0.0;
  ProgressSink* progress = nullptr;
  const CancelToken* cancel = nullptr;
  /// Called with the cracks opened so far once their count reaches `stop_check_at`; it returns
  /// the next count to call it at (> the current count), or 0 to stop the run there
  /// (FractureResult::stopped_early). The fit's early rejection (fit_trial.hpp): a trial whose
  /// pattern can no longer win is not run to the end. Empty: never called.
  std::function<int(const std::vector<CrackSurface>& cracks)> stop_check;
  int stop_check_at = 0;
  /// Label the 3-D fragments at the end (FractureResult::fragments, partial_cracks). The fit
  /// measures only the visible pattern and skips it.
  bool label_fragments = true;
};

/// Runs the simulation on `body` from the initial stress σ⁰ (#tets × 6, Pa; e.g. the recovered
/// static stress of the loads) against the resistance R_c,e of every tet (Pa), up to params.age.
/// `seed` draws each crack's noise offsets (the resistance field carries its own draws).
/// Deterministic: the same inputs give the same bytes on any thread count (it is serial).
/// Throws InvalidInput for invalid params, wrong sizes or non-finite inputs (naming the tet),
/// Cancelled when `options.cancel` fires.
FractureResult simulate_fracture(const FractureBody& body, const FractureParams& params, const StressField& initial_stress,
                                 const Eigen::VectorXd& resistance, std::uint64_t seed,
                                 const SimulationOptions& options = {});

/// The relaxation polynomial of Eq. 2: (r² − d²)³ / r⁶ for d < r, else 0.
double relaxation_kernel(double distance, double radius);

/// One element's relaxation (Eqs. 3–4) with the tensile-only clamp (paper-gaps §4, reading b):
/// `amount` = v_relax·φ (Pa, ≥ 0) is removed, but never more than the tensile stress it acts on.
///  - directional (Eq. 3): σ − min(amount, max(0, dᵀσd))·d dᵀ, d a unit vector; the normal stress
///    along d ends at ≥ 0 (0 when amount exceeds it) and is untouched when it was compressive;
///  - isotropic (Eq. 4, `direction` ignored): σ − min(amount, max(0, λ_max))·I; λ_max ends ≥ 0.
/// Either way a positive semi-definite tensor is subtracted, so no principal stress rises: the
/// property the event queue relies on (see the top of this file). simulate_fracture's relaxation.
Eigen::Matrix<double, 6, 1> relax_element_stress(const Eigen::Matrix<double, 6, 1>& stress, double amount,
                                                 bool directional, const Eigen::Vector3d& direction);

/// The energy criterion's constants (docs/architecture.md): the critical energy release rate
/// G_c = K_IC²/E (J/m²) and the Griffith flaw size a_f = K_IC² / (π R_cm²) (m) at which an
/// element's resistance is reached.
double critical_energy_release_rate(const FractureParams& params);
double flaw_size(const FractureParams& params);

}  // namespace fissure
