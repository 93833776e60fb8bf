#pragma once
// Multi-source nearest-seed propagation over a tet mesh's face adjacency ("vector propagation"):
// every tet reached takes, among the seeds its neighbours carry, the one nearest to it by the
// caller's distance, in Dijkstra order, until the distance exceeds a bound. It measures distances
// through the body (never across an air gap, such as between a bowl's walls) and costs a few
// distance evaluations per tet reached. The result can differ from the true nearest seed only
// where two seeds' regions meet at a narrow angle (the classic vector-propagation error); for
// crack polygons and boundary faces a few element sizes across that is well below the sizes it
// feeds (r_relax, the surface normal).
#include "fissure/mesh/tet_mesh.hpp"

#include <algorithm>
#include <functional>
#include <limits>
#include <utility>
#include <vector>

namespace fissure::detail {

class NearestSeedPropagation {
public:
  explicit NearestSeedPropagation(const TetMesh& mesh)
      : m_mesh(mesh),
        m_stamp(static_cast<std::size_t>(mesh.tet_count()), 0),
        m_distance(static_cast<std::size_t>(mesh.tet_count()), 0.0),
        m_seed(static_cast<std::size_t>(mesh.tet_count()), -1) {}

  /// Runs from `seeds` (tet, seed id), each tet reached with distance(tet, seed) < max_distance.
  /// Afterwards reached() lists the tets in the order they were settled, with seed_of / distance_of.
  template <class Distance>
  void run(const std::vector<std::pair<int, int>>& seeds, Distance&& distance, double max_distance) {
    ++m_current;
    m_reached.clear();
    // A min-heap of (distance, tet), ties by tet index (deterministic), kept between runs so a
    // run does not allocate.
    std::vector<Entry>& heap = m_heap;
    heap.clear();
    const std::greater<> later;
    auto offer = [&](int tet, int seed) {
      const auto t = static_cast<std::size_t>(tet);
      if (m_stamp[t] == m_current + kSettled) return;  // final: no distance to compute
      if (m_stamp[t] == m_current && m_seed[t] == seed) return;  // already offered this seed
      const double d = distance(tet, seed);
      if (!(d < max_distance)) return;
      if (m_stamp[t] == m_current && !(d < m_distance[t])) return;
      m_stamp[t] = m_current;
      m_distance[t] = d;
      m_seed[t] = seed;
      heap.emplace_back(d, tet);
      std::push_heap(heap.begin(), heap.end(), later);
    };
    for (const auto& [tet, seed] : seeds) offer(tet, seed);
    const auto& neighbours = m_mesh.neighbours();
    while (!heap.empty()) {
      std::pop_heap(heap.begin(), heap.end(), later);
      const auto [d, tet] = heap.back();
      heap.pop_back();
      const auto t = static_cast<std::size_t>(tet);
      if (m_stamp[t] != m_current || d != m_distance[t]) continue;  // stale entry
      m_stamp[t] = m_current + kSettled;
      m_reached.push_back(tet);
      for (int f = 0; f < 4; ++f) {
        const int u = neighbours(tet, f);
        if (u >= 0) offer(u, m_seed[t]);
      }
    }
    m_current += kSettled;  // stamps of this run are now all < the next run's
  }

  const std::vector<int>& reached() const { return m_reached; }
  int seed_of(int tet) const { return m_seed[static_cast<std::size_t>(tet)]; }
  double distance_of(int tet) const { return m_distance[static_cast<std::size_t>(tet)]; }

private:
  // A run uses two stamp values: m_current (queued) and m_current + kSettled (final).
  static constexpr unsigned kSettled = 1;
  using Entry = std::pair<double, int>;
  const TetMesh& m_mesh;
  std::vector<Entry> m_heap;
  std::vector<unsigned> m_stamp;
  std::vector<double> m_distance;
  std::vector<int> m_seed;
  std::vector<int> m_reached;
  unsigned m_current = 0;
};

}  // namespace fissure::detail
