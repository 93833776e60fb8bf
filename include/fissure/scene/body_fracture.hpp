#pragma once
/// One scene body fractured with a fracture material (issue 13): what `fissure scene fracture`
/// does to every assigned body, and the studio to a selected one.
///
/// The steps, in order, each a library call the CLI's `fissure fracture` makes too:
///  1. a fitted material with a posterior draws the five fitted parameters from it with the
///     body's seed ("similar, not identical", material_fit.hpp);
///  2. a fitted material's lengths follow the body's visible face (fitted_transfer.hpp);
///  3. the body is tetrahedralised (through `mesher`, so a test can count who reaches it) and
///     prepared with its supports (default: rests on its lowest face along up);
///  4. the load: the ones given, else a fitted material's rule drawn as the fit draws it (a patch
///     at a drawn cell of the grid over the body's top, with the force that keeps the fit's
///     stress), else the default patch of l·m·g at a point of the top drawn with the body's
///     seed (drawn_load(), fracture_scenario.hpp), so no two bodies are struck alike;
///  5. the resistance field and Algorithm 1 with the body's seed, to the given age or the
///     material's; then the fragments as closed meshes.
/// Deterministic: the same input and seed give the same fragments at any thread count.
#include "fissure/base/progress.hpp"
#include "fissure/fracture/crack_surface.hpp"
#include "fissure/fracture/fracture_result.hpp"
#include "fissure/fracture/fracture_scenario.hpp"
#include "fissure/fracture/fragment_mesh.hpp"
#include "fissure/fracture/material_file.hpp"
#include "fissure/mesh/surface_mesh.hpp"
#include "fissure/mesh/tet_mesh.hpp"
#include "fissure/mesh/tetrahedralize.hpp"

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace fissure {

/// Makes the tet mesh of a closed surface: tetrahedralize() unless a caller (a test, a cache)
/// puts another in.
using Mesher = std::function<TetMesh(const SurfaceMesh&, const TetrahedralizeOptions&)>;

/// A patch load as an artist places it (a click on the body): the boundary faces within `radius`
/// of `position` that face along `normal`, pushed into the body along −normal with `magnitude`
/// newtons. On the mesh, the radius is widened to two element sizes when it is smaller, so the
/// patch always holds faces (patch_load(), fracture_scenario.hpp).
struct PatchLoad {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< world coordinates, m
  Eigen::Vector3d normal = Eigen::Vector3d::UnitY();   ///< unit
  double magnitude = 0.0;                              ///< N, > 0
  double radius = 0.0;                                 ///< m, > 0
};

struct BodyFractureRequest {
  SurfaceMesh surface;                 ///< closed, world coordinates, m
  FractureMaterial material;
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();  ///< unit; the visible face looks along it
  std::vector<LoadSpec> loads;         ///< world coordinates; these and patch_loads empty: the material's rule
  std::vector<PatchLoad> patch_loads;  ///< world coordinates, added to `loads` once the body is meshed
  std::vector<SupportSpec> supports;   ///< empty: rests on its lowest face
  bool free_body = false;
  std::uint64_t seed = 1;
  std::optional<double> age;           ///< unset: the material's
  int target_tets = 0;                 ///< 0: a fitted material's fit body count, else 6000
  /// A mesh whose estimated memory exceeds this is refused (TetrahedralizeOptions); 0: this
  /// machine's physical memory.
  std::uint64_t memory_limit_bytes = 0;
  /// Keep the tet mesh in BodyFracture::mesh (the studio's age slider re-meshes fragments from
  /// it); off, a run over thousands of bodies holds only their fragments.
  bool keep_mesh = false;
};

/// Where a body's static stress fields are cached (static_stress_cache.hpp, beside the tet meshes);
/// an empty directory caches nothing.
struct BodyFieldCache {
  std::filesystem::path directory;
  std::uint64_t max_bytes = 0;
};

struct BodyFracture {
  FractureParams params;               ///< as simulated (drawn, scaled, age set)
  int tets = 0;
  int tets_asked = 0;                  ///< the request's target_tets, or the default it stood for
  std::vector<LoadSpec> loads;         ///< as applied, with their forces
  double length_scale = 1.0;           ///< a fitted material's (fitted_transfer.hpp); 1 otherwise
  bool posterior_draw = false;         ///< the five fitted parameters were drawn from a posterior
  FractureResult result;
  std::vector<FragmentMesh> fragments; ///< world coordinates
  /// With BodyFractureRequest::keep_mesh, the tet mesh it was fractured on (world coordinates):
  /// mesh_fragments(*mesh, result.cracks, result.crack_count_at(age)) gives its fragments at an
  /// earlier age without re-simulating (the studio's age slider). Null otherwise.
  std::shared_ptr<const TetMesh> mesh;
  bool stress_cached = false;          ///< every static field came from the cache: no FEM was built
  std::string cache_warning;           ///< why a solved field could not be cached (the run goes on)
  std::string overload;                ///< overload_note() of its loads, when they shatter it at once
  struct Seconds {
    double meshing = 0.0, preparation = 0.0, simulation = 0.0, fragments = 0.0;
  } seconds;
};

/// The tet count a body is meshed with when the request gives none.
constexpr int kDefaultBodyTets = 6000;

/// Fractures `request.surface`. Throws InvalidInput naming the problem (a body with no face to
/// rest on, a load that touches nothing, parameters out of range after the draw), NumericalFailure
/// from the mesher, Cancelled through `cancel`.
BodyFracture fracture_body_surface(const BodyFractureRequest& request, int threads = 1, const Mesher& mesher = {},
                                   const CancelToken* cancel = nullptr, const BodyFieldCache& field_cache = {});

}  // namespace fissure
