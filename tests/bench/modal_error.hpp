#pragma once
// Error measures of an approximate static solution against a reference (performance.md §5).

#include "fissure/fem/stress.hpp"

#include <Eigen/Core>

namespace fissure::bench {

struct SolutionError {
  double displacement = 0.0;   ///< ‖u − u_ref‖ / ‖u_ref‖
  double stress = 0.0;         ///< volume-weighted L2 of the tensor difference / that of σ_ref
  double peak_principal = 0.0; ///< |max s − max s_ref| / |max s_ref|
};

inline SolutionError solution_error(const Eigen::VectorXd& u, const StressField& s, const Eigen::VectorXd& smax,
                                    const Eigen::VectorXd& u_ref, const StressField& s_ref,
                                    const Eigen::VectorXd& smax_ref, const Eigen::VectorXd& volumes) {
  SolutionError e;
  e.displacement = (u - u_ref).norm() / u_ref.norm();
  double num = 0.0, den = 0.0;
  for (Eigen::Index t = 0; t < s.rows(); ++t) {
    // Frobenius norm of the symmetric tensor: shear components count twice.
    const Eigen::Matrix<double, 1, 6> d = s.row(t) - s_ref.row(t);
    const auto r = s_ref.row(t);
    num += volumes[t] * (d.head<3>().squaredNorm() + 2.0 * d.tail<3>().squaredNorm());
    den += volumes[t] * (r.head<3>().squaredNorm() + 2.0 * r.tail<3>().squaredNorm());
  }
  e.stress = std::sqrt(num / den);
  e.peak_principal = std::abs(smax.maxCoeff() - smax_ref.maxCoeff()) / std::abs(smax_ref.maxCoeff());
  return e;
}

}  // namespace fissure::bench
