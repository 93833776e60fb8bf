#pragma once
/// Tetrahedralisation of a closed surface with CGAL Mesh_3 (Delaunay refinement, sharp features
/// protected, then perturbation and exudation to remove slivers from the accepted refinement).

#include "fissure/base/progress.hpp"
#include "fissure/mesh/surface_mesh.hpp"
#include "fissure/mesh/tet_mesh.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace fissure {

struct TetrahedralizeOptions {
  /// Wanted number of tets. The result lands within ±`count_tolerance` of it: an attempt that
  /// misses is refined again with a corrected size bound (up to three attempts), and only the
  /// accepted one has its slivers removed.
  int target_tets = 24000;
  double count_tolerance = 0.25;
  /// Facets: minimum angle (degrees) of surface triangles. ≤ 30 guarantees termination. 20, not
  /// CGAL's usual 25: on a plate one or two tets thick, 25° leaves tets spanning the thickness
  /// with all four nodes on the faces that the perturber fights for seconds (docs/architecture.md).
  double facet_angle_deg = 20.0;
  /// Cells: circumradius / shortest edge bound; ≥ 2 guarantees termination. Removes every bad
  /// shape except slivers, which perturb and exude then attack.
  double cell_radius_edge_ratio = 3.0;
  /// Surface edges whose dihedral angle deviates from flat by more than this are protected as
  /// sharp features (box edges and corners stay exact).
  double feature_angle_deg = 60.0;
  /// Sliver removal: each pass stops at this min dihedral angle (degrees) or its time limit (s).
  double sliver_bound_deg = 12.0;
  double perturb_time_limit_s = 10.0;
  double exude_time_limit_s = 10.0;
  /// A result whose smallest dihedral angle is below this is refused (NumericalFailure): such a
  /// sliver makes K ill-conditioned and its stress unreliable (fem-pitfalls.md §2.4).
  double refuse_below_dihedral_deg = 1.0;
  /// Seed of CGAL's generator, reseeded before every call: same input → same mesh.
  unsigned seed = 0;
  /// Requests whose estimated peak memory (tetrahedralize_memory_estimate) exceeds this are
  /// refused before any work (InvalidInput). 0 = this machine's physical memory; UINT64_MAX = no
  /// limit.
  std::uint64_t memory_limit_bytes = 0;

  /// Readable problems, empty when valid.
  std::vector<std::string> problems() const;
  void validate() const;
};

/// What tetrahedralize() did, for the CLI and the studio to report.
struct TetrahedralizeReport {
  int attempts = 0;
  double cell_size = 0.0;    ///< final CGAL cell size bound, m
  QualityReport quality;
  std::vector<std::string> warnings;  ///< e.g. min dihedral below 5°
};

/// Estimated peak memory of tetrahedralize() for `target_tets` tets, bytes: 700 bytes per tet
/// (CGAL's triangulation, its refinement queues and the TetMesh; measured 630–650 with peak RSS
/// from 24K to 300K tets, see tetrahedralize.cpp) plus 100 MB, so 5M tets ≈ 3.6 GB and 50M ≈ 35 GB.
double tetrahedralize_memory_estimate(int target_tets);

/// Identifies what tetrahedralize() computes: Fissure's own algorithm version (bumped whenever a
/// change alters its output for some input) combined with CGAL's version. Caches of its meshes
/// (tet_mesh_cache.hpp) key on it, so a mesh made by other code is never reused.
std::int64_t tetrahedralize_version();

/// Tetrahedralises a closed, consistently oriented, manifold surface (see repair_surface). The
/// tets come out positively oriented, nodes in order of first use by the tets. Deterministic.
/// Every attempt is checked against the surface (boundary nodes on it, volume, boundary area,
/// bounding box); a mesh that does not fill it (a hollow plate) is re-made with a smaller size
/// bound, and refused after four such attempts or when that would need more than 10× the tets
/// asked for (+1e5). A size bound the body cannot hold (a 24000-tet request on a 0.01 m thick
/// 10 m plate) is refused up front with the count it needs.
/// Throws InvalidInput for an empty or open surface or a request beyond `memory_limit_bytes`;
/// NumericalFailure when CGAL produces no tets, a mesh that does not fill the surface (naming the
/// surface and the figures) or a mesh below `refuse_below_dihedral_deg`; Cancelled when `cancel`
/// is set: CGAL's refinement polls it (through Mesh_3's stop flag) and stops within
/// milliseconds; perturbation and exudation do not and end within their time limits.
/// Reports progress a few times per second during refinement. Cost: tenths of a second to a few
/// seconds from 7K to 54K tets (docs/BENCHMARKS.md, bench_mesh and bench_prepare_body). Runs on
/// the calling thread only.
TetMesh tetrahedralize(const SurfaceMesh& surface, const TetrahedralizeOptions& options,
                       TetrahedralizeReport* report = nullptr, ProgressSink* progress = nullptr,
                       const CancelToken* cancel = nullptr);

}  // namespace fissure
