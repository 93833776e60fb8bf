#pragma once
/// The parameters of a fracture simulation: the paper's Table 2 (Glondu et al. 2012, §5) as one
/// struct and one parameter table. The CLI flags, the material files, the fit's priors (Table 3)
/// and the studio's panel all read the table, so they cannot drift apart.
///
/// Units are SI. Simulated time is in "age units": Algorithm 1 only needs dσ_e·age, so an age
/// unit is whatever span the user means by age 1 (docs/architecture.md, "Fracture simulation").
#include "fissure/fem/elastic_material.hpp"

#include <array>
#include <string>
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

struct FractureParams {
  // Material (IN, from reference tables).
  double youngs_modulus = 3.0e10;     ///< E, Pa
  double poisson_ratio = 0.2;         ///< ν
  double density = 2400.0;            ///< ρ, kg/m³
  double resistance_mean = 3.0e6;     ///< R_cm, Pa: mean tensile strength of an element
  /// K_IC, Pa·√m: the energy criterion that stops a running crack (docs/architecture.md). Not in
  /// the paper's Table 2 (GMD12's criterion is not published); an advanced material field.
  double fracture_toughness = 1.0e6;

  // Simulation (IN).
  double age = 1.0;                   ///< duration of Algorithm 1, age units

  // Fitted (OPT, Table 3).
  double stress_rate = 0.0;           ///< dσ_e, Pa per age unit (in-plane tension, see below)
  double relax_radius = 0.05;         ///< r_relax, m
  double relax_rate = 0.0;            ///< v_relax, Pa
  double resistance_stddev = 0.0;     ///< R_cvar, Pa: read as a standard deviation
  double load_factor = 0.0;           ///< l: |f| = l · m_body · g (Table 3: 0–30, i.e. 0–3000 %)

  // Appearance (IN, set by hand).
  std::array<NoiseOctave, 4> noise{};
  RelaxationChoice relaxation = RelaxationChoice::Directional;

  /// The exemplar's junction density (junctions per unit normalised area), kept with the material
  /// for the fit and the statistics panel. Not a simulation input: age already decides how many
  /// cracks open, and a second stopping rule would fight it (docs/architecture.md).
  double junction_density = 0.0;

  ElasticMaterial elastic() const { return {youngs_modulus, poisson_ratio, density}; }

  /// Readable problems, one per parameter out of its range, each naming it by its JSON key (or
  /// its CLI flag when `use_flags`) with the range: "relax_radius -1 is outside (0, 10] m".
  /// Empty when valid.
  std::vector<std::string> problems(bool use_flags = false) const;
  /// Throws InvalidInput "fracture parameters: <problems>" when problems() is not empty.
  void validate() const;
};

/// The table of the scalar parameters of FractureParams, in the order above (noise octaves as
/// noise_amplitude_1 … noise_frequency_4). Names are the JSON keys; flags the CLI flags.
const std::vector<ParameterInfo>& fracture_parameter_table();

/// The scalar field of `params` a table row describes (by row index), for generic readers and
/// writers (CLI, JSON, studio panel, fit priors).
double& parameter_value(FractureParams& params, std::size_t row);
double parameter_value(const FractureParams& params, std::size_t row);

const char* to_string(RelaxationChoice choice);

}  // namespace fissure
