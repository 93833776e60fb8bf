#pragma once
// Points bucketed in cubic cells, for "which points lie near here" without a container per cell:
// one hash map from cell to the newest point in it, and a next-link per point.
#include <Eigen/Core>

#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace fissure::detail {

class PointGrid {
public:
  explicit PointGrid(double cell, std::size_t expected = 0) : m_cell(cell) {
    m_head.reserve(expected);
    m_point.reserve(expected);
    m_next.reserve(expected);
  }

  void add(int id, const Eigen::Vector3d& x) {
    const auto [it, inserted] = m_head.try_emplace(cell_of(x), -1);
    m_point.push_back(id);
    m_next.push_back(it->second);
    it->second = static_cast<int>(m_point.size()) - 1;
  }

  /// Calls visit(id) for every point in the cells the box [low, high] touches (a superset of the
  /// points inside it), each once.
  template <class Visit>
  void visit_box(const Eigen::Vector3d& low, const Eigen::Vector3d& high, Visit&& visit) const {
    const Cell a = cell_of(low), b = cell_of(high);
    for (std::int64_t x = a[0]; x <= b[0]; ++x)
      for (std::int64_t y = a[1]; y <= b[1]; ++y)
        for (std::int64_t z = a[2]; z <= b[2]; ++z) {
          const auto it = m_head.find(Cell{x, y, z});
          if (it == m_head.end()) continue;
          for (int k = it->second; k >= 0; k = m_next[static_cast<std::size_t>(k)]) visit(m_point[static_cast<std::size_t>(k)]);
        }
  }

private:
  using Cell = std::array<std::int64_t, 3>;
  struct CellHash {
    std::size_t operator()(const Cell& c) const {
      std::uint64_t h = static_cast<std::uint64_t>(c[0]) * 0x9E3779B97F4A7C15ull;
      h ^= static_cast<std::uint64_t>(c[1]) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
      h ^= static_cast<std::uint64_t>(c[2]) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
      return static_cast<std::size_t>(h);
    }
  };
  Cell cell_of(const Eigen::Vector3d& x) const {
    return {static_cast<std::int64_t>(std::floor(x.x() / m_cell)), static_cast<std::int64_t>(std::floor(x.y() / m_cell)),
            static_cast<std::int64_t>(std::floor(x.z() / m_cell))};
  }

  double m_cell;
  std::unordered_map<Cell, int, CellHash> m_head;
  std::vector<int> m_point, m_next;
};

}  // namespace fissure::detail
