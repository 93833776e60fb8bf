#include "fissure/base/atomic_file.hpp"

#include "fissure/base/error.hpp"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/stat.h>
#include <unistd.h>

namespace fissure {
namespace fs = std::filesystem;
namespace {

std::string errno_text() { return std::strerror(errno); }

// What a path names, without following a final symbolic link.
enum class Kind { Missing, Regular, Link, Stream, Directory, Other };

Kind kind_of(const fs::path& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0) return Kind::Missing;
  if (S_ISLNK(st.st_mode)) return Kind::Link;
  if (S_ISREG(st.st_mode)) return Kind::Regular;
  if (S_ISDIR(st.st_mode)) return Kind::Directory;
  if (S_ISFIFO(st.st_mode) || S_ISCHR(st.st_mode)) return Kind::Stream;
  return Kind::Other;  // block device, socket
}

// Follows symbolic links to the path that is finally written (which may not exist yet).
// Relative link targets are relative to the link's directory, as the kernel reads them.
fs::path resolve_links(const fs::path& target) {
  fs::path path = target;
  for (int depth = 0; depth < 40; ++depth) {
    if (kind_of(path) != Kind::Link) return path;
    std::error_code ec;
    const fs::path next = fs::read_symlink(path, ec);
    if (ec) throw IoError(target.string() + ": cannot read the symbolic link " + path.string() + ": " + ec.message());
    path = next.is_absolute() ? next : path.parent_path() / next;
  }
  throw IoError(target.string() + ": too many levels of symbolic links");
}

fs::path directory_of(const fs::path& path) { return path.has_parent_path() ? path.parent_path() : fs::path("."); }

fs::path temporary_beside(const fs::path& target) {
  static std::atomic<unsigned> counter{0};
  // Keep the extension last: some writers choose the format from it.
  return directory_of(target) / ("." + target.stem().string() + ".tmp" + std::to_string(::getpid()) + "-" +
                                 std::to_string(counter++) + target.extension().string());
}

// Writes all of `bytes` to `fd`, retrying short writes and interruptions.
void write_all(int fd, std::string_view bytes, const std::string& name) {
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw IoError(name + ": write failed: " + errno_text());
    }
    done += static_cast<std::size_t>(n);
  }
}

void fsync_path(const fs::path& path, int flags, const std::string& name) {
  const int fd = ::open(path.c_str(), flags | O_CLOEXEC);
  if (fd < 0) throw IoError(name + ": cannot reopen " + path.string() + " to flush it: " + errno_text());
  const int rc = ::fsync(fd);
  const int saved = errno;
  ::close(fd);
  // Directories on some filesystems do not support fsync (EINVAL): the rename is then as
  // durable as the filesystem makes it.
  if (rc != 0 && !(flags & O_DIRECTORY && (saved == EINVAL || saved == ENOTSUP))) {
    errno = saved;
    throw IoError(name + ": flushing to disk failed: " + errno_text());
  }
}

// Renames the flushed temporary file over `target`, keeping an existing file's permissions.
void commit(const fs::path& temp, const fs::path& target, const std::string& name) {
  struct stat st {};
  if (::stat(target.c_str(), &st) == 0 && S_ISREG(st.st_mode)) ::chmod(temp.c_str(), st.st_mode & 07777);
  fsync_path(temp, O_RDONLY, name);
  if (::rename(temp.c_str(), target.c_str()) != 0) {
    throw IoError(name + ": cannot replace " + target.string() + ": " + errno_text());
  }
  fsync_path(directory_of(target), O_RDONLY | O_DIRECTORY, name);
}

void remove_quietly(const fs::path& path) {
  std::error_code ec;
  fs::remove(path, ec);
}

// Writes to stdout, a FIFO or a character device: no temporary file, no rename.
void write_stream(const fs::path& resolved, std::string_view bytes, const std::string& name) {
  if (resolved == "-") {
    write_all(STDOUT_FILENO, bytes, "standard output");
    return;
  }
  const int fd = ::open(resolved.c_str(), O_WRONLY | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) throw IoError(name + ": cannot open for writing: " + errno_text());
  try {
    write_all(fd, bytes, name);
  } catch (...) {
    ::close(fd);
    throw;
  }
  if (::close(fd) != 0) throw IoError(name + ": write failed: " + errno_text());
}

// The path a write to `target` really goes to, after the checks of check_output_path().
fs::path checked_destination(const fs::path& target) {
  const std::string name = target.string();
  if (target.empty()) throw IoError("output file name is empty");
  if (target == "-") return target;
  const fs::path resolved = resolve_links(target);
  const std::string via = resolved == target ? std::string() : " (the link points to " + resolved.string() + ")";
  switch (kind_of(resolved)) {
    case Kind::Directory: throw IoError(name + ": is a directory" + via);
    case Kind::Other: throw IoError(name + ": is a block device or socket; Fissure writes regular files, FIFOs and character devices" + via);
    case Kind::Stream: return resolved;
    case Kind::Link: break;  // resolve_links never returns a link
    case Kind::Missing: break;
    case Kind::Regular: {
      // A file its owner made read-only is kept: renaming over it would succeed (the directory
      // is writable) and silently undo the protection. Root passes access(), so the mode bits
      // are read too.
      struct stat st {};
      if (::stat(resolved.c_str(), &st) == 0 && ((st.st_mode & 0222) == 0 || ::access(resolved.c_str(), W_OK) != 0))
        throw IoError(name + ": is read-only; make it writable (chmod u+w) to replace it, or write elsewhere" + via);
      break;
    }
  }
  const fs::path dir = directory_of(resolved);
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw IoError(name + ": directory " + dir.string() + " does not exist" + via);
  if (::access(dir.c_str(), W_OK | X_OK) != 0) {
    throw IoError(name + ": cannot write in directory " + dir.string() + ": " + errno_text() + via);
  }
  return resolved;
}

}  // namespace

bool is_stream_target(const fs::path& target) {
  if (target == "-") return true;
  return kind_of(resolve_links(target)) == Kind::Stream;
}

void check_output_path(const fs::path& target) { checked_destination(target); }

void write_file_atomically(const fs::path& target, std::string_view bytes) {
  const std::string name = target.string();
  const fs::path destination = checked_destination(target);
  if (destination == "-" || kind_of(destination) == Kind::Stream) {
    write_stream(destination, bytes, name);
    return;
  }
  const fs::path temp = temporary_beside(destination);
  const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0) throw IoError(name + ": cannot create a temporary file in " + directory_of(destination).string() + ": " + errno_text());
  try {
    write_all(fd, bytes, name);
    if (::fsync(fd) != 0) throw IoError(name + ": flushing to disk failed: " + errno_text());
    if (::close(fd) != 0) {
      remove_quietly(temp);
      throw IoError(name + ": write failed: " + errno_text());
    }
  } catch (...) {
    ::close(fd);
    remove_quietly(temp);
    throw;
  }
  try {
    commit(temp, destination, name);
  } catch (...) {
    remove_quietly(temp);
    throw;
  }
}

void write_atomically(const fs::path& target, const std::function<void(const fs::path& temp)>& write_to) {
  const std::string name = target.string();
  const fs::path destination = checked_destination(target);
  const bool stream = destination == "-" || kind_of(destination) == Kind::Stream;
  // A stream's directory (/dev) is no place for a temporary file: use the system's.
  const fs::path temp = stream ? temporary_beside(fs::temp_directory_path() / ("fissure" + target.extension().string()))
                               : temporary_beside(destination);
  try {
    write_to(temp);
    if (!fs::exists(temp)) throw IoError(name + ": the writer produced no file");
    if (stream) {
      write_stream(destination, read_file(temp), name);
      remove_quietly(temp);
    } else {
      commit(temp, destination, name);
    }
  } catch (...) {
    remove_quietly(temp);
    throw;
  }
}

namespace {
void require_existing_file(const fs::path& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw IoError(path.string() + ": no such file");
  if (fs::is_directory(path, ec)) throw IoError(path.string() + ": is a directory");
}
}  // namespace

void require_nonempty_file(const fs::path& path) {
  require_existing_file(path);
  std::error_code ec;
  if (fs::is_regular_file(path, ec) && fs::file_size(path, ec) == 0) throw IoError(path.string() + ": file is empty");
}

std::string read_file(const fs::path& path) {
  require_existing_file(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path.string() + ": cannot open for reading");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw IoError(path.string() + ": read failed");
  return buffer.str();
}

}  // namespace fissure
