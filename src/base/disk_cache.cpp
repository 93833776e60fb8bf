#include "fissure/base/disk_cache.hpp"

#include "fissure/base/atomic_file.hpp"
#include "fissure/base/error.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <string>
#include <system_error>
#include <tuple>
#include <vector>

namespace fissure {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kHeaderBytes = 8 + 8 + 16;
constexpr std::size_t kChecksumBytes = 16;

void append_pod(std::string& out, const void* data, std::size_t size) { out.append(static_cast<const char*>(data), size); }

}  // namespace

fs::path default_cache_directory() {
  if (const char* dir = std::getenv("FISSURE_CACHE_DIR"); dir && *dir) return dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return fs::path(xdg) / "fissure";
  if (const char* home = std::getenv("HOME"); home && *home) return fs::path(home) / ".cache" / "fissure";
  return fs::temp_directory_path() / "fissure-cache";
}

std::uint64_t default_cache_size_limit() {
  if (const char* text = std::getenv("FISSURE_CACHE_MAX_MB"); text && *text) {
    char* end = nullptr;
    const double mb = std::strtod(text, &end);
    if (end && *end == '\0' && mb > 0.0 && mb < 1e9) return static_cast<std::uint64_t>(mb * 1024.0 * 1024.0);
  }
  return std::uint64_t{4} << 30;
}

std::optional<std::string> read_cache_entry(const fs::path& directory, const std::string& name,
                                            const CacheEntryFormat& format, const Hash128& key) {
  const fs::path file = directory / name;
  std::string bytes;
  try {
    std::error_code ec;
    if (!fs::is_regular_file(file, ec)) return std::nullopt;
    bytes = read_file(file);
  } catch (const Error&) {
    return std::nullopt;  // removed by another run meanwhile, or unreadable: recompute
  }
  if (bytes.size() < kHeaderBytes + kChecksumBytes || format.magic.size() != 8) return std::nullopt;
  if (std::memcmp(bytes.data(), format.magic.data(), 8) != 0) return std::nullopt;
  std::int64_t version = 0;
  Hash128 stored_key, checksum;
  std::memcpy(&version, bytes.data() + 8, 8);
  std::memcpy(&stored_key.hi, bytes.data() + 16, 8);
  std::memcpy(&stored_key.lo, bytes.data() + 24, 8);
  const std::size_t body = bytes.size() - kChecksumBytes;
  std::memcpy(&checksum.hi, bytes.data() + body, 8);
  std::memcpy(&checksum.lo, bytes.data() + body + 8, 8);
  if (version != format.version || !(stored_key == key)) return std::nullopt;
  if (!(ContentHasher().add_bytes(bytes.data(), body).finish() == checksum)) return std::nullopt;
  std::error_code ec;
  fs::last_write_time(file, fs::file_time_type::clock::now(), ec);  // used now; failing only ages it
  return bytes.substr(kHeaderBytes, body - kHeaderBytes);
}

std::string write_cache_entry(const fs::path& directory, const std::string& name, const CacheEntryFormat& format,
                              const Hash128& key, std::string_view payload, std::uint64_t max_bytes) {
  if (format.magic.size() != 8) throw InvalidInput("cache entry magic must be 8 characters");
  std::error_code ec;
  fs::create_directories(directory, ec);
  if (ec) return "cannot create " + directory.string() + ": " + ec.message();
  std::string out;
  out.reserve(kHeaderBytes + payload.size() + kChecksumBytes);
  out.append(format.magic);
  append_pod(out, &format.version, 8);
  append_pod(out, &key.hi, 8);
  append_pod(out, &key.lo, 8);
  out.append(payload);
  const Hash128 checksum = ContentHasher().add_bytes(out.data(), out.size()).finish();
  append_pod(out, &checksum.hi, 8);
  append_pod(out, &checksum.lo, 8);
  try {
    write_file_atomically(directory / name, out);
  } catch (const Error& e) {
    return e.what();
  }
  prune_cache(directory, max_bytes, name);
  return {};
}

std::uint64_t prune_cache(const fs::path& directory, std::uint64_t max_bytes, const std::string& keep) {
  struct Entry {
    fs::file_time_type time;
    std::string name;
    std::uint64_t size;
  };
  std::vector<Entry> entries;
  std::uint64_t total = 0;
  std::error_code ec;
  for (fs::directory_iterator it(directory, ec), end; !ec && it != end; it.increment(ec)) {
    std::error_code e;
    if (!it->is_regular_file(e) || e) continue;
    const std::string file = it->path().filename().string();
    if (file.rfind('.', 0) == 0) continue;  // another run's temporary file, still being written
    const std::uint64_t size = it->file_size(e);
    if (e) continue;
    const fs::file_time_type time = it->last_write_time(e);
    if (e) continue;
    total += size;
    if (file != keep) entries.push_back({time, file, size});
  }
  std::sort(entries.begin(), entries.end(),
            [](const Entry& a, const Entry& b) { return std::tie(a.time, a.name) < std::tie(b.time, b.name); });
  for (const Entry& entry : entries) {
    if (total <= max_bytes) break;
    std::error_code e;
    fs::remove(directory / entry.name, e);
    total -= entry.size;  // removed by us or by another run: gone either way
  }
  return total;
}

}  // namespace fissure
