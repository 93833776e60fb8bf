#pragma once
/// Finiteness checks for values entering or leaving a module. The error names the quantity.

#include <Eigen/Core>

#include <string_view>

namespace fissure {

/// Throws NumericalFailure naming `what` and the first offending entry (its index for a vector,
/// its (row, column) for a matrix) when `values` holds a NaN or an infinity. O(size).
void require_finite(const Eigen::Ref<const Eigen::MatrixXd>& values, std::string_view what);

}  // namespace fissure
