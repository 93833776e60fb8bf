#pragma once
// Disjoint sets over 0 … n−1 (path halving, the lower index always the root, so a component's
// root is its lowest member and results do not depend on the order of unions). Used by the
// fragment labels (pieces of tets) and the visible pattern (pieces of triangles).
#include <algorithm>
#include <cstddef>
#include <numeric>
#include <vector>

namespace fissure::detail {

class UnionFind {
public:
  explicit UnionFind(std::size_t n = 0) : m_parent(n) { std::iota(m_parent.begin(), m_parent.end(), 0); }
  /// A new singleton set; returns its index.
  int add() {
    m_parent.push_back(static_cast<int>(m_parent.size()));
    return m_parent.back();
  }
  int find(int x) {
    while (m_parent[static_cast<std::size_t>(x)] != x) {
      m_parent[static_cast<std::size_t>(x)] = m_parent[static_cast<std::size_t>(m_parent[static_cast<std::size_t>(x)])];
      x = m_parent[static_cast<std::size_t>(x)];
    }
    return x;
  }
  void unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a != b) m_parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
  }
  std::size_t size() const { return m_parent.size(); }

private:
  std::vector<int> m_parent;
};

}  // namespace fissure::detail
