#pragma once
/// A scene project (issue 13): everything a scene fracture run needs, in one versioned JSON file,
/// so the result regenerates from it byte for byte, and the studio saves and opens the same file.
///
///   {
///     "fissure_project": 1,
///     "scene": "street.glb",                  // relative to the project's folder, or absolute
///     "seed": 7, "age": 12, "up": "+y", "tets": 0, "unit": 1,
///     "slice": [2, 4], "strict": true,         // --bodies 2/4, --strict
///     "assign": {"materials": {"concrete": "concrete"}, "nodes": {"/street/curb": "granite.json"}},
///     "bodies": {
///       "/street/sidewalk/slab_03": {
///         "loads": [{"position": [1.2, 0.15, 0.3], "normal": [0, 1, 0], "magnitude": 800, "radius": 0.05}],
///         "supports": ["box:0,0,0,2,0.01,1@y"]   // or "free": true
///       },
///       "/street/curb": {"up": "+z"}             // the way its visible face looks: struck there
///     },
///     "export": {"output": "street-broken.glb", "report": "report.json"}
///   }
///
/// A load is a patch in world coordinates (body_fracture.hpp's PatchLoad: the boundary faces
/// within `radius` of `position` facing along `normal`, pushed into the body with `magnitude`
/// newtons; `fissure scene info --json` gives each body's bounds to place it). Supports use `fissure fracture --fix`'s selections (fem/supports.hpp),
/// in world coordinates. A body with no loads gets its material's rule; with no supports it
/// rests on its lowest face along its up: its own "up", else the way its visible face looks
/// (body_facing.hpp: a standing plate, such as a wall tile, faces the scene's centre; anything
/// else, the scene's up). Unset "age", "up", "tets", "unit": each material's, the
/// format's, the default, 1 (metres; loads and supports are in the scene's units). Unknown and repeated keys are refused (a typo must not pass as a default).
#include "fissure/scene/scene_fracture.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace fissure {

constexpr int kSceneProjectVersion = 1;

struct SceneBodySetupEntry {
  std::vector<PatchLoad> loads;
  std::vector<std::string> supports;   ///< `--fix` selections
  bool free_body = false;
  std::optional<std::string> up;       ///< "+z", …: the way its visible face looks (body_facing.hpp)
};

struct SceneProject {
  std::string scene;                   ///< as written in the file
  std::uint64_t seed = 1;
  std::optional<double> age;
  std::optional<std::string> up;       ///< "+y", "-z", …
  int tets = 0;
  double unit = 1.0;                   ///< metres per scene unit (SceneFractureOptions::unit)
  int slice = 1, slices = 1;           ///< --bodies K/N (SceneFractureOptions::slice, slices)
  bool strict = false;                 ///< --strict: a skipped body or an unmatched assignment fails the run
  SceneAssignments assignments;
  std::map<std::string, SceneBodySetupEntry> bodies;  ///< by body path
  std::string output;                  ///< export: the scene with its fragments, as written
  std::string report;                  ///< export: the per-body report, as written (empty: none)
  std::string crack_masks;             ///< export: the folder of crack textures (crack_texture.hpp; empty: none)
  int crack_mask_size = 0;             ///< export: their side in pixels (0: CrackTextureOptions' default)
};

/// Reads a project file. Throws IoError naming the file for a missing, unreadable or malformed
/// file ("project.json: not a valid Fissure project: bodies./a.loads[0].radius is -1, not
/// positive"), one from a newer Fissure, and when the scene it names is not there
/// ("project.json: its scene street.glb is not at /work/street.glb: was it moved? Put the scene
/// back or edit \"scene\" in project.json").
SceneProject read_scene_project(const std::filesystem::path& file);

/// The project as its file's text (keys in the order above), and written atomically.
std::string scene_project_to_json(const SceneProject& project);
void write_scene_project(const std::filesystem::path& file, const SceneProject& project);

/// A path the project gives (scene, output, report): absolute as written, else relative to the
/// project's folder.
std::filesystem::path project_path(const std::filesystem::path& project_file, const std::string& written);

/// True when `file` is to be read as a project: its name ends in .json.
bool is_scene_project_file(const std::filesystem::path& file);

/// The options a project gives to fracture_scene() (assignments, seed, age, up, tets, slice, and
/// each body's loads and supports); threads and the cache are the caller's. Throws
/// InvalidInput naming the project, body and entry for a support or up axis that does not parse.
SceneFractureOptions scene_fracture_options(const SceneProject& project, const std::string& source);

}  // namespace fissure
