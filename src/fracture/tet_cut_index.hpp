#pragma once
// Every tet's cuts side by side (CSR), in crack order within each tet, copied out of the cracks:
// the fragment labeller and the fragment meshing visit tets in mesh order, and reaching each cut
// through its crack's array missed the cache (perf on the 54K slab of bench_fracture: those loads
// were the labeller's hot spots).
#include "fissure/fracture/crack_surface.hpp"
#include "tet_pieces.hpp"

#include <cmath>
#include <span>
#include <vector>

namespace fissure::detail {

class TetCutIndex {
public:
  /// The cuts of cracks[0 .. count) over a mesh of `tet_count` tets. Node values nearer zero
  /// than `min_node_value` are moved out to it, on their own side (fragment_mesh.cpp says why).
  TetCutIndex(int tet_count, const std::vector<CrackSurface>& cracks, int count, double min_node_value = 0.0)
      : m_first(static_cast<std::size_t>(tet_count) + 1, 0) {
    for (int k = 0; k < count; ++k)
      for (const CrackCut& c : cracks[static_cast<std::size_t>(k)].cuts) ++m_first[static_cast<std::size_t>(c.tet) + 1];
    for (std::size_t t = 1; t < m_first.size(); ++t) m_first[t] += m_first[t - 1];
    m_cuts.resize(static_cast<std::size_t>(m_first.back()));
    std::vector<int> next(m_first.begin(), m_first.end() - 1);
    for (int k = 0; k < count; ++k) {
      for (const CrackCut& c : cracks[static_cast<std::size_t>(k)].cuts) {
        TetCutPlane& out = m_cuts[static_cast<std::size_t>(next[static_cast<std::size_t>(c.tet)]++)];
        out = {k, c.node_values, c.clipped_by, c.clip_side};
        for (double& v : out.node_values)
          if (std::abs(v) < min_node_value) v = v > 0.0 ? min_node_value : -min_node_value;
      }
    }
  }

  std::span<const TetCutPlane> of(int tet) const {
    const auto t = static_cast<std::size_t>(tet);
    return {m_cuts.data() + m_first[t], m_cuts.data() + m_first[t + 1]};
  }

private:
  std::vector<int> m_first;  // tet t's cuts are m_cuts[m_first[t], m_first[t + 1])
  std::vector<TetCutPlane> m_cuts;
};

}  // namespace fissure::detail
