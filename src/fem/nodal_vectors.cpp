#include "fissure/fem/nodal_vectors.hpp"

#include <cmath>

namespace fissure {

NodalMaximum max_nodal_magnitude(const Eigen::VectorXd& field) {
  NodalMaximum out;
  const Eigen::Index nodes = field.size() / 3;
  for (Eigen::Index v = 0; v < nodes; ++v) {
    const double x = field[3 * v], y = field[3 * v + 1], z = field[3 * v + 2];
    const double m = std::fmax(std::fabs(x), std::fmax(std::fabs(y), std::fabs(z)));
    double length = 0.0;
    if (!std::isfinite(m)) {
      length = m;  // inf or nan propagates
    } else if (m > 0.0) {
      const double a = x / m, b = y / m, c = z / m;
      length = m * std::sqrt(a * a + b * b + c * c);
    }
    if (out.node < 0 || length > out.magnitude || std::isnan(length)) {
      out.magnitude = length;
      out.node = static_cast<int>(v);
      if (std::isnan(length)) break;
    }
  }
  return out;
}

}  // namespace fissure
