#pragma once
/// Isotropic linear elastic material in SI units, and the table that describes its parameters
/// once for the CLI, the studio panel, JSON keys and later the fit.

#include <Eigen/Core>

#include <array>
#include <string>
#include <vector>

namespace fissure {

/// One parameter's description. `min`/`max` bound the valid range; `max_exclusive` marks an open
/// upper bound (ν < 0.5).
struct ParameterInfo {
  const char* name;       ///< JSON key and identifier, e.g. "poisson_ratio"
  const char* flag;       ///< CLI flag, e.g. "--nu"
  const char* unit;       ///< SI unit, "" when dimensionless
  double min;
  double max;
  bool min_exclusive;
  bool max_exclusive;
  double default_value;
  const char* help;
  const char* reference;  ///< where the parameter comes from (paper table, textbook)
};

struct ElasticMaterial {
  double youngs_modulus = 3.0e10;  ///< E, Pa
  double poisson_ratio = 0.2;      ///< ν, dimensionless, in [0, 0.5)
  double density = 2400.0;         ///< ρ, kg/m³

  /// Human-readable problems, empty when valid: "poisson_ratio 0.62 is outside [0, 0.5)".
  std::vector<std::string> problems() const;
  /// Throws InvalidInput listing every problem.
  void validate() const;

  double shear_modulus() const { return youngs_modulus / (2.0 * (1.0 + poisson_ratio)); }
  double lame_lambda() const {
    return youngs_modulus * poisson_ratio / ((1.0 + poisson_ratio) * (1.0 - 2.0 * poisson_ratio));
  }
  /// Isotropic elasticity matrix D in Voigt order (xx, yy, zz, yz, xz, xy) with engineering shear
  /// strains: σ = D ε.
  Eigen::Matrix<double, 6, 6> elasticity_matrix() const;
};

/// The parameter table of ElasticMaterial: youngs_modulus, poisson_ratio, density.
const std::array<ParameterInfo, 3>& elastic_material_parameters();

/// "" when `value` is inside the range of `info`, else "<label> <value> is outside [min, max) unit",
/// or "<label> inf is not a finite number" for inf and nan (label: the JSON name or the CLI flag,
/// whichever the caller shows its user). Numbers are printed by format_number.
std::string parameter_problem(const ParameterInfo& info, double value, const std::string& label);

/// The range of `info` as parameter_problem writes it: "(0, 100] m", "[0, 0.5)".
std::string parameter_range_text(const ParameterInfo& info);

}  // namespace fissure
