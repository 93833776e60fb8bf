#include "fissure/base/finite.hpp"

#include "fissure/base/error.hpp"
#include "fissure/base/number_text.hpp"

#include <cmath>
#include <string>

namespace fissure {

void require_finite(const Eigen::Ref<const Eigen::MatrixXd>& values, std::string_view what) {
  for (Eigen::Index c = 0; c < values.cols(); ++c) {
    for (Eigen::Index r = 0; r < values.rows(); ++r) {
      if (!std::isfinite(values(r, c))) {
        const std::string where = values.cols() == 1
                                      ? std::to_string(r)
                                      : "(" + std::to_string(r) + ", " + std::to_string(c) + ")";
        throw NumericalFailure(std::string(what) + ": entry " + where + " is " +
                               format_number(values(r, c)));
      }
    }
  }
}

}  // namespace fissure
