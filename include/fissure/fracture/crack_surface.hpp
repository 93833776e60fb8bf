#pragma once
/// A crack as the simulation leaves it: the zero set of a noisy implicit plane S_k (paper §5.2–5.3,
/// [GMD12]) restricted to the set E_c of tets it has flooded. Inside a tet the crack is the zero
/// set of the linear (P1) interpolant of S_k's values at the tet's four nodes, so it is a plane
/// there: its polygon has its vertices on the tet's edges, neighbouring tets share those vertices
/// (the surface is watertight across faces), and later stages can clip tets by it exactly.
#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <vector>

namespace fissure {

/// The part of one crack inside one tet.
struct CrackCut {
  int tet = -1;
  /// S_k at the tet's four nodes (TetMesh::tets() order), never 0: values within 1e-6·h of zero
  /// are snapped away from it so no node lies on a crack. The crack is where the P1
  /// interpolant of these values vanishes.
  std::array<double, 4> node_values{};
  /// −1, or the earlier crack this one stopped on in this tet (a T-junction): here the crack
  /// exists only on the side of that crack's surface where it arrived, `clip_side` (±1) being
  /// the sign of the earlier crack's node interpolant on that side.
  int clipped_by = -1;
  int clip_side = 0;
};

struct CrackSurface {
  int id = -1;                    ///< index in FractureResult::cracks, in order of opening
  double time = 0.0;              ///< when it opened (age units)
  /// The element whose stress exceeded its resistance, where the crack's flood starts (cuts[0]);
  /// for a star crack, the tet around its kink it floods from, beside that element; for a star's
  /// third arm, the first tet along it.
  int origin_tet = -1;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  ///< centroid of origin_tet, m
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX(); ///< unit max principal direction there
  double opening_stress = 0.0;    ///< λ_max at the origin when it opened, Pa
  std::uint64_t noise_seed = 0;   ///< offsets of this crack's noise (see CrackNoise)
  std::vector<CrackCut> cuts;     ///< E_c, in the order the flood reached them; cuts[0] is the origin
  std::vector<int> stopped_on;    ///< earlier cracks it met and ended on (sorted, unique)
  double area = 0.0;              ///< area of its polygons, m²
  int branch_of = -1;             ///< the star crack whose kink it leaves (a star's third arm), or -1
};

/// The crack polygon inside one tet: the zero set of the P1 interpolant (3 or 4 vertices, in a
/// consistent cyclic order), clipped to the arrival side of `cut.clipped_by` when the caller
/// passes that crack's cut of the same tet. Vertices on edge (a, b) are a + t(b − a) with
/// t = S_a / (S_a − S_b). Empty when the values do not change sign.
std::vector<Eigen::Vector3d> crack_polygon(const Eigen::Matrix<double, 4, 3>& tet_nodes, const CrackCut& cut,
                                           const CrackCut* clipping_cut = nullptr);

}  // namespace fissure
