// draw_resistance: N(R_cm, R_cvar²) truncated at 0.05·R_cm by resampling, the same bytes at any
// thread count, indexed by tet.
//
// Statistical checks use n = 200,000 draws and 5 standard errors: each check fails by chance with
// p ≈ 5.7e-7, and the ~10 checks below together with p < 1e-5 (Bonferroni). The seeds are fixed,
// so a pass is reproducible; the bound says a pass is not luck of the seed.

#include "fissure/base/error.hpp"
#include "fissure/fracture/resistance_field.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>

namespace fissure {
namespace {

constexpr std::size_t kDraws = 200'000;
constexpr double kSigmas = 5.0;

double normal_pdf(double x) { return std::exp(-0.5 * x * x) / std::sqrt(2.0 * std::numbers::pi); }
double normal_cdf(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }

struct Moments {
  double mean = 0, variance = 0, fourth = 0;  // sample mean, central second and fourth moments
};

Moments moments(const Eigen::VectorXd& x) {
  Moments m;
  m.mean = x.mean();
  const Eigen::ArrayXd d = x.array() - m.mean;
  m.variance = d.square().mean();
  m.fourth = d.square().square().mean();
  return m;
}

// The normal truncated below at a = floor: with α = (a − μ)/σ and λ = φ(α)/(1 − Φ(α)),
// mean = μ + σλ and variance = σ²(1 + αλ − λ²).
void expect_truncated_normal(const Eigen::VectorXd& x, double mu, double sigma) {
  const double alpha = (kResistanceFloorFraction * mu - mu) / sigma;
  const double lambda = normal_pdf(alpha) / (1.0 - normal_cdf(alpha));
  const double mean = mu + sigma * lambda;
  const double variance = sigma * sigma * (1.0 + alpha * lambda - lambda * lambda);
  const Moments m = moments(x);
  const double n = static_cast<double>(x.size());
  // Standard errors: σ/√n for the mean; √((μ4 − σ⁴)/n) for the variance (asymptotic, from the
  // sample's own fourth moment: the truncated law is not normal).
  EXPECT_NEAR(m.mean, mean, kSigmas * std::sqrt(variance / n)) << "sigma/mu " << sigma / mu;
  EXPECT_NEAR(m.variance, variance, kSigmas * std::sqrt((m.fourth - m.variance * m.variance) / n))
      << "sigma/mu " << sigma / mu;
  // The share below the mean: P = (Φ(0) − Φ(α))/(1 − Φ(α)), binomial standard error. A clamp
  // would keep this share but pile the tail on the floor; resampling shows in the next check.
  const double p = (0.5 - normal_cdf(alpha)) / (1.0 - normal_cdf(alpha));
  const double below = static_cast<double>((x.array() < mu).count()) / n;
  EXPECT_NEAR(below, p, kSigmas * std::sqrt(p * (1 - p) / n)) << "sigma/mu " << sigma / mu;
  // The floor bounds every draw and none sits on it (resampled, not clamped).
  EXPECT_GT(x.minCoeff(), kResistanceFloorFraction * mu);
}

TEST(ResistanceField, DrawsFollowTheTruncatedNormal) {
  const double mu = 4.5e7;
  // 0.15·R_cm: the truncation is 6.3σ below the mean, so this is the plain normal.
  expect_truncated_normal(draw_resistance(kDraws, mu, 0.15 * mu, 11), mu, 0.15 * mu);
  // Table 3's largest spread, R_cvar = R_cm: 17 % of the normal lies below the floor.
  const Eigen::VectorXd wide = draw_resistance(kDraws, mu, mu, 12);
  expect_truncated_normal(wide, mu, mu);
  // There, the weakest draws still spread above the floor: the lowest 1 % of a clamped field
  // would all equal the floor.
  Eigen::VectorXd sorted = wide;
  std::sort(sorted.data(), sorted.data() + sorted.size());
  EXPECT_LT(sorted[0], sorted[static_cast<Eigen::Index>(kDraws / 100)]);
  // Far beyond Table 3 (σ = 100·R_cm, where over half the draws are resampled) the floor holds.
  EXPECT_GT(draw_resistance(10'000, mu, 100 * mu, 13).minCoeff(), kResistanceFloorFraction * mu);
}

TEST(ResistanceField, ZeroSpreadIsExactlyTheMean) {
  const Eigen::VectorXd r = draw_resistance(5000, 3.4e6, 0.0, 1);
  ASSERT_EQ(r.size(), 5000);
  for (Eigen::Index i = 0; i < r.size(); ++i) ASSERT_EQ(r[i], 3.4e6);
  EXPECT_EQ(draw_resistance(0, 3.4e6, 1e5, 1).size(), 0);
}

bool same_bytes(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}

TEST(ResistanceField, SameBytesAtAnyThreadCountAndIndexedByTet) {
  const std::size_t n = 10 * kResistanceBlock + 17;  // a partial last block
  const Eigen::VectorXd one = draw_resistance(n, 3e6, 1e6, 42, 1);
  EXPECT_TRUE(same_bytes(one, draw_resistance(n, 3e6, 1e6, 42, 2)));
  EXPECT_TRUE(same_bytes(one, draw_resistance(n, 3e6, 1e6, 42, 7)));
  EXPECT_TRUE(same_bytes(one, draw_resistance(n, 3e6, 1e6, 42, 1)));
  // Tet e's value depends on e, not on how many tets follow: a shorter field is a prefix.
  const Eigen::VectorXd shorter = draw_resistance(3 * kResistanceBlock + 5, 3e6, 1e6, 42, 2);
  EXPECT_TRUE(same_bytes(shorter, one.head(shorter.size())));
  // Another seed is another field.
  const Eigen::VectorXd other = draw_resistance(n, 3e6, 1e6, 43, 1);
  EXPECT_GT((one.array() != other.array()).count(), static_cast<Eigen::Index>(n) - 5);
  // Blocks are independent streams: block 1 is not block 0 again.
  EXPECT_FALSE(same_bytes(one.segment(0, 64), one.segment(static_cast<Eigen::Index>(kResistanceBlock), 64)));
}

TEST(ResistanceField, BadArgumentsAreRefused) {
  for (double mean : {0.0, -1.0, double(NAN), double(INFINITY)}) EXPECT_THROW(draw_resistance(10, mean, 1.0, 1), InvalidInput) << mean;
  for (double stddev : {-1.0, double(NAN), double(INFINITY)}) EXPECT_THROW(draw_resistance(10, 1.0, stddev, 1), InvalidInput) << stddev;
}

}  // namespace
}  // namespace fissure
