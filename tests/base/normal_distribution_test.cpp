// The standard normal tail and its quantile, against reference values and their own identities.

#include "fissure/base/normal_distribution.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace fissure {
namespace {

TEST(NormalDistribution, TailMatchesReferenceValues) {
  // Q(z) to 16 digits (Abramowitz & Stegun 26.2; Mathematica's N[Erfc[z/Sqrt[2]]/2, 20]).
  EXPECT_DOUBLE_EQ(standard_normal_tail(0.0), 0.5);
  EXPECT_NEAR(standard_normal_tail(1.0), 0.15865525393145705, 1e-16);
  EXPECT_NEAR(standard_normal_tail(1.959963984540054), 0.025, 1e-16);
  EXPECT_NEAR(standard_normal_tail(-3.0) , 0.9986501019683699, 1e-15);
  // Deep in the upper tail the relative precision stays: Q(10) = 7.619853024160527e-24.
  EXPECT_NEAR(standard_normal_tail(10.0) / 7.619853024160527e-24, 1.0, 1e-14);
}

// The quantile inverts the tail to a few ulps everywhere in (0, 1), both tails included: the
// refined Acklam step leaves a relative error ~1e-15 (its unrefined 1.2e-9 would fail this).
// Tolerances follow the conditioning: an ulp of z (relative 1.1e-16) moves Q(z) by a relative
// z·φ(z)/Q(z)·|z|·1.1e-16 ≈ z²·1.1e-16 in the upper tail, so Q(z)/q is held to 4e-15·max(1, z²);
// z from Q(z) is well conditioned only where Q is not close to 1 (z ≥ −1: dz = dQ/φ(z) ≤ 5e-16
// there; at z = −8, Q = 1 − 6e-16 and one ulp of Q moves z by 0.02, which is why the
// resistance field maps z < 0 through the lower tail).
TEST(NormalDistribution, QuantileInvertsTheTail) {
  for (double q : {1e-300, 1e-100, 1e-20, 1e-8, 0.001, 0.02425, 0.1, 0.3, 0.5, 0.7, 0.9, 0.97575, 0.999, 1 - 1e-9}) {
    const double z = standard_normal_tail_quantile(q);
    EXPECT_NEAR(standard_normal_tail(z) / q, 1.0, 4e-15 * std::max(1.0, z * z)) << "q " << q;
  }
  for (double z = -1.0; z <= 37.0; z += 0.37) {
    EXPECT_NEAR(standard_normal_tail_quantile(standard_normal_tail(z)), z, 1e-13 * std::max(1.0, std::abs(z))) << "z " << z;
  }
  EXPECT_DOUBLE_EQ(standard_normal_tail_quantile(0.5), 0.0);
  EXPECT_NEAR(standard_normal_tail_quantile(0.025), 1.959963984540054, 1e-14);
}

TEST(NormalDistribution, QuantileOutsideTheOpenIntervalIsInfiniteOrNaN) {
  EXPECT_EQ(standard_normal_tail_quantile(0.0), INFINITY);
  EXPECT_EQ(standard_normal_tail_quantile(1.0), -INFINITY);
  EXPECT_TRUE(std::isnan(standard_normal_tail_quantile(-0.1)));
  EXPECT_TRUE(std::isnan(standard_normal_tail_quantile(NAN)));
}

}  // namespace
}  // namespace fissure
