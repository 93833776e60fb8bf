#pragma once
/// The parameters of a fracture simulation: the paper's Table 2 (Glondu et al. 2012, §5) as one
/// struct and one parameter table. The CLI flags, the material files, the fit's priors (Table 3)
/// and the studio's panel all read the table, so they cannot drift apart.
///
/// Units are SI. Simulated time is in "age units": Algorithm 1 only needs dσ_e·age, so an age
/// unit is whatever span the user means by age 1 (docs/architecture.md, "Fracture simulation").
#include "fissure/fem/elastic_material.hpp"

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace fissure {

/// How the stress around a new crack is relaxed (paper §5.2).
enum class RelaxationChoice {
  Directional,   ///< Eq. 3: along d, orthogonal to the surface normal and the crack's path
  Isotropic,     ///< Eq. 4: in every direction
  FromExemplar,  ///< Eq. 3 when the exemplar's mean junction angle is in [75°, 90°], else Eq. 4
};

/// One octave of the crack-surface noise (paper §5.3): amplitude A_i (m) at frequency f_i (1/m).
struct NoiseOctave {
  double amplitude = 0.0;
  double frequency = 0.0;
};

/// Defaults: the bundled default material, assets/materials/ceramic-tile.json (a test keeps the
/// two equal), so FractureParams{} is a believable porcelain floor tile.
struct FractureParams {
  // Material (IN, from reference tables; docs/materials.md cites them).
  double youngs_modulus = 6.0e10;     ///< E, Pa
  double poisson_ratio = 0.22;        ///< ν
  double density = 2400.0;            ///< ρ, kg/m³
  double resistance_mean = 4.5e7;     ///< R_cm, Pa: mean tensile (flexural) strength of an element
  /// K_IC, Pa·√m: the energy criterion that stops a running crack (docs/architecture.md). Not in
  /// the paper's Table 2 (GMD12's criterion is not published); an advanced material field.
  double fracture_toughness = 1.2e6;
  /// m: the length over which the per-element resistance varies (resistance_field.hpp), so the
  /// resistance belongs to the body, not to its mesh; 0: one independent draw per element (the
  /// paper's, mesh-dependent). Not in the paper.
  double resistance_correlation = 0.1;
  /// β in [0, 1]: how readily a running crack turns toward the max principal direction of the
  /// stress along the surface where it goes: over the length r_relax·(1 − β)/β, faster where one
  /// direction pulls harder (docs/fracture.md, "Crack paths"). 0: the paper's noisy plane, one
  /// normal for the whole crack; 1: at once (maximum tangential stress criterion). Not in the paper.
  double crack_turning = 0.9;
  /// b* in [0, 1]: a crack opens as a three-armed star (arms 120° apart: a Y junction) where the
  /// in-plane stress at its origin is at least this biaxial, λ₂/λ₁ ≥ b* (docs/fracture.md, "Star
  /// cracks"); 1: never, the paper's single crack. Not in the paper.
  double star_biaxiality = 0.7;

  // Simulation (IN).
  double age = 10.0;                  ///< duration of Algorithm 1, age units

  // Fitted (OPT, Table 3).
  double stress_rate = 4.5e6;         ///< dσ_e, Pa per age unit (in-plane tension, see below)
  double relax_radius = 0.08;         ///< r_relax, m
  double relax_rate = 9.0e6;          ///< v_relax, Pa
  double resistance_stddev = 6.75e6;  ///< R_cvar, Pa: read as a standard deviation
  double load_factor = 20.0;          ///< l: |f| = l · m_body · g (Table 3: 0–30, i.e. 0–3000 %)

  // Appearance (IN, set by hand): S_k(x) = d̂·(x − c) + Σ_i A_i·simplex(f_i·x + offset_k).
  std::array<NoiseOctave, 4> noise{{{0.004, 10.0}, {0.002, 20.0}, {0.001, 40.0}, {0.0005, 80.0}}};
  RelaxationChoice relaxation = RelaxationChoice::Directional;

  /// The exemplar's junction density (junctions per unit normalised area), kept with the material
  /// for the fit and the statistics panel. Not a simulation input: age already decides how many
  /// cracks open, and a second stopping rule would fight it (docs/architecture.md).
  double junction_density = 0.0;

  ElasticMaterial elastic() const { return {youngs_modulus, poisson_ratio, density}; }

  /// Readable problems, one per parameter out of its range, each naming it by its JSON key (or
  /// its CLI flag when `use_flags`) with the range: "relax_radius -1 is outside (0, 100] m".
  /// Empty when valid. Each parameter is checked on its own (no parameter's range depends on
  /// another's: Table 3's relative priors belong to the fit).
  std::vector<std::string> problems(bool use_flags = false) const;
  /// Throws InvalidInput "fracture parameters: <problems>" when problems() is not empty.
  void validate() const;
};

/// The table of the scalar parameters of FractureParams, in the order above; the noise octaves
/// as noise_amplitude_1, noise_frequency_1, …, noise_amplitude_4, noise_frequency_4. Names are
/// the JSON keys, flags the CLI flags. The relaxation choice is not a number: see
/// parse_relaxation_choice. Every range is closed and finite except where a bound is excluded
/// (r_relax > 0), so "each parameter at both ends of its range" is a testable set.
const std::vector<ParameterInfo>& fracture_parameter_table();

/// The row of the table whose name (JSON key) is `name`, or -1.
int find_fracture_parameter(std::string_view name);

/// The row named `name`, which must be in the table (a name the code spells, like "age"; throws
/// std::logic_error otherwise).
const ParameterInfo& fracture_parameter_info(std::string_view name);

/// The scalar field of `params` a table row describes (by row index), for generic readers and
/// writers (CLI, JSON, studio panel, fit priors). `row` < fracture_parameter_table().size().
double& parameter_value(FractureParams& params, std::size_t row);
double parameter_value(const FractureParams& params, std::size_t row);

/// What a Table 3 prior is a fraction of.
enum class PriorReference {
  ResistanceMean,  ///< R_cm of the material
  FragmentScale,   ///< √(mean fragment area) on the body's visible face (paper-gaps §2)
  None,            ///< the parameter itself (l is already a multiple of the body's weight)
};

/// One of the fit's uniform priors (paper Table 3): [min_fraction, max_fraction] × reference.
struct FitPrior {
  const char* name;  ///< the parameter's row name in fracture_parameter_table()
  double min_fraction;
  double max_fraction;
  PriorReference reference;
};

/// Table 3 in the order of the paper's vector p = (dσ_e, r_relax, v_relax, R_cvar, l):
/// 0–33 % of R_cm, 0–100 % of √(fragment area), 0–33 % of R_cm, 0–100 % of R_cm, 0–3000 % of
/// the body's weight. The parameter table's absolute ranges hold these for every R_cm in range
/// (a test checks it); turning them into absolute bounds needs R_cm and the body, so it is the
/// fit's.
const std::array<FitPrior, 5>& table3_priors();

/// "directional", "isotropic", "from-exemplar": the JSON value and the --relaxation argument.
const char* to_string(RelaxationChoice choice);
/// The inverse of to_string (exact, lower case); nullopt for anything else.
std::optional<RelaxationChoice> parse_relaxation_choice(std::string_view text);
/// "directional, isotropic, from-exemplar", for messages that list the choices.
const char* relaxation_choice_names();

}  // namespace fissure
