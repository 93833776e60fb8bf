#pragma once
/// Entries of an on-disk cache of computed results (tet meshes, modal bases), keyed by a content
/// hash of every input (content_hash.hpp), so an entry is either exactly the result asked for or
/// absent. Safe under concurrent runs sharing the directory: an entry is written to a temporary
/// file and renamed into place, so a reader sees a whole entry or none, and two runs writing the
/// same key write the same bytes. Size-capped: after a write the least recently used entries are
/// removed until the directory fits the cap (a read marks an entry used).
///
/// An entry is framed as: 8-byte magic, format version (int64), the 128-bit key, the payload,
/// then a checksum of everything before it. A damaged, truncated or foreign entry reads as absent
/// (and is recomputed and overwritten by the caller), never as a wrong result.

#include "fissure/base/content_hash.hpp"

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace fissure {

struct CacheEntryFormat {
  std::string_view magic;     ///< exactly 8 characters, e.g. "FISSTETS"
  std::int64_t version = 1;   ///< bumped whenever the payload's layout or meaning changes
};

/// Where Fissure's caches live: $FISSURE_CACHE_DIR, else $XDG_CACHE_HOME/fissure, else
/// ~/.cache/fissure (else a folder in the system's temporary directory).
std::filesystem::path default_cache_directory();

/// The cap a cache directory is pruned to: $FISSURE_CACHE_MAX_MB megabytes when set to a
/// positive number, else 4 GiB.
std::uint64_t default_cache_size_limit();

/// The payload of entry `name` in `directory` when it exists, has `format`'s magic and version,
/// holds `key` and passes its checksum; nothing otherwise. Marks the entry as used.
std::optional<std::string> read_cache_entry(const std::filesystem::path& directory, const std::string& name,
                                            const CacheEntryFormat& format, const Hash128& key);

/// Writes entry `name` (creating `directory`), then prunes the directory to `max_bytes`.
/// Returns what went wrong ("cannot create /x: Permission denied"), empty on success: a cache
/// that cannot be written is for the caller to mention, not to fail on.
std::string write_cache_entry(const std::filesystem::path& directory, const std::string& name,
                              const CacheEntryFormat& format, const Hash128& key, std::string_view payload,
                              std::uint64_t max_bytes);

/// Removes the least recently used regular files of `directory` (by modification time, oldest
/// first, then by name) until the rest fit in `max_bytes`; `keep` (a file name) is never removed.
/// Files another run removes meanwhile are skipped. Returns the bytes left.
std::uint64_t prune_cache(const std::filesystem::path& directory, std::uint64_t max_bytes, const std::string& keep = {});

}  // namespace fissure
