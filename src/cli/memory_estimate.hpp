#pragma once
// The memory limit of --allow-large, and the one estimate the core does not make itself: a direct
// static solve (tetrahedralize and the modal basis check their own estimates against the limit
// their options carry). A request far beyond the machine is refused at once with the estimate;
// main() adds the --allow-large hint to every MemoryLimitExceeded.
//
// The coefficients are peak RSS measurements of this CLI (GNU time -v, Release build, the
// tile:1,1,0.05 plate); the estimates are linear fits through them, within 3 % at every measured
// point. Sparse factors fill in faster than linearly in 3-D, so far beyond the measured sizes the
// estimates are low: the safe side for a refusal, which must never hit a request that fits.

#include <cstdint>

namespace fissure::cli {

/// A direct static solve, bytes. Measured with `fissure solve`: 162.9 MB at 21 486 tets, 943.0 MB
/// at 197 378 tets: 4.44 kB a tet on top of 68 MB.
double static_solve_bytes(double tets);

/// The limit passed to require_memory: 0 (the machine's physical memory) or, with
/// --allow-large, no limit.
std::uint64_t memory_limit(bool allow_large);

}  // namespace fissure::cli
