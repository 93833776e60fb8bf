#pragma once
/// Surface import through assimp (OBJ, PLY, STL, glTF/GLB, FBX, OFF, and the other formats
/// assimp reads), followed by the checks and safe repairs of repair_surface().

#include "fissure/mesh/surface_mesh.hpp"
#include "fissure/mesh/surface_repair.hpp"

#include <filesystem>
#include <string>

namespace fissure {

/// Every mesh of the file's scene, with node transforms applied, triangulated, identical
/// vertices joined, then repaired. Units: metres are assumed (glTF is metres by definition; FBX
/// files are converted to metres from their UnitScaleFactor; OBJ, PLY, STL and OFF carry no unit
/// and are taken as metres). Throws IoError naming the file when it is missing, empty, unreadable
/// or not a format assimp knows (with assimp's reason), InvalidInput when it holds no triangles or
/// the surface cannot be repaired safely.
SurfaceMesh import_surface(const std::filesystem::path& path, SurfaceRepairReport& report,
                           const SurfaceRepairOptions& options = {});

/// "tile:W,H,T" → the procedural tile; anything else is a surface file for import_surface().
SurfaceMesh load_surface_input(const std::string& input, SurfaceRepairReport& report);

}  // namespace fissure
