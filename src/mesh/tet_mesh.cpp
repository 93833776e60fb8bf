#include "fissure/mesh/tet_mesh.hpp"

#include "fissure/base/error.hpp"
#include "fissure/base/number_text.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

namespace fissure {
namespace {

// |V| ≤ kZeroVolume·ℓ³ is "zero to round-off": double coordinates of size ℓ carry ~1e-16·ℓ of
// error, so a determinant of three edges is uncertain by ~1e-15·ℓ³; 1e-12 leaves a safety margin
// of 1000 while still accepting any sliver a mesher can produce on purpose (those are reported by
// quality(), not refused).
constexpr double kZeroVolume = 1e-12;

struct FaceRecord {
  std::array<int, 3> key;  // sorted node indices
  int tet;
  int local_face;
  bool operator<(const FaceRecord& o) const {
    // Field by field: std::array's operator< goes through memcmp, which was a third of the
    // construction time at 54K tets.
    if (key[0] != o.key[0]) return key[0] < o.key[0];
    if (key[1] != o.key[1]) return key[1] < o.key[1];
    if (key[2] != o.key[2]) return key[2] < o.key[2];
    return tet != o.tet ? tet < o.tet : local_face < o.local_face;
  }
};

std::string prefix(const std::string& source) { return source.empty() ? "" : source + ": "; }

}  // namespace

TetShape tet_shape(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                   const Eigen::Vector3d& d) {
  TetShape s;
  const Eigen::Vector3d p[4] = {a, b, c, d};
  const double det = (b - a).dot((c - a).cross(d - a));
  s.volume = det / 6.0;

  // Outward face normals (area-weighted), face f opposite vertex f.
  Eigen::Vector3d n[4];
  double area_sum = 0.0;
  for (int f = 0; f < 4; ++f) {
    const auto& lf = TetMesh::kLocalFaces[f];
    n[f] = 0.5 * (p[lf[1]] - p[lf[0]]).cross(p[lf[2]] - p[lf[0]]);
    area_sum += n[f].norm();
  }
  s.min_dihedral_deg = 180.0;
  s.max_dihedral_deg = 0.0;
  for (int i = 0; i < 4; ++i) {
    for (int j = i + 1; j < 4; ++j) {
      const double denom = n[i].norm() * n[j].norm();
      double cosine = denom > 0.0 ? n[i].dot(n[j]) / denom : 1.0;
      cosine = std::clamp(cosine, -1.0, 1.0);
      const double dihedral = 180.0 - std::acos(cosine) * 180.0 / std::numbers::pi;
      s.min_dihedral_deg = std::min(s.min_dihedral_deg, dihedral);
      s.max_dihedral_deg = std::max(s.max_dihedral_deg, dihedral);
    }
  }

  // Circumradius: R = |ℓa²(b×c) + ℓb²(c×a) + ℓc²(a×b)| / (2·det), edges from vertex 0.
  const Eigen::Vector3d e1 = b - a, e2 = c - a, e3 = d - a;
  const Eigen::Vector3d num =
      e1.squaredNorm() * e2.cross(e3) + e2.squaredNorm() * e3.cross(e1) + e3.squaredNorm() * e1.cross(e2);
  const double circumradius = det != 0.0 ? num.norm() / (2.0 * std::abs(det)) : INFINITY;
  const double inradius = area_sum > 0.0 ? 3.0 * std::abs(s.volume) / area_sum : 0.0;
  s.radius_ratio = std::isfinite(circumradius) && circumradius > 0.0 ? 3.0 * inradius / circumradius : 0.0;

  double shortest = INFINITY;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) shortest = std::min(shortest, (p[i] - p[j]).norm());
  s.radius_edge = shortest > 0.0 ? circumradius / shortest : INFINITY;
  return s;
}

TetMesh::TetMesh(Eigen::MatrixX3d nodes, Eigen::MatrixX4i tets, std::string source_name,
                 std::vector<NamedSet> named_sets, EntityTags tags)
    : m_nodes(std::move(nodes)),
      m_tets(std::move(tets)),
      m_source_name(std::move(source_name)),
      m_named_sets(std::move(named_sets)),
      m_tags(std::move(tags)) {
  validate_and_index();
}

std::int64_t TetMesh::node_tag(int v) const {
  return m_tags.nodes.empty() ? std::int64_t{v} + 1 : m_tags.nodes[static_cast<std::size_t>(v)];
}

std::int64_t TetMesh::tet_tag(int t) const {
  return m_tags.tets.empty() ? std::int64_t{t} + 1 : m_tags.tets[static_cast<std::size_t>(t)];
}

std::string TetMesh::node_label(int v) const { return "node " + std::to_string(node_tag(v)); }
std::string TetMesh::tet_label(int t) const { return "tet " + std::to_string(tet_tag(t)); }

namespace {

// True when the oriented triangles a and b (same three nodes) wind in opposite directions, as
// the two tets on either side of a face see it.
bool opposite_winding(const std::array<int, 3>& a, const std::array<int, 3>& b) {
  int k = 0;
  while (b[static_cast<std::size_t>(k)] != a[0]) ++k;
  // b rotated to start at a[0] must read (a[0], a[2], a[1]).
  return b[static_cast<std::size_t>((k + 1) % 3)] == a[2];
}

// Interior dihedral angle (radians) of tet (p0..p3) at its edge (i, j): the angle between the
// other two vertices seen along the edge. atan2 of |u×w| and u·w is accurate at 0 and π alike.
double dihedral_at_edge(const Eigen::Vector3d p[4], int i, int j) {
  int k = 0;
  while (k == i || k == j) ++k;
  const int l = 6 - i - j - k;
  // Unit vectors throughout (stableNormalized scales before squaring): a tet of size 1e-100 m
  // would otherwise underflow the cross product and read as a zero angle.
  const Eigen::Vector3d e = (p[j] - p[i]).stableNormalized();
  Eigen::Vector3d u = (p[k] - p[i]).stableNormalized(), w = (p[l] - p[i]).stableNormalized();
  u = (u - u.dot(e) * e).stableNormalized();
  w = (w - w.dot(e) * e).stableNormalized();
  return std::atan2(u.cross(w).norm(), u.dot(w));
}

}  // namespace

void TetMesh::validate_and_index() {
  const std::string where = prefix(m_source_name);
  const int n_nodes = node_count();
  const int n_tets = tet_count();
  if (n_tets == 0) throw InvalidInput(where + "mesh has no tetrahedra");
  if (!m_tags.nodes.empty() && m_tags.nodes.size() != static_cast<std::size_t>(n_nodes)) {
    throw InvalidInput(where + std::to_string(m_tags.nodes.size()) + " node tags for " + std::to_string(n_nodes) + " nodes");
  }
  if (!m_tags.tets.empty() && m_tags.tets.size() != static_cast<std::size_t>(n_tets)) {
    throw InvalidInput(where + std::to_string(m_tags.tets.size()) + " tet tags for " + std::to_string(n_tets) + " tets");
  }

  for (int i = 0; i < n_nodes; ++i) {
    if (!m_nodes.row(i).allFinite()) throw InvalidInput(where + node_label(i) + " has a non-finite coordinate");
  }

  // Indices, repeated nodes, orientation and volume.
  std::vector<char> used(static_cast<std::size_t>(n_nodes), 0);
  m_volumes.resize(n_tets);
  m_centroids.resize(n_tets, 3);
  m_total_volume = 0.0;
  for (int t = 0; t < n_tets; ++t) {
    for (int k = 0; k < 4; ++k) {
      const int v = m_tets(t, k);
      if (v < 0 || v >= n_nodes) {
        throw InvalidInput(where + tet_label(t) + " references node index " + std::to_string(v) + ", but the mesh has " +
                           std::to_string(n_nodes) + " nodes");
      }
      for (int j = 0; j < k; ++j) {
        if (m_tets(t, j) == v) throw InvalidInput(where + tet_label(t) + " uses " + node_label(v) + " twice");
      }
      used[static_cast<std::size_t>(v)] = 1;
    }
    const Eigen::Vector3d a = m_nodes.row(m_tets(t, 0));
    const Eigen::Vector3d b = m_nodes.row(m_tets(t, 1));
    const Eigen::Vector3d c = m_nodes.row(m_tets(t, 2));
    const Eigen::Vector3d d = m_nodes.row(m_tets(t, 3));
    const double volume = (b - a).dot((c - a).cross(d - a)) / 6.0;
    const double longest = std::max({(b - a).norm(), (c - a).norm(), (d - a).norm(),
                                     (c - b).norm(), (d - b).norm(), (d - c).norm()});
    if (std::abs(volume) <= kZeroVolume * longest * longest * longest) {
      throw InvalidInput(where + tet_label(t) + " has zero volume");
    }
    if (volume < 0.0) {
      throw InvalidInput(where + tet_label(t) + " is inverted (volume " + format_number(volume) + " m^3)");
    }
    m_volumes[t] = volume;
    m_total_volume += volume;
    m_centroids.row(t) = ((a + b + c + d) / 4.0).transpose();
  }
  for (int i = 0; i < n_nodes; ++i) {
    if (!used[static_cast<std::size_t>(i)]) throw InvalidInput(where + node_label(i) + " belongs to no tet");
  }

  // Tets around each node, ascending (counting sort: O(#tets)).
  m_node_tets.offsets.assign(static_cast<std::size_t>(n_nodes) + 1, 0);
  for (int t = 0; t < n_tets; ++t)
    for (int k = 0; k < 4; ++k) ++m_node_tets.offsets[static_cast<std::size_t>(m_tets(t, k)) + 1];
  for (int v = 0; v < n_nodes; ++v) m_node_tets.offsets[static_cast<std::size_t>(v) + 1] += m_node_tets.offsets[static_cast<std::size_t>(v)];
  m_node_tets.items.resize(static_cast<std::size_t>(m_node_tets.offsets.back()));
  {
    std::vector<int> fill(m_node_tets.offsets.begin(), m_node_tets.offsets.end() - 1);
    for (int t = 0; t < n_tets; ++t)
      for (int k = 0; k < 4; ++k) m_node_tets.items[static_cast<std::size_t>(fill[static_cast<std::size_t>(m_tets(t, k))]++)] = t;
  }

  // Face adjacency: the 4·#tets faces ordered by their sorted node triples, by bucketing on the
  // smallest node (counting sort) and sorting each small bucket. Two tets sharing a face must
  // lie on opposite sides of it, i.e. wind it in opposite directions; two on the same side
  // overlap (a duplicated or stacked tet), and their volume would count twice.
  std::vector<FaceRecord> faces(static_cast<std::size_t>(n_tets) * 4);
  {
    std::vector<int> bucket(static_cast<std::size_t>(n_nodes) + 1, 0);
    std::vector<FaceRecord> unsorted;
    unsorted.reserve(faces.size());
    for (int t = 0; t < n_tets; ++t) {
      for (int f = 0; f < 4; ++f) {
        FaceRecord r{{m_tets(t, kLocalFaces[f][0]), m_tets(t, kLocalFaces[f][1]), m_tets(t, kLocalFaces[f][2])}, t, f};
        std::sort(r.key.begin(), r.key.end());
        ++bucket[static_cast<std::size_t>(r.key[0]) + 1];
        unsorted.push_back(r);
      }
    }
    for (int v = 0; v < n_nodes; ++v) bucket[static_cast<std::size_t>(v) + 1] += bucket[static_cast<std::size_t>(v)];
    std::vector<int> fill(bucket.begin(), bucket.end() - 1);
    for (const FaceRecord& r : unsorted) faces[static_cast<std::size_t>(fill[static_cast<std::size_t>(r.key[0])]++)] = r;
    for (int v = 0; v < n_nodes; ++v) {
      std::sort(faces.begin() + bucket[static_cast<std::size_t>(v)], faces.begin() + bucket[static_cast<std::size_t>(v) + 1]);
    }
  }
  auto oriented = [&](const FaceRecord& r) {
    const auto& lf = kLocalFaces[static_cast<std::size_t>(r.local_face)];
    return std::array<int, 3>{m_tets(r.tet, lf[0]), m_tets(r.tet, lf[1]), m_tets(r.tet, lf[2])};
  };
  auto face_text = [&](const std::array<int, 3>& key) {
    return "face (" + node_label(key[0]) + ", " + std::to_string(node_tag(key[1])) + ", " + std::to_string(node_tag(key[2])) + ")";
  };
  m_neighbours.setConstant(n_tets, 4, -1);
  m_neighbour_faces.setConstant(n_tets, 4, -1);
  m_face_ids.setConstant(n_tets, 4, -1);
  m_face_count = 0;
  m_boundary_faces.clear();
  for (std::size_t i = 0; i < faces.size();) {
    std::size_t j = i + 1;
    while (j < faces.size() && faces[j].key == faces[i].key) ++j;
    if (j - i > 2) {
      throw InvalidInput(where + face_text(faces[i].key) + " is shared by " + std::to_string(j - i) + " tets (" +
                         tet_label(faces[i].tet) + ", " + std::to_string(tet_tag(faces[i + 1].tet)) + ", " +
                         std::to_string(tet_tag(faces[i + 2].tet)) + ")");
    }
    const FaceRecord& x = faces[i];
    m_face_ids(x.tet, x.local_face) = m_face_count;
    if (j - i == 2) {
      const FaceRecord& y = faces[i + 1];
      if (!opposite_winding(oriented(x), oriented(y))) {
        std::array<int, 4> ta{}, tb{};
        for (int k = 0; k < 4; ++k) {
          ta[static_cast<std::size_t>(k)] = m_tets(x.tet, k);
          tb[static_cast<std::size_t>(k)] = m_tets(y.tet, k);
        }
        std::sort(ta.begin(), ta.end());
        std::sort(tb.begin(), tb.end());
        if (ta == tb) throw InvalidInput(where + tet_label(x.tet) + " and " + tet_label(y.tet) + " are the same tet (duplicated)");
        throw InvalidInput(where + tet_label(x.tet) + " and " + tet_label(y.tet) + " overlap: both lie on the same side of " +
                           face_text(x.key));
      }
      m_neighbours(x.tet, x.local_face) = y.tet;
      m_neighbours(y.tet, y.local_face) = x.tet;
      m_neighbour_faces(x.tet, x.local_face) = y.local_face;
      m_neighbour_faces(y.tet, y.local_face) = x.local_face;
      m_face_ids(y.tet, y.local_face) = m_face_count;
    } else {
      BoundaryFace face{x.tet, x.local_face, oriented(x)};
      const Eigen::Vector3d a = m_nodes.row(face.nodes[0]), b = m_nodes.row(face.nodes[1]), c = m_nodes.row(face.nodes[2]);
      const Eigen::Vector3d twice = (b - a).cross(c - a);
      face.area = 0.5 * twice.norm();
      face.normal = twice.normalized();
      m_boundary_faces.push_back(face);
    }
    ++m_face_count;
    i = j;
  }
  std::sort(m_boundary_faces.begin(), m_boundary_faces.end(), [](const BoundaryFace& p, const BoundaryFace& q) {
    return p.tet != q.tet ? p.tet < q.tet : p.local_face < q.local_face;
  });

  // A mesh folded over itself passes every face test (each face has one tet on either side) but
  // wraps its interior edges twice: the dihedral angles around an interior edge sum to 2π in
  // any embedded mesh, 4π or more where tets overlap. Edges are gathered per smaller node from
  // the node → tet incidence, so no global sort is needed. O(#tets).
  {
    std::vector<char> on_boundary(static_cast<std::size_t>(n_nodes), 0);
    for (const BoundaryFace& f : m_boundary_faces)
      for (int v : f.nodes) on_boundary[static_cast<std::size_t>(v)] = 1;
    // Boundary edges, per smaller node (only boundary nodes have any).
    std::vector<std::vector<int>> boundary_neighbours(static_cast<std::size_t>(n_nodes));
    for (const BoundaryFace& f : m_boundary_faces)
      for (int k = 0; k < 3; ++k) {
        const int a = f.nodes[static_cast<std::size_t>(k)], b = f.nodes[static_cast<std::size_t>((k + 1) % 3)];
        boundary_neighbours[static_cast<std::size_t>(std::min(a, b))].push_back(std::max(a, b));
      }
    std::vector<std::pair<int, double>> around;  // (other node, angle sum) for edges (v, other > v)
    std::vector<int> first_tet;
    for (int v = 0; v < n_nodes; ++v) {
      around.clear();
      first_tet.clear();
      for (const int* it = m_node_tets.begin(v); it != m_node_tets.end(v); ++it) {
        const int t = *it;
        Eigen::Vector3d p[4];
        int local = 0;
        for (int k = 0; k < 4; ++k) {
          p[k] = m_nodes.row(m_tets(t, k)).transpose();
          if (m_tets(t, k) == v) local = k;
        }
        for (int k = 0; k < 4; ++k) {
          const int w = m_tets(t, k);
          if (w <= v) continue;
          const auto& bn = boundary_neighbours[static_cast<std::size_t>(v)];
          if (on_boundary[static_cast<std::size_t>(v)] && on_boundary[static_cast<std::size_t>(w)] &&
              std::find(bn.begin(), bn.end(), w) != bn.end()) {
            continue;  // a boundary edge: its angles sum to the surface's own angle there
          }
          const double angle = dihedral_at_edge(p, local, k);
          std::size_t e = 0;
          while (e < around.size() && around[e].first != w) ++e;
          if (e == around.size()) {
            around.emplace_back(w, 0.0);
            first_tet.push_back(t);
          }
          around[e].second += angle;
        }
      }
      for (std::size_t e = 0; e < around.size(); ++e) {
        // Each angle carries ~1e-15 rad of round-off (more for slivers, still far below 1e-6).
        if (std::abs(around[e].second - 2.0 * std::numbers::pi) > 1e-6) {
          throw InvalidInput(where + "tets overlap around the edge (" + node_label(v) + ", " +
                             std::to_string(node_tag(around[e].first)) + "): their angles there sum to " +
                             format_number(around[e].second * 180.0 / std::numbers::pi, 5) + " deg instead of 360 (e.g. " +
                             tet_label(first_tet[e]) + ")");
        }
      }
    }
  }

  // Connected components of the face-adjacency graph (iterative flood fill).
  m_component_of_tet.assign(static_cast<std::size_t>(n_tets), -1);
  m_component_count = 0;
  std::vector<int> stack;
  for (int seed = 0; seed < n_tets; ++seed) {
    if (m_component_of_tet[static_cast<std::size_t>(seed)] >= 0) continue;
    const int component = m_component_count++;
    stack.push_back(seed);
    m_component_of_tet[static_cast<std::size_t>(seed)] = component;
    while (!stack.empty()) {
      const int t = stack.back();
      stack.pop_back();
      for (int f = 0; f < 4; ++f) {
        const int n = m_neighbours(t, f);
        if (n >= 0 && m_component_of_tet[static_cast<std::size_t>(n)] < 0) {
          m_component_of_tet[static_cast<std::size_t>(n)] = component;
          stack.push_back(n);
        }
      }
    }
  }

  // Named sets must reference existing nodes.
  for (const NamedSet& set : m_named_sets) {
    auto bad_node = [&](int v) {
      throw InvalidInput(where + "set \"" + set.name + "\" references node index " + std::to_string(v) + " of " + std::to_string(n_nodes));
    };
    for (int v : set.nodes)
      if (v < 0 || v >= n_nodes) bad_node(v);
    for (const auto& face : set.faces)
      for (int v : face)
        if (v < 0 || v >= n_nodes) bad_node(v);
    for (int t : set.tets) {
      if (t < 0 || t >= n_tets) {
        throw InvalidInput(where + "set \"" + set.name + "\" references tet index " + std::to_string(t) + " of " + std::to_string(n_tets));
      }
    }
  }
}

Eigen::Matrix<double, 2, 3> TetMesh::bounding_box() const {
  Eigen::Matrix<double, 2, 3> box;
  box.row(0) = m_nodes.colwise().minCoeff();
  box.row(1) = m_nodes.colwise().maxCoeff();
  return box;
}

Eigen::MatrixX3i TetMesh::boundary_triangles() const {
  Eigen::MatrixX3i tris(static_cast<Eigen::Index>(m_boundary_faces.size()), 3);
  for (std::size_t i = 0; i < m_boundary_faces.size(); ++i) {
    for (int k = 0; k < 3; ++k) tris(static_cast<Eigen::Index>(i), k) = m_boundary_faces[i].nodes[k];
  }
  return tris;
}

std::vector<int> TetMesh::component_of_node() const {
  std::vector<int> component(static_cast<std::size_t>(node_count()), -1);
  for (int t = 0; t < tet_count(); ++t) {
    const int c = m_component_of_tet[static_cast<std::size_t>(t)];
    for (int k = 0; k < 4; ++k) {
      int& slot = component[static_cast<std::size_t>(m_tets(t, k))];
      if (slot < 0 || c < slot) slot = c;
    }
  }
  return component;
}

const NamedSet* TetMesh::find_named_set(const std::string& name) const {
  for (const NamedSet& set : m_named_sets) {
    if (set.name == name) return &set;
  }
  return nullptr;
}

QualityReport TetMesh::quality(double sliver_threshold_deg) const {
  QualityReport q;
  q.min_dihedral_deg = 180.0;
  q.min_radius_ratio = 1.0;
  q.min_volume = INFINITY;
  for (int t = 0; t < tet_count(); ++t) {
    const TetShape s = tet_shape(m_nodes.row(m_tets(t, 0)), m_nodes.row(m_tets(t, 1)),
                                 m_nodes.row(m_tets(t, 2)), m_nodes.row(m_tets(t, 3)));
    if (s.min_dihedral_deg < q.min_dihedral_deg) {
      q.min_dihedral_deg = s.min_dihedral_deg;
      q.worst_dihedral_tet = t;
    }
    if (s.radius_ratio < q.min_radius_ratio) {
      q.min_radius_ratio = s.radius_ratio;
      q.worst_radius_ratio_tet = t;
    }
    q.max_dihedral_deg = std::max(q.max_dihedral_deg, s.max_dihedral_deg);
    q.max_radius_edge = std::max(q.max_radius_edge, s.radius_edge);
    q.min_volume = std::min(q.min_volume, s.volume);
    q.max_volume = std::max(q.max_volume, s.volume);
    if (s.min_dihedral_deg < sliver_threshold_deg) ++q.sliver_count;
  }
  return q;
}

}  // namespace fissure
