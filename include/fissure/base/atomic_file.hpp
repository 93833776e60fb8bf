#pragma once
/// Atomic file writes: a reader (or a crash) never sees a half-written file and an existing file
/// is never lost. The content goes to a temporary file beside the target, is flushed to disk, and
/// is then renamed over the target.

#include <filesystem>
#include <functional>
#include <string_view>

namespace fissure {

/// Writes `bytes` to `target` atomically. Throws IoError naming the file on any failure; the
/// target is then untouched and the temporary file removed.
void write_file_atomically(const std::filesystem::path& target, std::string_view bytes);

/// For writers that insist on a file name (gmsh, OpenCV, assimp): `write_to(temp)` must create
/// `temp`; it is then flushed and renamed over `target`. Exceptions from `write_to` propagate after
/// the temporary file is removed; a missing temporary file is an IoError.
void write_atomically(const std::filesystem::path& target,
                      const std::function<void(const std::filesystem::path& temp)>& write_to);

/// Throws IoError when `target` could not be written atomically: empty name, a directory, or a
/// missing parent directory. Commands call it before any long computation so a typo in an output
/// path costs nothing.
void check_output_path(const std::filesystem::path& target);

/// Throws IoError naming the file when it is missing, a directory, or empty: the checks every
/// reader makes before handing a path to a library whose own messages are vaguer.
void require_nonempty_file(const std::filesystem::path& path);

/// Reads a whole file. Throws IoError naming the file if it is missing, unreadable or a directory.
std::string read_file(const std::filesystem::path& path);

}  // namespace fissure
