#pragma once
/// Surface import: OBJ, PLY (ASCII and binary), STL (ASCII and binary) and OFF through Fissure's
/// own strict readers; glTF, GLB and FBX through assimp, its output checked before it is
/// trusted. Then the checks and safe repairs of repair_surface().

#include "fissure/mesh/surface_mesh.hpp"
#include "fissure/mesh/surface_repair.hpp"

#include <filesystem>
#include <string>

namespace fissure {

/// The formats import_surface() reads, for messages and help texts.
inline constexpr const char* kSurfaceFormats = "OBJ, PLY, STL, OFF, glTF, GLB, FBX and COLLADA (.dae)";

/// Every mesh of the file, triangulated (convex faces as fans, others ear-clipped), then
/// repaired; for glTF, FBX and COLLADA every mesh of the scene with node transforms applied. The
/// format is chosen by the extension (case-insensitive). Units: metres are assumed (glTF is metres
/// by definition; FBX files are converted to metres from their UnitScaleFactor, COLLADA files
/// from their <unit meter> and Z_UP turned to +Y; OBJ, PLY, STL and OFF carry no unit and are
/// taken as metres).
///
/// Throws IoError naming the file when it is missing, empty, not a regular file (a device or
/// FIFO would be read without end), unreadable, of another format, or
/// corrupt: the message names the line (text formats) and the 1-based vertex, face or facet
/// ("part.ply: vertex 17 has a non-finite coordinate", "part.obj:40: face 5 references vertex
/// 12, but only 8 vertices come before it"). Counts in headers are checked against the file's
/// size before anything is allocated, so memory stays a small multiple of the file's size.
/// Throws InvalidInput when the file holds no faces, when reading it would need more memory
/// than the machine has, or when the surface cannot be repaired safely. Cost: O(file size) to
/// read, then repair_surface().
SurfaceMesh import_surface(const std::filesystem::path& path, SurfaceRepairReport& report,
                           const SurfaceRepairOptions& options = {});

/// "tile:W,H,T" → the procedural tile; anything else is a surface file for import_surface().
SurfaceMesh load_surface_input(const std::string& input, SurfaceRepairReport& report);

}  // namespace fissure
