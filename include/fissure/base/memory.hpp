#pragma once
/// Memory limits: requests far beyond the machine (a 50M-tet mesh, 5000 modes of a large body)
/// are refused before any work, with the estimate, instead of swapping or being killed after
/// minutes.

#include <cstdint>
#include <string>
#include <string_view>

namespace fissure {

/// Physical memory of this machine in bytes (sysconf), or 0 when unknown.
std::uint64_t physical_memory_bytes();

/// "38.2 GB", "512 MB", "12 kB": bytes in decimal units with three significant digits.
std::string format_bytes(double bytes);

/// Throws MemoryLimitExceeded (an InvalidInput) "<what> needs about <estimate>, more than the <limit> allowed (this
/// machine has <physical>)" when `estimated_bytes` > `limit_bytes`. A limit of 0 means the
/// machine's physical memory; pass UINT64_MAX to allow anything.
void require_memory(double estimated_bytes, std::uint64_t limit_bytes, std::string_view what);

}  // namespace fissure
