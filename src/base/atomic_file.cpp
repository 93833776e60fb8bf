#include "fissure/base/atomic_file.hpp"

#include "fissure/base/error.hpp"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>

namespace fissure {
namespace fs = std::filesystem;
namespace {

fs::path temporary_beside(const fs::path& target) {
  static std::atomic<unsigned> counter{0};
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  // Keep the extension last: some writers (gmsh, OpenCV) choose the format from it.
  return dir / ("." + target.stem().string() + ".tmp" + std::to_string(::getpid()) + "-" +
                std::to_string(counter++) + target.extension().string());
}

void flush_to_disk(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) {
    throw IoError(path.string() + ": cannot reopen to flush: " + std::strerror(errno));
  }
  const int rc = ::fsync(fd);
  ::close(fd);
  if (rc != 0) throw IoError(path.string() + ": fsync failed: " + std::strerror(errno));
}

void commit(const fs::path& temp, const fs::path& target) {
  flush_to_disk(temp);
  std::error_code ec;
  fs::rename(temp, target, ec);
  if (ec) {
    fs::remove(temp, ec);
    throw IoError(target.string() + ": cannot replace: " + ec.message());
  }
}

}  // namespace

void write_file_atomically(const fs::path& target, std::string_view bytes) {
  write_atomically(target, [&](const fs::path& temp) {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    if (!out) throw IoError(target.string() + ": cannot create " + temp.string());
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) throw IoError(target.string() + ": write failed (disk full?)");
  });
}

void check_output_path(const fs::path& target) {
  if (target.empty()) throw IoError("output file name is empty");
  if (fs::is_directory(target)) throw IoError(target.string() + ": is a directory");
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  if (!fs::is_directory(dir)) {
    throw IoError(target.string() + ": directory " + dir.string() + " does not exist");
  }
}

void write_atomically(const fs::path& target,
                      const std::function<void(const fs::path& temp)>& write_to) {
  check_output_path(target);
  const fs::path temp = temporary_beside(target);
  try {
    write_to(temp);
    if (!fs::exists(temp)) throw IoError(target.string() + ": the writer produced no file");
    commit(temp, target);
  } catch (...) {
    std::error_code ec;
    fs::remove(temp, ec);
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
  if (fs::file_size(path, ec) == 0) throw IoError(path.string() + ": file is empty");
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
