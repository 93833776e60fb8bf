#include "fissure/fracture/overload.hpp"

#include "fissure/base/number_text.hpp"

#include <cmath>

namespace fissure {

std::optional<std::string> overload_note(const StressField& initial, const FractureParams& params) {
  if (initial.rows() == 0) return std::nullopt;
  Eigen::VectorXd lambda;
  max_principal_of(initial, lambda);
  const Eigen::Index over = (lambda.array() >= params.resistance_mean).count();
  if (2 * over <= lambda.size()) return std::nullopt;
  const double percent = std::floor(100.0 * static_cast<double>(over) / static_cast<double>(lambda.size()));
  return "the loads stress " + format_number(percent) + " % of the tets past the material's mean resistance (" +
         format_number(params.resistance_mean) + " Pa) at age 0, the largest to " + format_number(lambda.maxCoeff()) +
         " Pa: it shatters at once; are the forces in newtons?";
}

}  // namespace fissure
