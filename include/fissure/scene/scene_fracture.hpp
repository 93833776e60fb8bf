#pragma once
/// "Fracture all bodies of this material" over a whole scene (issue 13), and the scene written
/// back with the fragments in it. Qt-free: `fissure scene fracture` and the studio call it.
///
/// - Assignments: a fracture material (a file path, or a name looked up by find_material():
///   the bundled library, then the user library) per scene material name, and per node path,
///   which overrides and covers the node's descendants (the nearest assigned ancestor wins).
///   Every assigned material is loaded before any body is touched: one that does not load
///   fails the run (naming the assignment), not each of its bodies. A body with no assignment
///   is never checked, tetrahedralised or analysed: it costs nothing (the `mesher` hook lets a
///   test prove it).
/// - Each assigned body gets its own seed, body_seed(project seed, body path), and with it its
///   own resistance field, noise, load position and, for a material with a posterior, its own
///   parameter draw: bodies sharing a material break "similar, not identical". The result does
///   not depend on the thread count or on which other bodies are assigned.
/// - A body that cannot be fractured (open, self-intersecting, no face to rest on) is skipped
///   with its reason; the others go on.
/// - Slices: slice K of N fractures the assigned bodies whose ordinal among the assigned ones is
///   K − 1 modulo N, leaving the rest as they are (a job array's share).
#include "fissure/io/scene_export.hpp"
#include "fissure/io/scene_import.hpp"
#include "fissure/scene/body_fracture.hpp"

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace fissure {

struct SceneAssignments {
  std::map<std::string, std::string> by_material;  ///< scene material name → fracture material
  std::map<std::string, std::string> by_path;      ///< node path → fracture material (and its subtree)
};

/// How one body is struck and held, in world coordinates (fracture_scenario.hpp's meaning):
/// no loads, its material's rule; no supports and not free, it rests on its lowest face along
/// its up: `up` when given, else the way its visible face looks (body_facing.hpp).
struct SceneBodySetup {
  std::vector<PatchLoad> loads;
  std::vector<SupportSpec> supports;
  bool free_body = false;
  std::optional<Eigen::Vector3d> up;      ///< a coordinate axis
};

struct SceneFractureOptions {
  SceneAssignments assignments;
  /// Fail (InvalidInput) before any body is meshed when an assignment or setup matches nothing or
  /// an assigned body of the slice is not fracturable, instead of warning and skipping it. A body
  /// that fails later (its mesher refuses it) is still a skip: the caller's --strict sees it.
  bool strict = false;
  /// By body path. A setup for a path that is no body is a warning, like an assignment.
  std::map<std::string, SceneBodySetup> body_setups;
  std::uint64_t seed = 1;                 ///< the project seed
  std::optional<double> age;              ///< unset: each material's
  std::optional<Eigen::Vector3d> up;      ///< unset: the scene's (its format's convention)
  /// Metres per scene unit (0.01 for a scene modelled in centimetres): bodies are fractured at
  /// their size in metres and written back in the scene's units. 1: the format's convention
  /// (metres for glTF; assimp converts FBX). Loads and supports are given in scene units.
  double unit = 1.0;
  int target_tets = 0;                    ///< per body; 0: BodyFractureRequest's default
  std::uint64_t memory_limit_bytes = 0;   ///< per body's mesh (BodyFractureRequest)
  int threads = 1;                        ///< bodies run in parallel, one thread each
  bool keep_meshes = false;               ///< BodyFractureRequest::keep_mesh for every body
  int slice = 1, slices = 1;              ///< K of N, K from 1
  Mesher mesher;                          ///< empty: tetrahedralize(), through the cache below
  /// Tet meshes and static stress fields are cached here by content (tet_mesh_cache.hpp,
  /// static_stress_cache.hpp), so a second run, or a run after an edit to other bodies, meshes
  /// and solves nothing it has done before. Empty: no cache.
  std::filesystem::path cache_dir;
  std::uint64_t cache_max_bytes = 0;      ///< the cache's cap; 0: default_cache_size_limit()
  const CancelToken* cancel = nullptr;
  /// Called after each assigned body of the slice finishes (from worker threads, one at a time):
  /// bodies done, bodies to do, the body's path.
  std::function<void(int, int, const std::string&)> on_body_done;
};

struct SceneBodyReport {
  enum class Status { Fractured, Skipped, Unassigned, OtherSlice };
  std::string path;
  Status status = Status::Unassigned;
  std::string reason;                     ///< why skipped
  std::vector<std::string> repairs;       ///< what the check repaired
  std::string material;                   ///< the assignment as given, and the material's name
  std::string material_name;
  std::uint64_t seed = 0;
  int fragments = 0;                      ///< closed meshes
  int tets = 0;
  bool mesh_cached = false;               ///< its tet mesh came from the cache
  bool stress_cached = false;             ///< its static stress came from the cache: no FEM built
  std::vector<std::string> loads;         ///< the loads as applied, as `--load` specs (forces in N)
  Eigen::Vector3d up = Eigen::Vector3d::Zero();  ///< the up it was fractured along (body_facing.hpp)
  BodyFracture::Seconds seconds;
};

/// "fractured", "skipped", "unassigned", "other slice".
const char* status_name(SceneBodyReport::Status status);

/// A fractured body: its fragments, and its surface's look for their outer faces.
struct FracturedSceneBody {
  BodyFracture fracture;
  SurfaceAppearance appearance;           ///< world coordinates (scene_body_check.hpp)
  std::vector<int> scene_materials;       ///< per appearance material, the scene's index (-1: none)
};

struct SceneFracture {
  std::vector<SceneBody> bodies;          ///< scene_bodies() of the scene
  std::vector<SceneBodyReport> reports;   ///< one per body
  std::vector<std::optional<FracturedSceneBody>> results;  ///< one per body, set when fractured
  /// Assignments that match nothing in the scene ("--assign tiles=…: the scene has no material
  /// tiles (it has: a, b)"), and a cache that could not be written; the run goes on.
  std::vector<std::string> warnings;
  /// What the user asked for but did not get, in body order: a thin body meshed with far more
  /// tets than target_tets (the mesher keeps elements no larger than the body's thickness, or it
  /// leaves the body hollow), a body that came out whole. Not failures: --strict ignores them.
  std::vector<std::string> notes;
  int slice = 1, slices = 1;              ///< the slice run (SceneFractureOptions)
  double unit = 1.0;                      ///< metres per scene unit (SceneFractureOptions)
  /// The scene's up axis as the run took it (SceneFractureOptions::up, else the format's):
  /// scene_export() writes each format turned from it to the format's own.
  Eigen::Vector3d up = Eigen::Vector3d::UnitY();
  /// What identifies the run across its slices: a hash of the scene's content (nodes, meshes,
  /// materials) and of every option but the slice. scene_merge.hpp joins only slices that share it.
  std::string run;
};

/// The fracture material `body` is assigned, or null: its node's or its nearest assigned
/// ancestor's, else that of the first of its meshes' scene materials that has one.
const std::string* body_assignment(const ImportedScene& scene, const SceneBody& body, const SceneAssignments& assignments);

/// The body's own seed: a hash of (project seed, body path).
std::uint64_t body_seed(std::uint64_t project_seed, const std::string& path);

/// Fractures every assigned body of `scene` (of the slice). Throws InvalidInput for bad options
/// (a slice outside 1..N, an unknown material name), IoError for a material file that does not
/// load, Cancelled through options.cancel; a body's own failure is its report.
SceneFracture fracture_scene(const ImportedScene& scene, const SceneFractureOptions& options);

/// The scene as it was read, with each fractured body's mesh replaced by one child node per
/// fragment (fragment_NNN, in the body's node frame, the crack material added, the fragment's
/// extras: scene/fragment_export.hpp) and everything else kept: node names, hierarchy,
/// transforms, materials, colours and base-colour texture references (a texture embedded in the
/// input, and maps other than the base colour, are not carried). An untouched body is its node's
/// geometry, one primitive per material. The root node an importer adds above a glTF's scene
/// nodes is left out, so an export imports back as it was. Meshes shared by several nodes are
/// written once per node. Materials: the scene's, then `default` when a mesh has none, then the
/// crack material when any body is assigned (fractured or not, in this slice or another), so
/// every slice of a run has the same list. The scene's extras name the run and the slice
/// ({"fissure": {"slice": [K, N], "run": …}}), which `fissure scene merge` checks.
ExportScene scene_export(const ImportedScene& scene, const SceneFracture& fracture);

}  // namespace fissure
