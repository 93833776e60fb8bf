#include "fissure/fracture/resistance_field.hpp"

#include "fissure/base/error.hpp"
#include "fissure/base/number_text.hpp"
#include "fissure/base/parallel.hpp"
#include "fissure/base/rng.hpp"

#include <algorithm>
#include <cmath>

namespace fissure {

Eigen::VectorXd draw_resistance(std::size_t tet_count, double mean, double stddev, std::uint64_t seed, int threads) {
  if (!(std::isfinite(mean) && mean > 0.0)) {
    throw InvalidInput("resistance field: mean resistance " + format_number(mean) + " Pa is not positive and finite");
  }
  if (!(std::isfinite(stddev) && stddev >= 0.0)) {
    throw InvalidInput("resistance field: resistance stddev " + format_number(stddev) +
                       " Pa is not non-negative and finite");
  }
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

}  // namespace fissure
