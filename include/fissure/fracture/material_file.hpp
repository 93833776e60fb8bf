#pragma once
/// A fracture material: the physical properties and the fracture parameters of FractureParams,
/// with a name, a description and where the values come from, as a versioned JSON file
/// (docs/materials.md shows one):
///
///   { "schema": "fissure-material", "version": 1, "name": "glass", "description": "…",
///     "provenance": ["EN 572-1: …", …],
///     "parameters": { "youngs_modulus": 7e10, …, "relaxation": "directional", … } }
///
/// Every key of fracture_parameter_table() and "relaxation" is required in "parameters"; so are
/// "schema", "version", "name" and "parameters"; "description" and "provenance" are optional.
/// An unknown key is an error (it is a typo, or a key of a newer version), and so is a key given
/// twice (JSON readers would silently keep one of them).
#include "fissure/fracture/fracture_params.hpp"
#include "fissure/fracture/material_fit.hpp"

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace fissure {

constexpr const char* kMaterialSchema = "fissure-material";
/// Written as "version". Version 2 added the optional "fit" object; version 1 files (no "fit")
/// are still read. Readers refuse other versions.
constexpr int kMaterialVersion = 2;
/// The material used when none is given: assets/materials/ceramic-tile.json.
constexpr const char* kDefaultMaterialName = "ceramic-tile";

struct FractureMaterial {
  std::string name;                     ///< e.g. "ceramic-tile"; a bundled file is <name>.json
  std::string description;              ///< one line for a user
  FractureParams params;
  std::vector<std::string> provenance;  ///< one source note per entry: reference, values, ranges
  std::optional<MaterialFit> fit;       ///< set by `fissure fit`
};

/// The file's text (2-space indented, keys in table order, numbers round-trip exactly). Throws
/// InvalidInput `material "<name>": <problems>` when the parameters are out of range or the
/// name is empty: an invalid material is never written.
std::string material_to_json(const FractureMaterial& material);

/// Parses a material file's text. Errors name `source` (the file) and the key:
/// - IoError "<source>: not a valid material file: <what>" for a syntax error, another schema
///   or version, a missing, unknown, repeated or wrong-typed key ("parameters.age is string,
///   not a number");
/// - InvalidInput `<source>: material "<name>": parameters.relax_radius -1 is outside (0, 100] m`
///   (every out-of-range value, "; "-separated) for a well-formed file with bad values.
FractureMaterial material_from_json(const std::string& text, const std::string& source);

/// Atomic write (base/atomic_file.hpp) / read of a material file; errors as above, naming the file.
/// save_material() writes only what load_material() reads back: a material with an invalid fit
/// record gets the reader's error and leaves the file as it was.
void save_material(const std::filesystem::path& path, const FractureMaterial& material);
FractureMaterial load_material(const std::filesystem::path& path);

/// Where bundled materials are looked up, in order, keeping only directories that exist:
/// 1. <prefix>/share/fissure/materials, <prefix> being the directory above the running
///    executable's bin/ (or libexec/fissure/) directory: an installed Fissure;
/// 2. the source tree's assets/materials (its path is compiled in): a build tree;
/// 3. the user library, $XDG_DATA_HOME/fissure/materials (default ~/.local/share/fissure/materials),
///    last, so a bundled name always means the bundled file.
std::vector<std::filesystem::path> material_directories();

/// The names of the bundled materials (file stems of *.json in material_directories(), first
/// directory first, each name once, sorted within a directory).
std::vector<std::string> bundled_material_names();

/// Resolves a --material argument: text containing '/' or ending in ".json" is a path, returned
/// as is (load_material reports a missing file); any other text is a bundled material's name,
/// the first <dir>/<name>.json over material_directories(). Throws InvalidInput
/// `material "<name>" is not a file or a bundled material (bundled: a, b, …)` otherwise.
std::filesystem::path find_material(const std::string& name_or_path);

}  // namespace fissure
