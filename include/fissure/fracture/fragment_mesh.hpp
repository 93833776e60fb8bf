#pragma once
/// The fragments of a cracked tet mesh as closed surfaces (paper §8: fragments "can be moved or
/// removed independently"; docs/fragments.md). Each tet is cut into convex pieces by its cracks'
/// planes; pieces of face-adjacent tets join where their footprints on the shared face overlap
/// with positive area, so a crack that ends inside the body (partial) does not separate. A
/// fragment's surface is its pieces' faces on the body's boundary and on cracks between it and
/// other fragments; faces of partial cracks are dropped (they separate nothing and would leave
/// zero-thickness slits inside a mesh that engines treat as solid). A fragment less than 3e-6 of
/// the body's size (or of its distance from the origin) across — debris where cracks meet within
/// round-off — joins the neighbour it shares the most crack area with: float32 files cannot hold it.
#include "fissure/fracture/crack_surface.hpp"
#include "fissure/mesh/tet_mesh.hpp"

#include <Eigen/Core>

#include <vector>

namespace fissure {

/// Where two fragments touch across cracks: engines use these as a support graph.
struct FragmentContact {
  int fragment = -1;  ///< the other fragment's index
  double area = 0.0;  ///< m², of the crack faces between them
};

/// One fragment's closed, outward-wound, 2-manifold surface.
struct FragmentMesh {
  Eigen::MatrixX3d vertices;
  Eigen::MatrixX3i triangles;        ///< counter-clockwise seen from outside
  std::vector<int> triangle_crack;   ///< per triangle: the crack it lies on, or -1 on the body's surface
  double volume = 0.0;               ///< m³, enclosed by the surface
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  ///< centre of volume, m
  int first_tet = -1;                ///< the lowest tet holding part of it (fragments are in its order)
  /// When it came loose: the earliest opening time of the cracks on its surface; −1 for a
  /// fragment no crack bounds (the body uncracked, or a part the cracks left whole).
  double crack_onset_time = -1.0;
  std::vector<FragmentContact> contacts;  ///< by ascending fragment index
  /// The vertices moved off the exact construction, for the float32 files readers merge by
  /// position; mostly none. Where the fragment's solid touches itself (two cracks cross in a tet
  /// and it holds opposite corners of the cross) each sheet has its own copy of the vertex, moved
  /// 4e-7 of the fragment's size into its own side; an edge shorter than 3e-7 of it is collapsed
  /// into one end. Each moved by at most `max_move`.
  std::vector<int> moved_vertices;
  double max_move = 0.0;  ///< m
};

/// The fragments of `mesh` cut by cracks[0 .. crack_count), in order of their lowest tet, on up to
/// `threads` threads (the same bytes at any count). Thread-safe.
std::vector<FragmentMesh> mesh_fragments(const TetMesh& mesh, const std::vector<CrackSurface>& cracks,
                                         int crack_count, int threads = 1);

}  // namespace fissure
