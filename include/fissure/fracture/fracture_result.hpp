#pragma once
/// What a fracture simulation returns: the cracks in order of opening, each with its time, so the
/// state at any age up to the simulated one is available without re-running (the studio's age
/// scrubber, paper Fig. 10), and per-tet fragment labels at that age.
#include "fissure/fracture/crack_surface.hpp"
#include "fissure/mesh/tet_mesh.hpp"

#include <vector>

namespace fissure {

/// Fragments of a tet mesh cut by cracks. A cut tet splits into pieces (its points with the same
/// side of every crack that cuts it; a crack clipped at a T-junction exists only on its arrival
/// side). Pieces of face-adjacent tets join where their footprints on the shared face overlap,
/// probed at seven points of the face (inset corners, inset edge midpoints, centre), so a piece
/// thinner than about a sixth of a face can be missed: the exact construction is the fragment
/// meshing's. A crack that ends inside the body (partial) does not separate: the pieces beyond
/// its tip connect both sides. A tet's label is that of the piece holding its centroid; a
/// fragment that holds no tet centroid (a sliver) is not counted.
struct FragmentLabels {
  std::vector<int> fragment_of_tet;  ///< in [0, count), numbered by lowest tet index
  int count = 0;
};

struct FractureResult {
  std::vector<CrackSurface> cracks;  ///< in order of opening (non-decreasing time)
  double simulated_age = 0.0;
  /// True when SimulationOptions::max_cracks stopped the run before `simulated_age` was reached;
  /// simulated_age is then the time of the last crack.
  bool crack_limit_reached = false;
  /// True when SimulationOptions::stop_check stopped the run (simulated_age: the last crack's).
  bool stopped_early = false;
  /// Cracks that separate nothing at the simulated age (every tet on both sides of them is one
  /// fragment), by index.
  std::vector<int> partial_cracks;
  FragmentLabels fragments;          ///< at the simulated age

  /// Number of cracks that had opened by `age` (cracks[0 .. n) ).
  int crack_count_at(double age) const;
};

/// Labels the fragments of `mesh` cut by cracks[0 .. crack_count). When `partial_cracks` is given,
/// it receives the cracks that separate no piece of a tet they cut from the piece on its other
/// side (the tip region joins them), ascending. O(#tets + Σ cuts).
FragmentLabels label_fragments(const TetMesh& mesh, const std::vector<CrackSurface>& cracks, int crack_count,
                               std::vector<int>* partial_cracks = nullptr);

}  // namespace fissure
