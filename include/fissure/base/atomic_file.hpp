#pragma once
/// Safe file writes: a reader (or a crash) never sees a half-written file, an existing file is
/// never lost, and nothing but a regular file is ever replaced.
///
/// Where a write goes depends on what the target is:
/// - a regular file, or a name that does not exist yet: the content goes to a temporary file
///   beside it, is flushed to disk, and is renamed over it (atomic; the old file stays intact
///   on any failure, and keeps its permissions when replaced); a read-only file is refused;
/// - a symbolic link: the same, applied to the file the link points to (followed to the end of
///   the chain, also when that file does not exist yet), so the link itself is kept;
/// - "-": standard output; a FIFO or a character device (/dev/null, a terminal): written
///   directly, in order, every write checked (/dev/full fails with "no space left");
/// - a directory, a block device or a socket: refused.

#include <filesystem>
#include <functional>
#include <string_view>

namespace fissure {

/// Writes `bytes` to `target` as above. Throws IoError naming the file on any failure (a full
/// disk, a missing or read-only directory, a refused special file); a regular target is then
/// untouched and the temporary file removed.
void write_file_atomically(const std::filesystem::path& target, std::string_view bytes);

/// For writers that insist on a file name (OpenCV, libraries): `write_to(temp)` must create
/// `temp`; it is then flushed and renamed over the target (or, for a stream target, copied to
/// it and removed). Exceptions from `write_to` propagate after the temporary file is removed; a
/// missing temporary file is an IoError.
void write_atomically(const std::filesystem::path& target,
                      const std::function<void(const std::filesystem::path& temp)>& write_to);

/// Throws IoError when `target` could not be written: an empty name, a directory, a block
/// device or socket, a missing or unwritable parent directory, a symbolic link loop. Commands
/// call it before any long computation so a typo in an output path costs nothing.
void check_output_path(const std::filesystem::path& target);

/// True when `target` is "-", a FIFO or a character device (after following links): written
/// directly rather than replaced.
bool is_stream_target(const std::filesystem::path& target);

/// Throws IoError naming the file when it is missing, a directory, or empty: the checks every
/// reader makes before handing a path to a library whose own messages are vaguer.
void require_nonempty_file(const std::filesystem::path& path);

/// Reads a whole file. Throws IoError naming the file if it is missing, unreadable or a directory.
std::string read_file(const std::filesystem::path& path);

}  // namespace fissure
