#include "fissure/base/memory.hpp"

#include "fissure/base/error.hpp"
#include "fissure/base/number_text.hpp"

#include <string>
#include <unistd.h>

namespace fissure {

std::uint64_t physical_memory_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES);
  const long page_size = ::sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page_size <= 0) return 0;
  return static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page_size);
}

std::string format_bytes(double bytes) {
  const char* units[] = {"B", "kB", "MB", "GB", "TB", "PB"};
  int unit = 0;
  while (bytes >= 1000.0 && unit < 5) {
    bytes /= 1000.0;
    ++unit;
  }
  return format_number(bytes, 3) + " " + units[unit];
}

void require_memory(double estimated_bytes, std::uint64_t limit_bytes, std::string_view what) {
  const std::uint64_t physical = physical_memory_bytes();
  const std::uint64_t limit = limit_bytes == 0 ? physical : limit_bytes;
  if (limit == 0 || !(estimated_bytes > static_cast<double>(limit))) return;
  throw MemoryLimitExceeded(std::string(what) + " needs about " + format_bytes(estimated_bytes) + ", more than the " +
                     format_bytes(static_cast<double>(limit)) + " allowed (this machine has " +
                     format_bytes(static_cast<double>(physical)) + ")");
}

}  // namespace fissure
