#include "fissure/fracture/fracture_result.hpp"

#include "tet_cut_index.hpp"
#include "union_find.hpp"

#include <algorithm>
#include <numeric>
#include <span>
#include <string>

namespace fissure {
namespace {

// The seven probe points of a face, as weights on its three nodes.
constexpr double kProbes[7][3] = {{0.8, 0.1, 0.1},   {0.1, 0.8, 0.1},   {0.1, 0.1, 0.8},   {0.45, 0.45, 0.1},
                                  {0.1, 0.45, 0.45}, {0.45, 0.1, 0.45}, {1.0 / 3, 1.0 / 3, 1.0 / 3}};

using TetCut = detail::TetCutPlane;

class PieceLabeller {
public:
  PieceLabeller(const TetMesh& mesh, const std::vector<CrackSurface>& cracks, int count)
      : m_mesh(mesh), m_cuts(mesh.tet_count(), cracks, count),
        m_pieces(static_cast<std::size_t>(mesh.tet_count())),
        m_sets(static_cast<std::size_t>(mesh.tet_count())) {
    // Uncut tets are one piece each, with the tet's index as its id.
  }

  // The piece of `tet` holding the point with weights `w` on its local nodes.
  int piece(int tet, const std::array<double, 4>& w, bool create) {
    const auto cuts = cuts_of(tet);
    if (cuts.empty()) return tet;
    std::string& key = m_key;
    key.assign(cuts.size(), '\0');
    for (std::size_t i = 0; i < cuts.size(); ++i) {
      const TetCut& c = cuts[i];
      char code = value(c, w) > 0.0 ? 1 : 2;
      if (c.clipped_by >= 0) {
        // The crack exists only on its arrival side of the crack it stopped on.
        for (const TetCut& other : cuts) {
          if (other.crack == c.clipped_by && c.clip_side * value(other, w) < 0.0) code = 0;
        }
      }
      key[i] = code;
    }
    auto& pieces = m_pieces[static_cast<std::size_t>(tet)];
    for (const auto& [k, id] : pieces) {
      if (same_key(k, key)) return id;
    }
    if (!create) return -1;
    const int id = m_sets.add();
    pieces.emplace_back(key, id);
    return id;
  }

  FragmentLabels label() {
    const auto& tets = m_mesh.tets();
    for (int t = 0; t < m_mesh.tet_count(); ++t) {
      for (int f = 0; f < 4; ++f) {
        const int u = m_mesh.neighbours()(t, f);
        if (u < t) continue;  // each shared face once; boundary faces (−1) skipped
        const bool cut = !cuts_of(t).empty() || !cuts_of(u).empty();
        if (!cut) {
          m_sets.unite(t, u);
          continue;
        }
        const auto& face = TetMesh::kLocalFaces[static_cast<std::size_t>(f)];
        // Where no crack of either tet changes sign across this face, every probe lands in the
        // same piece on each side: one probe does (most faces of a finely cracked body).
        const int u_face = m_mesh.neighbour_faces()(t, f);
        const bool uniform = uniform_on_face(t, face) &&
                             uniform_on_face(u, TetMesh::kLocalFaces[static_cast<std::size_t>(u_face)]);
        const std::span<const double[3]> probes(kProbes);  // the last is the face's centre
        for (const auto& probe : uniform ? probes.last(1) : probes) {
          std::array<double, 4> wt{}, wu{};
          for (int i = 0; i < 3; ++i) {
            const int node = tets(t, face[static_cast<std::size_t>(i)]);
            wt[static_cast<std::size_t>(face[static_cast<std::size_t>(i)])] = probe[i];
            for (int j = 0; j < 4; ++j) {
              if (tets(u, j) == node) wu[static_cast<std::size_t>(j)] = probe[i];
            }
          }
          m_sets.unite(piece(t, wt, true), piece(u, wu, true));
        }
      }
    }
    FragmentLabels labels;
    labels.fragment_of_tet.resize(static_cast<std::size_t>(m_mesh.tet_count()));
    std::vector<int> centre_piece(static_cast<std::size_t>(m_mesh.tet_count()));
    for (int t = 0; t < m_mesh.tet_count(); ++t) centre_piece[static_cast<std::size_t>(t)] = piece(t, {0.25, 0.25, 0.25, 0.25}, true);
    // Number fragments by the lowest tet whose centroid lies in them. Pieces holding no centroid
    // (slivers a crack cuts off a tet's corner, or between two cracks in one tet) join a
    // fragment where a probe finds them connected and are not counted otherwise: the labels do
    // not resolve anything smaller than a tet's share, the fragment meshing does.
    std::vector<int> number(m_sets.size(), -1);
    for (int t = 0; t < m_mesh.tet_count(); ++t) {
      const int root = m_sets.find(centre_piece[static_cast<std::size_t>(t)]);
      if (number[static_cast<std::size_t>(root)] < 0) number[static_cast<std::size_t>(root)] = labels.count++;
      labels.fragment_of_tet[static_cast<std::size_t>(t)] = number[static_cast<std::size_t>(root)];
    }
    return labels;
  }

  // Cracks that separate no piece of any tet they cut from its other side: partial cracks.
  // Call after label().
  std::vector<int> partial_cracks(int count) {
    std::vector<char> separates(static_cast<std::size_t>(count), 0);
    for (std::size_t tet = 0; tet < m_pieces.size(); ++tet) {
      const auto& pieces = m_pieces[tet];
      const auto cuts = cuts_of(static_cast<int>(tet));
      for (std::size_t i = 0; i < cuts.size(); ++i) {
        if (separates[static_cast<std::size_t>(cuts[i].crack)]) continue;
        for (const auto& [ka, ia] : pieces) {
          for (const auto& [kb, ib] : pieces) {
            // Two pieces on opposite sides of crack i, alike otherwise.
            if (ka[i] != 1 || kb[i] != 2) continue;
            bool alike = true;
            for (std::size_t j = 0; j < ka.size() && alike; ++j) alike = j == i || ka[j] == kb[j];
            if (alike && m_sets.find(ia) != m_sets.find(ib)) separates[static_cast<std::size_t>(cuts[i].crack)] = 1;
          }
        }
      }
    }
    std::vector<int> partial;
    for (int k = 0; k < count; ++k) {
      if (!separates[static_cast<std::size_t>(k)]) partial.push_back(k);
    }
    return partial;
  }

private:
  // Whether every crack cutting `tet`, and every crack clipping one, has one sign on all three
  // nodes of the face (local nodes `face`): then it has that sign all over the face.
  bool uniform_on_face(int tet, const std::array<int, 3>& face) const {
    for (const TetCut& c : cuts_of(tet)) {
      const auto& v = c.node_values;
      const bool positive = v[static_cast<std::size_t>(face[0])] > 0.0;
      if ((v[static_cast<std::size_t>(face[1])] > 0.0) != positive || (v[static_cast<std::size_t>(face[2])] > 0.0) != positive)
        return false;
    }
    return true;
  }

  std::span<const TetCut> cuts_of(int tet) const { return m_cuts.of(tet); }

  // Keys are a few codes long; std::string's == (and std::equal) called memcmp for them, nearly a
  // third of the labelling time on bench_fracture's 7K tile.
  static bool same_key(const std::string& a, const std::string& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
      if (a[i] != b[i]) return false;
    return true;
  }

  static double value(const TetCut& c, const std::array<double, 4>& w) {
    return w[0] * c.node_values[0] + w[1] * c.node_values[1] + w[2] * c.node_values[2] + w[3] * c.node_values[3];
  }

  const TetMesh& m_mesh;
  detail::TetCutIndex m_cuts;
  // Per cut tet, its pieces so far: (the side of each of its cuts the piece lies on, as a
  // code per cut in m_cuts order: 1 positive, 2 negative, 0 beyond a clip; the piece's id).
  std::vector<std::vector<std::pair<std::string, int>>> m_pieces;
  std::string m_key;  // piece()'s scratch key
  detail::UnionFind m_sets;
};

}  // namespace

FragmentLabels label_fragments(const TetMesh& mesh, const std::vector<CrackSurface>& cracks, int crack_count,
                               std::vector<int>* partial_cracks) {
  crack_count = std::clamp(crack_count, 0, static_cast<int>(cracks.size()));
  PieceLabeller labeller(mesh, cracks, crack_count);
  FragmentLabels labels = labeller.label();
  if (partial_cracks) *partial_cracks = labeller.partial_cracks(crack_count);
  return labels;
}

int FractureResult::crack_count_at(double age) const {
  const auto it = std::upper_bound(cracks.begin(), cracks.end(), age,
                                   [](double a, const CrackSurface& c) { return a < c.time; });
  return static_cast<int>(it - cracks.begin());
}

}  // namespace fissure
