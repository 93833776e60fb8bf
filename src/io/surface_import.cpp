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
  if (ext == ".gltf" || ext == ".glb" || ext == ".fbx" || ext == ".dae") return Reader::Assimp;
  throw IoError(name + ": unsupported surface format '" + ext.substr(0, 20) + "' (Fissure reads " + kSurfaceFormats + ")");
}

}  // namespace

namespace io_detail {

std::string read_input_bytes(const fs::path& path, const std::string& name) {
  std::error_code ec;
  const auto size = fs::file_size(path, ec);
  if (!ec) require_memory(static_cast<double>(size), 0, name + ": reading the file");
  return read_file(path);
}

void check_input_file(const fs::path& path) {
  require_nonempty_file(path);
  // A device or FIFO (a link to /dev/zero named part.obj) would be read without end.
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw IoError(path.string() + ": not a regular file");
}

SurfaceMesh read_surface_file(const fs::path& path) {
  const std::string name = path.string();
  check_input_file(path);
  const Reader reader = reader_for(path, name);
  if (reader == Reader::Assimp) return import_with_assimp(path, name);
  const std::string bytes = read_input_bytes(path, name);
  switch (reader) {
    case Reader::Obj: {
      // The colours of its materials from its .mtl files (a missing one leaves them grey).
      SurfaceMesh surface = read_obj(bytes, name);
      apply_material_libraries(path, bytes, surface.appearance, nullptr);
      return surface;
    }
    case Reader::Ply: return read_ply(bytes, name);
    case Reader::Stl: return read_stl(bytes, name);
    default: return read_off(bytes, name);
  }
}

}  // namespace io_detail

SurfaceMesh import_surface(const fs::path& path, SurfaceRepairReport& report, const SurfaceRepairOptions& options) {
  SurfaceMesh read = io_detail::read_surface_file(path);
  try {
    return repair_surface(std::move(read), report, options);
  } catch (const InvalidInput& e) {
    // A scene's objects read as one surface: touching bodies (a curb against a road) cross.
    // The likely cause, and the command that breaks each object on its own.
    const std::string ext = io_detail::lower_ascii(path.extension().string());
    const bool scene_format = ext == ".glb" || ext == ".gltf" || ext == ".fbx" || ext == ".dae" || ext == ".obj";
    if (!scene_format || std::string_view(e.what()).find(": self-intersecting: ") == std::string_view::npos) throw;
    throw InvalidInput(std::string(e.what()) + " (a scene of several objects that touch? fissure scene fracture breaks each on its own)");
  }
}

SurfaceMesh load_surface_input(const std::string& input, SurfaceRepairReport& report) {
  if (is_tile_spec(input)) return make_tile_surface(parse_tile_spec(input));
  return import_surface(input, report);
}

}  // namespace fissure
