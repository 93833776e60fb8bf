#pragma once
// Points bucketed in cubic cells, for "which points lie near here" without a container per cell:
// one hash table from cell to the newest point in it, and a next-link per point. The table is
// open-addressed in one array (no allocation per cell: fragment meshing builds one grid per
// fragment, and node-based maps made the allocator its largest cost).
#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace fissure::detail {

class PointGrid {
public:
  explicit PointGrid(double cell, std::size_t expected = 0) : m_cell(cell) {
    rehash(2 * std::max<std::size_t>(expected, 8));
    m_point.reserve(expected);
    m_next.reserve(expected);
  }

  void add(int id, const Eigen::Vector3d& x) {
    if (2 * (m_cells + 1) > m_slots.size()) rehash(2 * m_slots.size());
    Slot& slot = m_slots[find_slot(cell_of(x))];
    if (slot.head < 0) {
      slot.cell = cell_of(x);
      ++m_cells;
    }
    m_point.push_back(id);
    m_next.push_back(slot.head);
    slot.head = static_cast<int>(m_point.size()) - 1;
  }

  /// Calls visit(id) for every point in the cells the box [low, high] touches (a superset of the
  /// points inside it), each once.
  template <class Visit>
  void visit_box(const Eigen::Vector3d& low, const Eigen::Vector3d& high, Visit&& visit) const {
    const Cell a = cell_of(low), b = cell_of(high);
    for (std::int64_t x = a[0]; x <= b[0]; ++x)
      for (std::int64_t y = a[1]; y <= b[1]; ++y)
        for (std::int64_t z = a[2]; z <= b[2]; ++z) {
          const Slot& slot = m_slots[find_slot(Cell{x, y, z})];
          for (int k = slot.head; k >= 0; k = m_next[static_cast<std::size_t>(k)]) visit(m_point[static_cast<std::size_t>(k)]);
        }
  }

private:
  using Cell = std::array<std::int64_t, 3>;
  struct Slot {
    Cell cell{};
    int head = -1;  // −1: an empty slot
  };
  static std::size_t hash(const Cell& c) {
    std::uint64_t h = static_cast<std::uint64_t>(c[0]) * 0x9E3779B97F4A7C15ull;
    h ^= static_cast<std::uint64_t>(c[1]) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
    h ^= static_cast<std::uint64_t>(c[2]) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
    return static_cast<std::size_t>(h ^ (h >> 29));
  }
  // The slot holding `c`, or the empty slot where it would go (linear probing; the table is at
  // most half full, so a probe ends).
  std::size_t find_slot(const Cell& c) const {
    const std::size_t mask = m_slots.size() - 1;
    std::size_t i = hash(c) & mask;
    while (m_slots[i].head >= 0 && m_slots[i].cell != c) i = (i + 1) & mask;
    return i;
  }
  void rehash(std::size_t size) {
    std::size_t slots = 16;
    while (slots < size) slots *= 2;
    std::vector<Slot> old = std::move(m_slots);
    m_slots.assign(slots, Slot{});
    for (const Slot& s : old)
      if (s.head >= 0) m_slots[find_slot(s.cell)] = s;
  }
  Cell cell_of(const Eigen::Vector3d& x) const {
    return {static_cast<std::int64_t>(std::floor(x.x() / m_cell)), static_cast<std::int64_t>(std::floor(x.y() / m_cell)),
            static_cast<std::int64_t>(std::floor(x.z() / m_cell))};
  }

  double m_cell;
  std::vector<Slot> m_slots;
  std::size_t m_cells = 0;
  std::vector<int> m_point, m_next;
};

}  // namespace fissure::detail
