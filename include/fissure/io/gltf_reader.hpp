#pragma once
/// Reads back a glTF or GLB that write_scene() wrote (scene_export.hpp) into the ExportScene it
/// was written from, exactly: writing the result again gives the same bytes. `fissure scene
/// merge` joins the slices of a sliced scene fracture this way, so its output is the file an
/// unsliced run writes.
///
/// It reads only what Fissure's writer writes (one buffer, float32 positions and UVs, uint32
/// triangle indices, primitives sharing their node's vertex array, at most one material per
/// primitive, base-colour textures by URI, a tree of nodes whose parents come first) and refuses
/// anything else, naming the file and the element (by its glTF index) that it cannot read: for
/// other glTF files import_scene() (scene_import.hpp) is the reader. A corrupt file is refused,
/// never read past its end.

#include "fissure/io/scene_export.hpp"

#include <filesystem>
#include <string>

namespace fissure {

/// The scene in `path` (.glb or .gltf, by its contents). Throws IoError naming the file when it
/// cannot be read, InvalidInput naming the file and element when it is not one Fissure wrote.
ExportScene read_fissure_gltf(const std::filesystem::path& path);

/// The same from the file's bytes; `name` stands for the file in messages.
ExportScene decode_fissure_gltf(const std::string& bytes, const std::string& name);

}  // namespace fissure
