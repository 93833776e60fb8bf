#pragma once
// Private to io: Fissure's strict readers of the simple surface formats, OBJ, PLY (ASCII and
// binary, either byte order), STL (ASCII and binary) and OFF.
//
// assimp 5.2.5 crashes on truncated PLY and OFF (a SIGSEGV in its binary PLY reader, an
// ai_assert abort in its triangulation), hangs or allocates without bound when a header claims
// 2·10⁹ vertices, and drops NaN vertices without a word (measured: docs/architecture.md, "Surface
// import"). These readers check every count against the bytes that remain before allocating,
// every index against the vertex count and every coordinate for finiteness, and throw IoError
// naming the file, the line (in text) and the 1-based vertex, face or facet. Each takes the whole
// file's bytes; `name` prefixes every message. The result is not yet repaired.

#include "fissure/mesh/surface_mesh.hpp"

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace fissure::io_detail {

/// Wavefront OBJ: `v` and `f` lines (`f 1/2/3 …`, negative indices count back from the last
/// vertex), and `vt` and `usemtl` as the appearance; points, lines, normals and groups are ignored.
/// Per triangle of an OBJ surface, the object (`o NAME`) it belongs to: names[0] is "" (the
/// faces before the first `o`).
struct ObjObjects {
  std::vector<std::string> names;
  std::vector<int> triangle_object;
};
SurfaceMesh read_obj(std::string_view bytes, const std::string& name, ObjObjects* objects = nullptr);

/// The MTL files an OBJ's `mtllib` lines name, as written (relative to the OBJ's folder).
std::vector<std::string> obj_material_libraries(std::string_view obj_bytes, const std::string& name);

/// A Wavefront MTL's materials: per `newmtl`, its `Kd` colour (when given) and `map_Kd` texture
/// reference (the file name as written, or empty). Throws IoError naming the file and line for
/// a Kd that is not three numbers or a statement before any newmtl.
struct MtlMaterial {
  std::string name;
  std::optional<Eigen::Vector3d> colour;
  std::string texture;
};
std::vector<MtlMaterial> read_mtl(std::string_view bytes, const std::string& name);

/// The MTL files the OBJ `obj` (whose bytes are `obj_bytes`) names, read from beside it: each
/// material of `look` named in one takes its Kd colour. Returns per material name its map_Kd
/// reference. A library that is not there adds a line to `warnings` (when given) and changes
/// nothing; a corrupt one throws IoError "<obj>: its material library <mtl>:<line>: …".
std::map<std::string, std::string> apply_material_libraries(const std::filesystem::path& obj, std::string_view obj_bytes,
                                                            SurfaceAppearance& look, std::vector<std::string>* warnings);

/// Stanford PLY 1.0, `ascii`, `binary_little_endian` or `binary_big_endian`: the `vertex`
/// element's x, y, z (and texture coordinates s, t / u, v / texture_u, texture_v, kept as the
/// appearance) and the `face` element's `vertex_indices` (or `vertex_index`) list, of any PLY
/// scalar type; other elements and properties are read past.
SurfaceMesh read_ply(std::string_view bytes, const std::string& name);

/// STL, binary (when the size is 84 + 50·count or the file does not start with "solid") or
/// ASCII; each facet brings its own three vertices, joined later by repair_surface.
SurfaceMesh read_stl(std::string_view bytes, const std::string& name);

/// Object File Format (OFF, COFF, NOFF, CNOFF, STOFF and the like; the keyword may be omitted):
/// the first three numbers of each vertex line, then faces "n i₁ … iₙ [colour]".
SurfaceMesh read_off(std::string_view bytes, const std::string& name);

/// Throws IoError naming the file when it is missing, empty or not a regular file (a device or
/// FIFO would be read without end).
void check_input_file(const std::filesystem::path& path);

/// The whole file, once its size fits in memory (require_memory: "<name>: reading the file
/// needs about …"). Throws IoError naming the file when it cannot be read.
std::string read_input_bytes(const std::filesystem::path& path, const std::string& name);

/// The file by its extension (case-insensitive; assimp's guess from the content would hand a file
/// that is not what its name says to a reader that was never fuzzed with it): OBJ, PLY, STL, OFF
/// by the readers above, glTF, GLB and FBX through assimp with node transforms applied. Not yet
/// repaired. The messages of import_surface().
SurfaceMesh read_surface_file(const std::filesystem::path& path);

}  // namespace fissure::io_detail
