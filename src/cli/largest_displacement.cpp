#include "largest_displacement.hpp"

#include <cmath>
#include <limits>

namespace fissure::cli {

double largest_displacement(const Eigen::VectorXd& u) {
  if (u.size() == 0) return 0.0;
  if (u.hasNaN()) return std::numeric_limits<double>::quiet_NaN();
  const double scale = u.cwiseAbs().maxCoeff();
  if (scale == 0.0 || !std::isfinite(scale)) return scale;
  // After the division every component is in [-1, 1], so the squares neither overflow nor (for
  // the largest node, whose norm is >= 1) underflow to zero.
  double largest_squared = 0.0;
  for (Eigen::Index i = 0; i + 2 < u.size(); i += 3) {
    const double x = u[i] / scale, y = u[i + 1] / scale, z = u[i + 2] / scale;
    largest_squared = std::max(largest_squared, x * x + y * y + z * z);
  }
  return scale * std::sqrt(largest_squared);
}

}  // namespace fissure::cli
