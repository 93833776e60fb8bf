// draw_resistance: N(R_cm, R_cvar²) truncated at 0.05·R_cm by resampling, the same bytes at any
// thread count, indexed by tet; draw_resistance_field: the same law as a correlated random field
// of position.
//
// Statistical checks use n = 200,000 draws and 5 standard errors: each check fails by chance with
// p ≈ 5.7e-7, and the ~10 checks below together with p < 1e-5 (Bonferroni). The seeds are fixed,
// so a pass is reproducible; the bound says a pass is not luck of the seed.

#include "fissure/base/error.hpp"
#include "fissure/base/rng.hpp"
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

// The correlated field (draw_resistance_field), spacing L.
constexpr double kSpacing = 0.05;

// Points two spacings apart in x and y: their lattice cells share no corner, so their values
// are independent draws and the field's marginal law can be checked like draw_resistance's.
Eigen::MatrixX3d independent_points(std::size_t n, std::uint64_t seed) {
  Rng rng(seed);
  const auto side = static_cast<std::size_t>(std::ceil(std::sqrt(static_cast<double>(n))));
  Eigen::MatrixX3d p(static_cast<Eigen::Index>(n), 3);
  for (std::size_t i = 0; i < n; ++i) {
    p.row(static_cast<Eigen::Index>(i)) << (2.0 * static_cast<double>(i % side) + rng.uniform()) * kSpacing - 3.0,
        (2.0 * static_cast<double>(i / side) + rng.uniform()) * kSpacing - 7.0, rng.uniform() * kSpacing;
  }
  return p;
}

TEST(ResistanceField, CorrelatedFieldHasTheTruncatedNormalMarginal) {
  const double mu = 4.5e7;
  const Eigen::MatrixX3d points = independent_points(kDraws, 5);
  expect_truncated_normal(draw_resistance_field(points, mu, 0.15 * mu, kSpacing, 21), mu, 0.15 * mu);
  // Where the truncation matters (R_cvar = R_cm): the quantile mapping, not a clamp, keeps the
  // tail above the floor spread out.
  const Eigen::VectorXd wide = draw_resistance_field(points, mu, mu, kSpacing, 22);
  expect_truncated_normal(wide, mu, mu);
  Eigen::VectorXd sorted = wide;
  std::sort(sorted.data(), sorted.data() + sorted.size());
  EXPECT_LT(sorted[0], sorted[static_cast<Eigen::Index>(kDraws / 100)]);
  EXPECT_GE(draw_resistance_field(points.topRows(10'000), mu, 100 * mu, kSpacing, 23).minCoeff(),
            kResistanceFloorFraction * mu);
}

double correlation(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  const Eigen::ArrayXd x = a.array() - a.mean(), y = b.array() - b.mean();
  return (x * y).sum() / std::sqrt(x.square().sum() * y.square().sum());
}

// Nearby points are nearly equal, points two spacings apart independent: the field varies over
// L, not over an element. Pairs from independent_points (each pair in its own cells).
TEST(ResistanceField, CorrelatedFieldVariesOverItsCorrelationLength) {
  constexpr std::size_t n = 40'000;
  const Eigen::MatrixX3d base = independent_points(n, 6);
  auto values_at = [&](const Eigen::RowVector3d& offset) {
    const Eigen::MatrixX3d p = base.rowwise() + offset;
    return draw_resistance_field(p, 3e6, 1e6, kSpacing, 9);
  };
  const Eigen::VectorXd here = values_at(Eigen::RowVector3d::Zero());
  // 5 % of a spacing away: the smoothstep blend moves by at most 1.5·0.05 of the corner
  // differences, so ρ ≈ 1 − O(0.05²); measured 0.996. 0.98 fails for i.i.d. values (ρ = 0).
  EXPECT_GT(correlation(here, values_at({0.05 * kSpacing, 0.0, 0.0})), 0.98);
  // Two spacings away in x: no shared lattice node, independent; |ρ| below 5 standard errors
  // (1/√n) of an independent pair's sample correlation.
  EXPECT_LT(std::abs(correlation(here, values_at({2.0 * kSpacing, 0.0, 0.0}))), 5.0 / std::sqrt(double(n)));
}

// The field is a function of position: the same point gets the same value whatever the other
// points, their order, their number (the lattice is drawn once for dense sets, per point for
// sparse ones: same values) and the thread count. That is what makes a fracture independent of
// the mesh's element order.
TEST(ResistanceField, CorrelatedFieldIsAFunctionOfPosition) {
  constexpr std::size_t n = 3 * kResistanceBlock + 11;
  Rng rng(3);
  Eigen::MatrixX3d p(static_cast<Eigen::Index>(n), 3);
  for (Eigen::Index i = 0; i < p.rows(); ++i) p.row(i) << rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5), rng.uniform(0, 0.03);
  const Eigen::VectorXd r = draw_resistance_field(p, 3e6, 1e6, kSpacing, 42, 1);
  EXPECT_TRUE(same_bytes(r, draw_resistance_field(p, 3e6, 1e6, kSpacing, 42, 2)));
  // Reversed order: reversed values.
  const Eigen::MatrixX3d reversed = p.colwise().reverse();
  EXPECT_TRUE(same_bytes(r.reverse(), draw_resistance_field(reversed, 3e6, 1e6, kSpacing, 42, 2)));
  // One point with a companion 1 km away (a lattice far larger than the points: drawn per
  // point) gets the value it had among the dense set.
  Eigen::MatrixX3d sparse(2, 3);
  sparse.row(0) = p.row(17);
  sparse.row(1) << 1000.0, 0.0, 0.0;
  EXPECT_EQ(draw_resistance_field(sparse, 3e6, 1e6, kSpacing, 42)[0], r[17]);
  // Another seed is another field; L = 0 is the per-element draw.
  EXPECT_GT((r.array() != draw_resistance_field(p, 3e6, 1e6, kSpacing, 43).array()).count(), p.rows() - 5);
  EXPECT_TRUE(same_bytes(draw_resistance_field(p, 3e6, 1e6, 0.0, 42), draw_resistance(n, 3e6, 1e6, 42)));
}

TEST(ResistanceField, CorrelatedFieldRefusesBadArguments) {
  const Eigen::MatrixX3d p = Eigen::MatrixX3d::Zero(4, 3);
  for (double l : {-1.0, double(NAN), double(INFINITY)}) EXPECT_THROW(draw_resistance_field(p, 1.0, 0.1, l, 1), InvalidInput) << l;
  Eigen::MatrixX3d bad = p;
  bad(2, 1) = NAN;
  EXPECT_THROW(draw_resistance_field(bad, 1.0, 0.1, kSpacing, 1), InvalidInput);
  Eigen::MatrixX3d far = p;
  far(0, 0) = 1e6;
  EXPECT_THROW(draw_resistance_field(far, 1.0, 0.1, 1e-12, 1), InvalidInput);
  EXPECT_THROW(draw_resistance_field(p, 0.0, 0.1, kSpacing, 1), InvalidInput);
}

}  // namespace
}  // namespace fissure
