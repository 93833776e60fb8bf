#include "fissure/fracture/resistance_field.hpp"

#include "fissure/base/error.hpp"
#include "fissure/base/normal_distribution.hpp"
#include "fissure/base/number_text.hpp"
#include "fissure/base/parallel.hpp"
#include "fissure/base/rng.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace fissure {
namespace {

void check_spread(double mean, double stddev) {
  if (!(std::isfinite(mean) && mean > 0.0)) {
    throw InvalidInput("resistance field: mean resistance " + format_number(mean) + " Pa is not positive and finite");
  }
  if (!(std::isfinite(stddev) && stddev >= 0.0)) {
    throw InvalidInput("resistance field: resistance stddev " + format_number(stddev) +
                       " Pa is not non-negative and finite");
  }
}

// The lattice node's standard normal: a function of (seed, i, j, k) only.
double lattice_value(std::uint64_t seed, std::int64_t i, std::int64_t j, std::int64_t k) {
  // Distinct odd multipliers spread the three indices over the 64-bit index Rng::derive mixes.
  const std::uint64_t index = static_cast<std::uint64_t>(i) * 0x9E3779B97F4A7C15ULL ^
                              static_cast<std::uint64_t>(j) * 0xC2B2AE3D27D4EB4FULL ^
                              static_cast<std::uint64_t>(k) * 0x165667B19E3779F9ULL;
  return Rng::derive(seed, "resistance_field", index).normal();
}

double smoothstep(double u) { return u * u * (3.0 - 2.0 * u); }

}  // namespace

Eigen::VectorXd draw_resistance(std::size_t tet_count, double mean, double stddev, std::uint64_t seed, int threads) {
  check_spread(mean, stddev);
  Eigen::VectorXd r(static_cast<Eigen::Index>(tet_count));
  if (stddev == 0.0) {
    r.setConstant(mean);
    return r;
  }
  const double floor = kResistanceFloorFraction * mean;
  const std::size_t blocks = (tet_count + kResistanceBlock - 1) / kResistanceBlock;
  // Each block owns its stream and its slots: the thread that draws it does not matter.
  parallel_for(blocks, threads, [&](std::size_t b) {
    Rng rng = Rng::derive(seed, "resistance", b);
    const std::size_t end = std::min(tet_count, (b + 1) * kResistanceBlock);
    for (std::size_t e = b * kResistanceBlock; e < end; ++e) {
      double value;
      do {
        value = rng.normal(mean, stddev);
      } while (value < floor);  // resample: see the header for why not clamp
      r[static_cast<Eigen::Index>(e)] = value;
    }
  });
  return r;
}

Eigen::VectorXd draw_resistance_field(const Eigen::MatrixX3d& points, double mean, double stddev,
                                      double correlation_length, std::uint64_t seed, int threads) {
  check_spread(mean, stddev);
  if (!(std::isfinite(correlation_length) && correlation_length >= 0.0)) {
    throw InvalidInput("resistance field: correlation length " + format_number(correlation_length) +
                       " m is not non-negative and finite");
  }
  if (!points.allFinite()) throw InvalidInput("resistance field: a point is not finite");
  const auto n = static_cast<std::size_t>(points.rows());
  if (correlation_length == 0.0) return draw_resistance(n, mean, stddev, seed, threads);
  Eigen::VectorXd r(points.rows());
  if (n == 0) return r;
  if (stddev == 0.0) {
    r.setConstant(mean);
    return r;
  }
  const Eigen::RowVector3d lo = points.colwise().minCoeff(), hi = points.colwise().maxCoeff();
  if (std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff()) / correlation_length > 0x1p52) {
    throw InvalidInput("resistance field: correlation length " + format_number(correlation_length) +
                       " m is too small for a body reaching " +
                       format_number(std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff())) + " m");
  }
  // The lattice nodes over the bounding box, drawn once when there are not many more of them
  // than points (else each point draws its eight corners: the same values, more slowly).
  std::array<std::int64_t, 3> first{}, count{};
  double nodes = 1.0;
  for (int a = 0; a < 3; ++a) {
    first[static_cast<std::size_t>(a)] = static_cast<std::int64_t>(std::floor(lo(a) / correlation_length));
    count[static_cast<std::size_t>(a)] =
        static_cast<std::int64_t>(std::floor(hi(a) / correlation_length)) - first[static_cast<std::size_t>(a)] + 2;
    nodes *= static_cast<double>(count[static_cast<std::size_t>(a)]);
  }
  std::vector<double> grid;
  if (nodes <= 4.0 * static_cast<double>(n) + 4096.0) {
    grid.resize(static_cast<std::size_t>(nodes));
    parallel_for(static_cast<std::size_t>(count[2]), threads, [&](std::size_t kk) {
      for (std::int64_t jj = 0; jj < count[1]; ++jj)
        for (std::int64_t ii = 0; ii < count[0]; ++ii)
          grid[(kk * static_cast<std::size_t>(count[1]) + static_cast<std::size_t>(jj)) * static_cast<std::size_t>(count[0]) +
               static_cast<std::size_t>(ii)] =
              lattice_value(seed, first[0] + ii, first[1] + jj, first[2] + static_cast<std::int64_t>(kk));
    });
  }
  auto node = [&](std::int64_t i, std::int64_t j, std::int64_t k) {
    if (grid.empty()) return lattice_value(seed, i, j, k);
    return grid[(static_cast<std::size_t>(k - first[2]) * static_cast<std::size_t>(count[1]) +
                 static_cast<std::size_t>(j - first[1])) *
                    static_cast<std::size_t>(count[0]) +
                static_cast<std::size_t>(i - first[0])];
  };
  const double alpha = (kResistanceFloorFraction * mean - mean) / stddev;
  const double tail_alpha = standard_normal_tail(alpha);   // Q(α) = P(Z > α): the kept mass
  const double head_alpha = standard_normal_tail(-alpha);  // Φ(α): the mass cut away
  const std::size_t blocks = (n + kResistanceBlock - 1) / kResistanceBlock;
  parallel_for(blocks, threads, [&](std::size_t b) {
    const std::size_t end = std::min(n, (b + 1) * kResistanceBlock);
    for (std::size_t e = b * kResistanceBlock; e < end; ++e) {
      const auto row = static_cast<Eigen::Index>(e);
      std::array<std::int64_t, 3> cell{};
      std::array<double, 3> s{};
      for (int a = 0; a < 3; ++a) {
        const double x = points(row, a) / correlation_length;
        const double f = std::floor(x);
        cell[static_cast<std::size_t>(a)] = static_cast<std::int64_t>(f);
        s[static_cast<std::size_t>(a)] = smoothstep(x - f);
      }
      double sum = 0.0, weights = 0.0;
      for (int c = 0; c < 8; ++c) {
        double w = 1.0;
        for (int a = 0; a < 3; ++a) w *= (c >> a & 1) ? s[static_cast<std::size_t>(a)] : 1.0 - s[static_cast<std::size_t>(a)];
        sum += w * node(cell[0] + (c & 1), cell[1] + (c >> 1 & 1), cell[2] + (c >> 2 & 1));
        weights += w * w;
      }
      const double z = sum / std::sqrt(weights);
      // Quantile mapping onto the truncated normal, in the tail z lies in so neither loses its
      // precision to a 1 − p: above, P(R > r) = Q((r − mean)/stddev)/Q(α) = Q(z); below,
      // P(R < r) = (Φ((r − mean)/stddev) − Φ(α))/Q(α) = Φ(z), with Φ(x) = Q(−x).
      const double value =
          z >= 0.0 ? mean + stddev * standard_normal_tail_quantile(tail_alpha * standard_normal_tail(z))
                   : mean - stddev * standard_normal_tail_quantile(head_alpha + tail_alpha * standard_normal_tail(-z));
      r[row] = std::max(value, kResistanceFloorFraction * mean);  // round-off at the floor
    }
  });
  return r;
}

Eigen::VectorXd draw_resistance(const Eigen::MatrixX3d& centroids, const FractureParams& params, std::uint64_t seed,
                                int threads) {
  return draw_resistance_field(centroids, params.resistance_mean, params.resistance_stddev,
                               params.resistance_correlation, seed, threads);
}

}  // namespace fissure
