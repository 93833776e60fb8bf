#pragma once
// The path of a turning crack along the body's surface (docs/fracture.md, "Crack paths").
//
// The paper's crack is one noisy plane: it keeps the normal of the element that opened it however
// far it runs, so cracks cross the stress field, and each other, at any angle (a tile's cracks
// met at 60° on average; traced tiles, glazes and mud meet near 90°). A crack that turns toward
// the local principal direction as it runs is a curved surface instead. Growing that surface
// element by element from the flood (valuing each new node from the plane of the tet it was
// reached from) folded it: two paths of one crack reaching a node with different headings gave
// it values that disagree, and the surface broke into element-sized loops. Here the crack's
// course is traced first, once, as a polyline along the surface through its origin, and the crack
// is the zero set of one function of position built from it, so every node has one value
// whatever the order the flood reaches it in, and the surface is one watertight level set:
//
//   D(x) = N(s)·(x − P(s)), P(s) the point of the polyline nearest x, N(s) the crack normal there
//
// (distances measured along the surface, i.e. with the component along the path's surface normal
// removed, so a tile's crack is the same through its thickness). The simulation adds the noise
// octaves to D as it adds them to the paper's plane.
#include "fissure/mesh/tet_mesh.hpp"

#include <Eigen/Core>

#include <functional>
#include <vector>

namespace fissure::detail {

/// The tet holding x, walking from `start` across faces toward it; -1 when the walk leaves the
/// body. For points an element or two from `start`.
int locate_tet(const TetMesh& mesh, int start, const Eigen::Vector3d& x);

class CrackPath {
public:
  /// The new crack normal after a step of `length` from tet `from` into `tet` with normal
  /// `normal`, turning about the surface normal `up`.
  using Turn = std::function<Eigen::Vector3d(int from, int tet, const Eigen::Vector3d& normal,
                                             const Eigen::Vector3d& up, double length)>;

  struct Options {
    double step = 0.0;        ///< m between path points
    double max_length = 0.0;  ///< m, per arm
    /// m: the tightest bend. D jumps where the nearest point of the path switches across a bend
    /// (its medial axis, a bend radius away on the inner side); with bends of an element's radius
    /// that jump fell inside the tets the flood visits and the crack ran along it in element-sized
    /// zigzags. A few elements keeps it outside.
    double min_radius = 0.0;
    /// Whether the path may end after entering `tet` (an earlier crack cuts it: the flood ends
    /// there in a T). The arm goes on a few steps more, for a flood that reaches around the end
    /// of a crack that stops inside the body, then stops: most paths end an arm's length from
    /// their origin, not across the body. Optional.
    std::function<bool(int tet)> ends_at;
  };

  /// Traces both arms from `origin` (inside `origin_tet`) with crack normal `normal`, each arm
  /// until it leaves the body or reaches options.max_length. `surface_normals` holds each tet's
  /// nearest surface normal (FractureBody); the arms run across them.
  CrackPath(const TetMesh& mesh, const Eigen::MatrixX3d& surface_normals, int origin_tet, const Eigen::Vector3d& origin,
            const Eigen::Vector3d& normal, const Options& options, const Turn& turn)
      : CrackPath(mesh, surface_normals, origin_tet, origin, normal, normal, options, turn) {}

  /// A path with a kink at `origin`: the minus arm leaves with crack normal `normal_minus`, the
  /// plus arm with `normal_plus` (each arm runs along the surface across its normal; both normals
  /// on the same side of the path, i.e. up × (direction of travel from the minus end to the plus
  /// end)). Two arms of a three-armed star crack (docs/fracture.md, "Star cracks").
  CrackPath(const TetMesh& mesh, const Eigen::MatrixX3d& surface_normals, int origin_tet, const Eigen::Vector3d& origin,
            const Eigen::Vector3d& normal_minus, const Eigen::Vector3d& normal_plus, const Options& options,
            const Turn& turn);

  /// D(x) above. Beyond either end of the path the end segment goes on as a straight ray.
  double operator()(const Eigen::Vector3d& x) const;

  /// The path's vertices, from one end to the other (for tests and diagnostics).
  const std::vector<Eigen::Vector3d>& points() const { return m_points; }

private:
  void trace_arm(const TetMesh& mesh, const Eigen::MatrixX3d& surface_normals, int origin_tet, double sign,
                 const Options& options, const Turn& turn, std::vector<Eigen::Vector3d>& points,
                 std::vector<Eigen::Vector3d>& normals, std::vector<Eigen::Vector3d>& up) const;

  std::vector<Eigen::Vector3d> m_points;   // P_i
  std::vector<Eigen::Vector3d> m_normals;  // N_i, unit
  std::vector<Eigen::Vector3d> m_up;       // the surface normal at P_i, unit
  std::vector<Eigen::Vector3d> m_along;    // segment i, P_i → P_i+1, along the surface (up_i+1 removed)
  std::vector<double> m_along_length2;     // |m_along[i]|²
};

}  // namespace fissure::detail
