#include "fissure/io/surface_import.hpp"

#include "assimp_import.hpp"
#include "byte_cursor.hpp"
#include "surface_readers.hpp"

#include "fissure/base/atomic_file.hpp"
#include "fissure/base/error.hpp"
#include "fissure/base/memory.hpp"
#include "fissure/mesh/tile.hpp"

namespace fissure {
namespace fs = std::filesystem;

namespace {

enum class Reader { Obj, Ply, Stl, Off, Assimp };

// By extension, case-insensitively: assimp's guess from the content would hand a file that is
// not what its name says to a reader that was never fuzzed with it.
Reader reader_for(const fs::path& path, const std::string& name) {
  const std::string ext = io_detail::lower_ascii(path.extension().string());
  if (ext == ".obj") return Reader::Obj;
  if (ext == ".ply") return Reader::Ply;
  if (ext == ".stl") return Reader::Stl;
  if (ext == ".off") return Reader::Off;
  if (ext == ".gltf" || ext == ".glb" || ext == ".fbx") return Reader::Assimp;
  throw IoError(name + ": unsupported surface format '" + ext.substr(0, 20) + "' (Fissure reads " + kSurfaceFormats + ")");
}

}  // namespace

SurfaceMesh import_surface(const fs::path& path, SurfaceRepairReport& report, const SurfaceRepairOptions& options) {
  const std::string name = path.string();
  require_nonempty_file(path);
  // A device or FIFO (a link to /dev/zero named part.obj) would be read without end.
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw IoError(name + ": not a regular file");
  const Reader reader = reader_for(path, name);
  SurfaceMesh surface;
  if (reader == Reader::Assimp) {
    surface = io_detail::import_with_assimp(path, name);
  } else {
    const auto size = fs::file_size(path, ec);
    if (!ec) require_memory(static_cast<double>(size), 0, name + ": reading the file");
    const std::string bytes = read_file(path);
    switch (reader) {
      case Reader::Obj: surface = io_detail::read_obj(bytes, name); break;
      case Reader::Ply: surface = io_detail::read_ply(bytes, name); break;
      case Reader::Stl: surface = io_detail::read_stl(bytes, name); break;
      default: surface = io_detail::read_off(bytes, name); break;
    }
  }
  return repair_surface(surface, report, options);
}

SurfaceMesh load_surface_input(const std::string& input, SurfaceRepairReport& report) {
  if (is_tile_spec(input)) return make_tile_surface(parse_tile_spec(input));
  return import_surface(input, report);
}

}  // namespace fissure
