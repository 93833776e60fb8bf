#include "memory_estimate.hpp"

#include <limits>

namespace fissure::cli {

double static_solve_bytes(double tets) { return 68e6 + 4440.0 * tets; }

std::uint64_t memory_limit(bool allow_large) {
  return allow_large ? std::numeric_limits<std::uint64_t>::max() : 0;
}

}  // namespace fissure::cli
