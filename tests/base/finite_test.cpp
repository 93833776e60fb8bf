#include "fissure/base/error.hpp"
#include "fissure/base/finite.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace fissure {
namespace {

TEST(RequireFinite, NamesQuantityAndIndex) {
  Eigen::VectorXd v = Eigen::VectorXd::Ones(10);
  EXPECT_NO_THROW(require_finite(v, "displacement"));
  v[7] = std::numeric_limits<double>::quiet_NaN();
  try {
    require_finite(v, "displacement");
    FAIL();
  } catch (const NumericalFailure& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("displacement"), std::string::npos);
    EXPECT_NE(msg.find("7"), std::string::npos);
  }
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(3, 3);
  m(1, 2) = std::numeric_limits<double>::infinity();
  EXPECT_THROW(require_finite(m, "stress"), NumericalFailure);
}

}  // namespace
}  // namespace fissure
