#include "fissure/fem/elastic_material.hpp"

#include "fissure/base/error.hpp"
#include "fissure/base/number_text.hpp"

#include <cmath>
#include <limits>

namespace fissure {
namespace {

void check(const ParameterInfo& info, double value, std::vector<std::string>& problems) {
  std::string problem = parameter_problem(info, value, info.name);
  if (!problem.empty()) problems.push_back(std::move(problem));
}

}  // namespace

std::string parameter_problem(const ParameterInfo& info, double value, const std::string& label) {
  const bool below = info.min_exclusive ? value <= info.min : value < info.min;
  const bool above = info.max_exclusive ? value >= info.max : value > info.max;
  // A non-finite value is not "outside (0, inf]" (inf is the bound's notation, not a value).
  if (!std::isfinite(value)) return label + " " + format_number(value) + " is not a finite number";
  if (!below && !above) return {};
  return label + " " + format_number(value) + " is outside " + parameter_range_text(info);
}

std::string parameter_range_text(const ParameterInfo& info) {
  return (info.min_exclusive ? "(" : "[") + format_number(info.min) + ", " + format_number(info.max) +
         (info.max_exclusive ? ")" : "]") + (info.unit[0] ? std::string(" ") + info.unit : std::string());
}

const std::array<ParameterInfo, 3>& elastic_material_parameters() {
  constexpr double inf = std::numeric_limits<double>::infinity();
  static const std::array<ParameterInfo, 3> table{{
      {"youngs_modulus", "--E", "Pa", 0.0, inf, true, false, 3.0e10,
       "Young's modulus E (concrete 3e10, glass 7e10, ceramic tile 5e10)", "paper Table 2 (IN)"},
      {"poisson_ratio", "--nu", "", 0.0, 0.5, false, true, 0.2,
       "Poisson's ratio nu; linear tets lock as nu approaches 0.5 (docs/architecture.md)",
       "paper Table 2 (IN)"},
      {"density", "--rho", "kg/m^3", 0.0, inf, true, false, 2400.0,
       "Mass density rho (concrete 2400, glass 2500)", "paper Table 2 (IN)"},
  }};
  return table;
}

std::vector<std::string> ElasticMaterial::problems() const {
  std::vector<std::string> out;
  const auto& table = elastic_material_parameters();
  check(table[0], youngs_modulus, out);
  check(table[1], poisson_ratio, out);
  check(table[2], density, out);
  return out;
}

void ElasticMaterial::validate() const { throw_if_problems("material", problems()); }

Eigen::Matrix<double, 6, 6> ElasticMaterial::elasticity_matrix() const {
  const double lambda = lame_lambda();
  const double mu = shear_modulus();
  Eigen::Matrix<double, 6, 6> d = Eigen::Matrix<double, 6, 6>::Zero();
  d.topLeftCorner<3, 3>().setConstant(lambda);
  for (int i = 0; i < 3; ++i) {
    d(i, i) = lambda + 2.0 * mu;
    d(3 + i, 3 + i) = mu;
  }
  return d;
}

}  // namespace fissure
