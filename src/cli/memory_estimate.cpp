#include "memory_estimate.hpp"

#include "fissure/base/error.hpp"
#include "fissure/base/memory.hpp"

#include <limits>
#include <string>

namespace fissure::cli {

double meshing_bytes(double tets) { return 96e6 + 684.0 * tets; }

double modal_bytes(double tets, double nodes, double modes) {
  constexpr double kRigidModes = 6.0;
  return 50e6 + 4800.0 * tets + 40.0 * 3.0 * nodes * (modes + kRigidModes);
}

double static_solve_bytes(double tets) { return 68e6 + 4440.0 * tets; }

std::uint64_t memory_limit(bool allow_large) {
  return allow_large ? std::numeric_limits<std::uint64_t>::max() : 0;
}

void require_memory_unless_allowed(double estimated_bytes, bool allow_large, const char* what) {
  try {
    require_memory(estimated_bytes, memory_limit(allow_large), what);
  } catch (const InvalidInput& e) {
    throw InvalidInput(std::string(e.what()) + "; --allow-large tries anyway");
  }
}

}  // namespace fissure::cli
