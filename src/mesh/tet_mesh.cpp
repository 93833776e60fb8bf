#include "fissure/mesh/tet_mesh.hpp"

#include "fissure/base/error.hpp"

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
    return key != o.key ? key < o.key : (tet != o.tet ? tet < o.tet : local_face < o.local_face);
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
                 std::vector<NamedSet> named_sets)
    : m_nodes(std::move(nodes)),
      m_tets(std::move(tets)),
      m_source_name(std::move(source_name)),
      m_named_sets(std::move(named_sets)) {
  validate_and_index();
}

void TetMesh::validate_and_index() {
  const std::string where = prefix(m_source_name);
  const int n_nodes = node_count();
  const int n_tets = tet_count();
  if (n_tets == 0) throw InvalidInput(where + "mesh has no tetrahedra");

  for (int i = 0; i < n_nodes; ++i) {
    if (!m_nodes.row(i).allFinite()) {
      throw InvalidInput(where + "node " + std::to_string(i) + " has a non-finite coordinate");
    }
  }

  // Indices, repeated nodes, orientation and volume.
  std::vector<char> used(static_cast<std::size_t>(n_nodes), 0);
  m_volumes.resize(n_tets);
  m_total_volume = 0.0;
  for (int t = 0; t < n_tets; ++t) {
    for (int k = 0; k < 4; ++k) {
      const int v = m_tets(t, k);
      if (v < 0 || v >= n_nodes) {
        throw InvalidInput(where + "tet " + std::to_string(t) + " references node " +
                           std::to_string(v) + ", but the mesh has " + std::to_string(n_nodes) +
                           " nodes");
      }
      for (int j = 0; j < k; ++j) {
        if (m_tets(t, j) == v) {
          throw InvalidInput(where + "tet " + std::to_string(t) + " uses node " +
                             std::to_string(v) + " twice");
        }
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
      throw InvalidInput(where + "tet " + std::to_string(t) + " has zero volume");
    }
    if (volume < 0.0) {
      throw InvalidInput(where + "tet " + std::to_string(t) + " is inverted (volume " +
                         std::to_string(volume) + " m^3)");
    }
    m_volumes[t] = volume;
    m_total_volume += volume;
  }
  for (int i = 0; i < n_nodes; ++i) {
    if (!used[static_cast<std::size_t>(i)]) {
      throw InvalidInput(where + "node " + std::to_string(i) + " belongs to no tet");
    }
  }

  // Face adjacency by sorting the 4·#tets faces on their sorted node triples.
  std::vector<FaceRecord> faces;
  faces.reserve(static_cast<std::size_t>(n_tets) * 4);
  for (int t = 0; t < n_tets; ++t) {
    for (int f = 0; f < 4; ++f) {
      FaceRecord r{{m_tets(t, kLocalFaces[f][0]), m_tets(t, kLocalFaces[f][1]),
                    m_tets(t, kLocalFaces[f][2])},
                   t, f};
      std::sort(r.key.begin(), r.key.end());
      faces.push_back(r);
    }
  }
  std::sort(faces.begin(), faces.end());
  m_neighbours.setConstant(n_tets, 4, -1);
  m_boundary_faces.clear();
  for (std::size_t i = 0; i < faces.size();) {
    std::size_t j = i + 1;
    while (j < faces.size() && faces[j].key == faces[i].key) ++j;
    if (j - i > 2) {
      throw InvalidInput(where + "face (" + std::to_string(faces[i].key[0]) + ", " +
                         std::to_string(faces[i].key[1]) + ", " + std::to_string(faces[i].key[2]) +
                         ") is shared by " + std::to_string(j - i) + " tets (tets " +
                         std::to_string(faces[i].tet) + ", " + std::to_string(faces[i + 1].tet) +
                         ", " + std::to_string(faces[i + 2].tet) + ")");
    }
    if (j - i == 2) {
      m_neighbours(faces[i].tet, faces[i].local_face) = faces[i + 1].tet;
      m_neighbours(faces[i + 1].tet, faces[i + 1].local_face) = faces[i].tet;
    } else {
      const int t = faces[i].tet;
      const auto& lf = kLocalFaces[faces[i].local_face];
      m_boundary_faces.push_back(
          BoundaryFace{t, faces[i].local_face, {m_tets(t, lf[0]), m_tets(t, lf[1]), m_tets(t, lf[2])}});
    }
    i = j;
  }
  std::sort(m_boundary_faces.begin(), m_boundary_faces.end(),
            [](const BoundaryFace& x, const BoundaryFace& y) {
              return x.tet != y.tet ? x.tet < y.tet : x.local_face < y.local_face;
            });

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
    for (int v : set.nodes) {
      if (v < 0 || v >= n_nodes) {
        throw InvalidInput(where + "set \"" + set.name + "\" references node " + std::to_string(v));
      }
    }
    for (const auto& face : set.faces) {
      for (int v : face) {
        if (v < 0 || v >= n_nodes) {
          throw InvalidInput(where + "set \"" + set.name + "\" references node " + std::to_string(v));
        }
      }
    }
    for (int t : set.tets) {
      if (t < 0 || t >= n_tets) {
        throw InvalidInput(where + "set \"" + set.name + "\" references tet " + std::to_string(t));
      }
    }
  }
}

Eigen::Vector3d TetMesh::centroid(int tet) const {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int k = 0; k < 4; ++k) c += m_nodes.row(m_tets(tet, k)).transpose();
  return c / 4.0;
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
