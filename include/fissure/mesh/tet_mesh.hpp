#pragma once
/// The volume mesh every simulation runs on: linear tetrahedra with face adjacency, boundary
/// faces, volumes, connected components, named node/face sets and a quality report.

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace fissure {

/// A named group of mesh entities, e.g. a gmsh physical group. `dimension` is the group's
/// dimension in gmsh terms (0 points, 1 curves, 2 surfaces, 3 volumes). Faces are node triples
/// (for dimension-2 groups); nodes are every node of the group.
struct NamedSet {
  std::string name;
  int dimension = 2;
  std::vector<int> nodes;
  std::vector<std::array<int, 3>> faces;
  std::vector<int> tets;
};

/// One triangle on the boundary of the mesh, oriented outward.
struct BoundaryFace {
  int tet = -1;        ///< the tet that owns the face
  int local_face = 0;  ///< 0–3: the face opposite the tet's local node `local_face`
  std::array<int, 3> nodes{};
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  ///< outward unit normal
  double area = 0.0;                                 ///< m²
};

/// The numbers a user's tools show for nodes and tets (gmsh's node and element tags, 1-based),
/// used in every message that names one. Empty: node v is tag v + 1, tet t is tag t + 1, which
/// is what Fissure's own .msh files write.
struct EntityTags {
  std::vector<std::int64_t> nodes;
  std::vector<std::int64_t> tets;
};

/// Compressed rows: the items of row r are items[offsets[r] .. offsets[r + 1]).
struct Incidence {
  std::vector<int> offsets;
  std::vector<int> items;
  int size(int row) const { return offsets[static_cast<std::size_t>(row) + 1] - offsets[static_cast<std::size_t>(row)]; }
  const int* begin(int row) const { return items.data() + offsets[static_cast<std::size_t>(row)]; }
  const int* end(int row) const { return items.data() + offsets[static_cast<std::size_t>(row) + 1]; }
};

/// Shape measures over all tets. Angles in degrees. radius_ratio = 3·inradius / circumradius
/// (1 for the regular tet, → 0 for slivers); radius_edge = circumradius / shortest edge (0.612 for
/// the regular tet, large for needles and caps, but NOT for slivers, hence both).
struct QualityReport {
  double min_dihedral_deg = 0.0;
  double max_dihedral_deg = 0.0;
  double min_radius_ratio = 0.0;
  double max_radius_edge = 0.0;
  double min_volume = 0.0;
  double max_volume = 0.0;
  int worst_dihedral_tet = -1;
  int worst_radius_ratio_tet = -1;
  /// Tets whose smallest dihedral angle is below `sliver_threshold_deg` of quality().
  int sliver_count = 0;
};

/// Linear tetrahedral mesh. Nodes in metres. Every tet is positively oriented:
/// det[x1−x0, x2−x0, x3−x0] > 0. Local face f is the face opposite local node f, with outward
/// winding (kLocalFaces). Immutable after construction; derived data is computed once there.
class TetMesh {
public:
  /// Outward-wound local faces: face f is opposite local node f.
  static constexpr std::array<std::array<int, 3>, 4> kLocalFaces{
      {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}}};

  TetMesh() = default;

  /// Validates and indexes the mesh. `source_name` (file or spec) prefixes error messages, which
  /// name nodes and tets by `tags` (see EntityTags). Throws InvalidInput naming the culprit for:
  /// non-finite coordinates; node indices out of range or repeated within a tet; a node used by
  /// no tet; an inverted tet or one whose volume is zero to round-off (|V| ≤ 1e-12·ℓ³, ℓ its
  /// longest edge); a face shared by more than two tets; tags of the wrong count.
  /// O(#tets log #tets).
  TetMesh(Eigen::MatrixX3d nodes, Eigen::MatrixX4i tets, std::string source_name = {},
          std::vector<NamedSet> named_sets = {}, EntityTags tags = {});

  const Eigen::MatrixX3d& nodes() const { return m_nodes; }
  const Eigen::MatrixX4i& tets() const { return m_tets; }
  int node_count() const { return static_cast<int>(m_nodes.rows()); }
  int tet_count() const { return static_cast<int>(m_tets.rows()); }
  const std::string& source_name() const { return m_source_name; }

  /// The tag users see for node `v` / tet `t` (1-based unless the file said otherwise), and
  /// "node 12" / "tet 97" phrases built from them for messages.
  std::int64_t node_tag(int v) const;
  std::int64_t tet_tag(int t) const;
  std::string node_label(int v) const;
  std::string tet_label(int t) const;
  const EntityTags& tags() const { return m_tags; }

  /// Volume of every tet, m³ (positive).
  const Eigen::VectorXd& volumes() const { return m_volumes; }
  double total_volume() const { return m_total_volume; }
  /// Centroid of every tet (row t), m.
  const Eigen::MatrixX3d& centroids() const { return m_centroids; }
  Eigen::Vector3d centroid(int tet) const { return m_centroids.row(tet).transpose(); }
  /// Axis-aligned bounds of the nodes: row 0 the minimum corner, row 1 the maximum.
  Eigen::Matrix<double, 2, 3> bounding_box() const;

  /// neighbours()(t, f) is the tet across local face f of tet t, or −1 on the boundary.
  const Eigen::MatrixX4i& neighbours() const { return m_neighbours; }
  /// neighbour_faces()(t, f) is the local face of neighbours()(t, f) that is the same triangle
  /// (−1 on the boundary): crossing face f of t arrives through that face of the neighbour.
  const Eigen::MatrixX4i& neighbour_faces() const { return m_neighbour_faces; }
  /// Global face ids: face_ids()(t, f) in [0, face_count()); the two tets sharing a triangle give
  /// it the same id. Numbered in order of the sorted node triples, so deterministic.
  const Eigen::MatrixX4i& face_ids() const { return m_face_ids; }
  int face_count() const { return m_face_count; }
  /// Tets around each node (row v: the tets that use node v, ascending).
  const Incidence& node_tets() const { return m_node_tets; }
  /// Every boundary triangle, outward-wound, sorted by (tet, local face).
  const std::vector<BoundaryFace>& boundary_faces() const { return m_boundary_faces; }
  /// The boundary as a surface (same node indices; unused nodes are simply not referenced).
  Eigen::MatrixX3i boundary_triangles() const;

  /// Components of the face-adjacency graph: component_of_tet()[t] in [0, component_count()).
  /// Numbered in order of their lowest tet index, so the numbering is deterministic.
  int component_count() const { return m_component_count; }
  const std::vector<int>& component_of_tet() const { return m_component_of_tet; }
  /// Component of each node (a node's tets all lie in one component unless two components touch
  /// at that node only; the lowest component wins then).
  std::vector<int> component_of_node() const;

  const std::vector<NamedSet>& named_sets() const { return m_named_sets; }
  /// The set called `name`, or nullptr.
  const NamedSet* find_named_set(const std::string& name) const;

  /// Shape report; tets with min dihedral below `sliver_threshold_deg` are counted as slivers.
  /// O(#tets).
  QualityReport quality(double sliver_threshold_deg = 5.0) const;

private:
  void validate_and_index();

  Eigen::MatrixX3d m_nodes;
  Eigen::MatrixX4i m_tets;
  std::string m_source_name;
  std::vector<NamedSet> m_named_sets;
  EntityTags m_tags;
  Eigen::VectorXd m_volumes;
  double m_total_volume = 0.0;
  Eigen::MatrixX3d m_centroids;
  Eigen::MatrixX4i m_neighbours;
  Eigen::MatrixX4i m_neighbour_faces;
  Eigen::MatrixX4i m_face_ids;
  int m_face_count = 0;
  Incidence m_node_tets;
  std::vector<BoundaryFace> m_boundary_faces;
  std::vector<int> m_component_of_tet;
  int m_component_count = 0;
};

/// Per-tet shape measures used by quality(), exposed for tests and for the validator of imports.
struct TetShape {
  double volume = 0.0;
  double min_dihedral_deg = 0.0;
  double max_dihedral_deg = 0.0;
  double radius_ratio = 0.0;
  double radius_edge = 0.0;
};
TetShape tet_shape(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                   const Eigen::Vector3d& d);

}  // namespace fissure
