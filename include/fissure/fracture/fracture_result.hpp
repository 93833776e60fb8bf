#pragma once
/// What a fracture simulation returns: the cracks in order of opening, each with its time, so the
/// state at any age up to the simulated one is available without re-running (the studio's age
/// scrubber, paper Fig. 10), and per-tet fragment labels at that age.
#include "fissure/fracture/crack_surface.hpp"
#include "fissure/mesh/tet_mesh.hpp"

#include <vector>

namespace fissure {

/// Fragments of a tet mesh cut by cracks: two face-adjacent tets belong to one fragment unless a
/// crack that cuts either of them has their centroids on opposite sides of its surface. A cut tet
/// belongs to the side its centroid is on. A crack that ends inside the body (partial) does not
/// separate: the tets beyond its tip connect both sides.
struct FragmentLabels {
  std::vector<int> fragment_of_tet;  ///< in [0, count), numbered by lowest tet index
  int count = 0;
};

struct FractureResult {
  std::vector<CrackSurface> cracks;  ///< in order of opening (non-decreasing time)
  double simulated_age = 0.0;
  /// Cracks that separate nothing at the simulated age (every tet on both sides of them is one
  /// fragment), by index.
  std::vector<int> partial_cracks;
  FragmentLabels fragments;          ///< at the simulated age

  /// Number of cracks that had opened by `age` (cracks[0 .. n) ).
  int crack_count_at(double age) const;
};

/// Labels the fragments of `mesh` cut by cracks[0 .. crack_count). O(#tets + Σ cuts).
FragmentLabels label_fragments(const TetMesh& mesh, const std::vector<CrackSurface>& cracks, int crack_count);

}  // namespace fissure
