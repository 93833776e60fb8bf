#pragma once
// A tet cut by cracks, as convex pieces (issue 11, paper-gaps §5 step 1): the first stage of
// the closed fragment meshes.
//
// Inside a tet each crack is the zero set of the P1 interpolant of its node values, a plane, so
// the tet splits into convex polytopes. A crack that stopped on an earlier one in this tet (a T,
// CrackCut::clipped_by) exists only on its arrival side of that crack's plane: it splits only
// the part of the tet on that side. Each piece carries the labeller's key (fragment_labels.cpp):
// per cut, in the tet's crack order, 1 on the crack's positive side, 2 on its negative side, 0
// where the crack does not exist (beyond its clip), so a point's piece here and in the labeller
// agree.
//
// Where a clipping crack does not itself exist across a piece (a chain of clips in one tet), the
// piece is divided along the clipping crack's plane without a crack there: those faces are
// marked `open`, and the two pieces on either side of one are connected.
//
// Seams are exact: every vertex is kept as barycentric weights on the tet's nodes, and values
// and positions are summed over the nodes in a caller-given order (ascending global node id),
// so a point on a face two tets share gets the same bits in both.
#include "small_vector.hpp"

#include <Eigen/Core>

#include <array>
#include <span>
#include <string>
#include <vector>

namespace fissure::detail {

/// One crack's cut of the tet being split (a CrackCut without its tet).
struct TetCutPlane {
  int crack = -1;
  std::array<double, 4> node_values{};  ///< at the tet's local nodes; never 0
  int clipped_by = -1;                  ///< an earlier crack among the cuts, or -1
  int clip_side = 0;                    ///< ±1: the clipping crack's sign on the arrival side
};

/// Where a face of a piece lies.
enum class PieceFaceKind {
  TetFace,  ///< on local face `index` of the tet
  Crack,    ///< on the crack `index` (a crack id)
  Open,     ///< on the plane of crack `index` where that crack does not exist: no separation
};

struct PieceFace {
  PieceFaceKind kind = PieceFaceKind::TetFace;
  int index = -1;
  /// A planar convex polygon, counter-clockwise seen from outside the piece (a tet face cut by
  /// k planes has at most 3 + k corners: 8 in place covers all but rare faces).
  SmallVector<Eigen::Vector3d, 8> points;
  /// Each point's barycentric weights on the tet's local nodes (0 exactly off its face).
  SmallVector<Eigen::Vector4d, 8> weights;
};

struct TetPieceOptions {
  /// The order in which sums over the tet's local nodes run: ascending global node id, so that
  /// tets sharing a face compute its points alike.
  std::array<int, 4> node_order{0, 1, 2, 3};
  /// |value| at or below this is on a crack's plane, in the units of the node values; one value
  /// for every tet, so that neighbours classify a shared point alike. 0: 1e-12 of the largest
  /// |node value| of the tet (for a tet on its own).
  double on_plane = 0.0;
};

struct TetPiece {
  std::string key;  ///< the labeller's key (above)
  std::vector<PieceFace> faces;
};

/// The convex pieces of the tet with corner positions `nodes` (rows, local order) cut by `cuts`
/// (in crack order, as the labeller lists a tet's cuts). Faces smaller than 1e-20 of the tet's
/// size², and pieces left with fewer than four faces or no volume, are dropped. Without cuts: the tet itself, key "".
std::vector<TetPiece> tet_pieces(const Eigen::Matrix<double, 4, 3>& nodes, std::span<const TetCutPlane> cuts,
                                 const TetPieceOptions& options = {});

/// The volume of a closed piece (divergence theorem over its faces).
double piece_volume(const TetPiece& piece);

}  // namespace fissure::detail
