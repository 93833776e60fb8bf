#include "fissure/fracture/fragment_mesh.hpp"

#include "fissure/base/parallel.hpp"

#include "point_grid.hpp"
#include "polygon_geometry.hpp"
#include "tet_cut_index.hpp"
#include "tet_pieces.hpp"
#include "union_find.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numeric>
#include <tuple>
#include <unordered_map>

namespace fissure {
namespace {

// Dust, as a fraction of the mean element volume (mesh_fragments below).
constexpr double kDustPerElement = 0.01;

using Polygon = detail::SmallVector<Eigen::Vector3d, 8>;  // the type of PieceFace::points
using detail::PieceFace;
using detail::PieceFaceKind;
using detail::TetPiece;

using detail::polygon_area;
using detail::polygon_area_vector;
using detail::position_before;

// The part of convex polygon `a` (counter-clockwise about `normal`) on the left of the line
// through e0 → e1 in its plane. The line's function is taken from its lexicographically first
// end, and crossings from their segment's first end, so clipping by the same line from either
// side gives the same bits.
Polygon clip_left(const Polygon& a, Eigen::Vector3d e0, Eigen::Vector3d e1, const Eigen::Vector3d& normal) {
  double sign = 1.0;
  if (position_before(e1, e0)) {
    std::swap(e0, e1);
    sign = -1.0;
  }
  const Eigen::Vector3d inward = normal.cross(e1 - e0);
  detail::SmallVector<double, 16> f;
  for (std::size_t i = 0; i < a.size(); ++i) f.push_back(sign * inward.dot(a[i] - e0));
  Polygon out;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const std::size_t j = (i + 1) % a.size();
    if (f[i] >= 0.0) out.push_back(a[i]);
    if ((f[i] > 0.0 && f[j] < 0.0) || (f[i] < 0.0 && f[j] > 0.0)) {
      std::size_t p = i, q = j;
      if (position_before(a[j], a[i])) std::swap(p, q);
      const double t = f[p] / (f[p] - f[q]);
      out.push_back(a[p] + t * (a[q] - a[p]));
    }
  }
  return out;
}

// A ∩ B for coplanar convex polygons, B wound the other way (the face across from A). Wound like A.
Polygon intersect(const Polygon& a, const Polygon& b_across) {
  const Eigen::Vector3d normal = polygon_area_vector(a).normalized();
  if (!(polygon_area_vector(b_across).dot(normal) < 0.0)) return {};  // not facing: beside it on one side
  Polygon out = a;
  // B wound like A: its edges run the other way round.
  for (std::size_t i = 0; i < b_across.size() && out.size() >= 3; ++i) {
    const std::size_t j = (i + 1) % b_across.size();
    out = clip_left(out, b_across[j], b_across[i], normal);
  }
  return out.size() >= 3 ? out : Polygon{};
}

// Whether the boxes of two polygons are apart along an axis by more than `slack`: then they
// share no area, and intersect() (most of the pairs meshing tries) need not run. The slack
// matters: two faces on one plane agree only to round-off where their corners are not the
// canonical crossings (a point where two cracks meet on a tet face is clipped in each tet), so
// on the face z = 0.01 of a tile one had every z one ulp above the other's, and without slack
// the pieces were never joined (a cell of three crack faces left open beside a hole).
bool boxes_apart(const Polygon& a, const Polygon& b, double slack) {
  Eigen::Vector3d a_low = a[0], a_high = a[0], b_low = b[0], b_high = b[0];
  for (const auto& x : a) {
    a_low = a_low.cwiseMin(x);
    a_high = a_high.cwiseMax(x);
  }
  for (const auto& x : b) {
    b_low = b_low.cwiseMin(x);
    b_high = b_high.cwiseMax(x);
  }
  return (a_high.array() + slack < b_low.array()).any() || (b_high.array() + slack < a_low.array()).any();
}

const PieceFace* face_on(const TetPiece& piece, PieceFaceKind kind, int index) {
  for (const PieceFace& f : piece.faces)
    if (f.kind == kind && f.index == index) return &f;
  return nullptr;
}

struct Emitted {
  Polygon polygon;
  int crack;  // -1: the body's surface
};

// Positions within `tolerance` of each other become one vertex (the lowest-numbered one near):
// crossings of one line found in two polygons agree to round-off, not always to the bit.
class VertexWelder {
public:
  VertexWelder(double tolerance, std::size_t expected) : m_tolerance(tolerance), m_grid(4.0 * tolerance, expected) {
    m_points.reserve(expected);
  }

  int index(const Eigen::Vector3d& x) {
    int found = -1;
    const Eigen::Vector3d reach = Eigen::Vector3d::Constant(m_tolerance);
    m_grid.visit_box(x - reach, x + reach, [&](int v) {
      if ((found < 0 || v < found) && (m_points[static_cast<std::size_t>(v)] - x).norm() <= m_tolerance) found = v;
    });
    if (found >= 0) return found;
    const int v = static_cast<int>(m_points.size());
    m_points.push_back(x);
    m_grid.add(v, x);
    return v;
  }

  const std::vector<Eigen::Vector3d>& points() const { return m_points; }

private:
  double m_tolerance;
  detail::PointGrid m_grid;
  std::vector<Eigen::Vector3d> m_points;
};

// The triangles round an edge used by more than two, paired: each with the one next to it round
// the edge on its solid side (the two bound one solid wedge).
std::vector<std::pair<int, int>> wedge_pairs(const std::vector<Eigen::Vector3d>& vertices, const std::vector<Eigen::Vector3i>& triangles,
                                             std::pair<int, int> edge, const std::vector<int>& ts) {
  const Eigen::Vector3d a = vertices[static_cast<std::size_t>(edge.first)];
  const Eigen::Vector3d u = (vertices[static_cast<std::size_t>(edge.second)] - a).normalized();
  const Eigen::Vector3d e1 = u.unitOrthogonal(), e2 = u.cross(e1);
  struct Around {
    double angle;
    int triangle;
    bool inner_ahead;  // its solid side lies toward increasing angle
  };
  std::vector<Around> order;
  for (int t : ts) {
    const auto& tri = triangles[static_cast<std::size_t>(t)];
    int c = 0;
    for (int i = 0; i < 3; ++i)
      if (tri(i) != edge.first && tri(i) != edge.second) c = tri(i);
    const Eigen::Vector3d w = vertices[static_cast<std::size_t>(c)] - a;
    const Eigen::Vector3d p0 = vertices[static_cast<std::size_t>(tri(0))], p1 = vertices[static_cast<std::size_t>(tri(1))],
                          p2 = vertices[static_cast<std::size_t>(tri(2))];
    const Eigen::Vector3d normal = (p1 - p0).cross(p2 - p0);  // outward
    order.push_back({std::atan2(w.dot(e2), w.dot(e1)), t, u.cross(w).dot(-normal) > 0.0});
  }
  std::sort(order.begin(), order.end(), [](const Around& x, const Around& y) { return x.angle < y.angle; });
  std::vector<std::pair<int, int>> pairs;
  const std::size_t n = order.size();
  for (std::size_t i = 0; i < n; ++i)
    if (order[i].inner_ahead) pairs.emplace_back(order[i].triangle, order[(i + 1) % n].triangle);
  return pairs;
}

// Where one fragment's surface touches itself along an edge or at a vertex (two cracks cross
// in a tet and the fragment holds two opposite corners of the cross, joined elsewhere), each
// sheet gets its own copy of the vertex, so every edge is used by exactly two triangles. The
// sheets at a vertex are its triangles joined across its edges: across a manifold edge (one
// triangle each way) the two triangles; across a pinched edge each triangle with the one next
// to it round the edge on its inner side (the two bound the same solid wedge).
//
// The copies are then moved into their own sheet's solid side, by 4e-7 of the fragment's size:
// copies at one position would be welded back into the pinch by readers that merge vertices by
// position (Blender's glTF "merge vertices" compares float32 positions relative to the origin,
// the centre of mass; 4e-7 of the size is ≥ 2 float32 steps along the largest component of the
// move). The volume changes by that times the area round the vertex: ~1e-10 of it here.
// An edge whose sheets also join round both its ends (no copy of an end parts them: one of 849
// fragments of the 1 m tile at 57K tets and 2,005 cracks) is split at its midpoint, one
// midpoint per sheet, moved the same way; a far shorter one (8e-11 m on a 6 cm fragment, seen
// in the sanitizer build, whose round-off differs) is merged into a point first.
// `triangle_crack` follows the triangles.
// Returns the separation and the vertices moved.
std::pair<double, std::vector<int>> unpinch(std::vector<Eigen::Vector3d>& vertices, std::vector<Eigen::Vector3i>& triangles,
                                            std::vector<int>& triangle_crack) {
  Eigen::Vector3d low = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), high = -low;
  for (const auto& x : vertices) {
    low = low.cwiseMin(x);
    high = high.cwiseMax(x);
  }
  const double separation = vertices.empty() ? 0.0 : 4e-7 * (high - low).norm();
  // A pinched edge far shorter than the separation is a pinch at a point: its ends are merged
  // (the triangles on it, two per sheet, go), and the vertex pass below parts the sheets there.
  // Split instead, its halves would be collapsed back into a pinch by collapse_short_edges.
  {
    std::map<std::pair<int, int>, int> uses;
    for (const auto& t : triangles)
      for (int i = 0; i < 3; ++i) ++uses[{std::min(t(i), t((i + 1) % 3)), std::max(t(i), t((i + 1) % 3))}];
    std::vector<int> merged(vertices.size());
    std::iota(merged.begin(), merged.end(), 0);
    bool any = false;
    for (const auto& [edge, count] : uses) {
      if (count <= 2 || merged[static_cast<std::size_t>(edge.first)] != edge.first || merged[static_cast<std::size_t>(edge.second)] != edge.second) continue;
      if ((vertices[static_cast<std::size_t>(edge.first)] - vertices[static_cast<std::size_t>(edge.second)]).norm() >= 10.0 * separation) continue;
      merged[static_cast<std::size_t>(edge.second)] = edge.first;
      any = true;
    }
    if (any) {
      std::vector<Eigen::Vector3i> kept;
      std::vector<int> kept_crack;
      for (std::size_t t = 0; t < triangles.size(); ++t) {
        Eigen::Vector3i tri = triangles[t];
        for (int i = 0; i < 3; ++i) tri(i) = merged[static_cast<std::size_t>(tri(i))];
        if (tri(0) == tri(1) || tri(1) == tri(2) || tri(2) == tri(0)) continue;
        kept.push_back(tri);
        kept_crack.push_back(triangle_crack[t]);
      }
      triangles = std::move(kept);
      triangle_crack = std::move(kept_crack);
    }
  }
  const std::vector<Eigen::Vector3i> before = triangles;  // the sheets are read off the input
  // Each undirected edge's triangles.
  std::map<std::pair<int, int>, std::vector<int>> edge_triangles;
  for (std::size_t t = 0; t < before.size(); ++t)
    for (int i = 0; i < 3; ++i) {
      const int a = before[t](i), b = before[t]((i + 1) % 3);
      edge_triangles[{std::min(a, b), std::max(a, b)}].push_back(static_cast<int>(t));
    }
  // Pairs of triangles joined across each edge.
  std::map<std::pair<int, int>, std::vector<std::pair<int, int>>> joined;
  for (const auto& [edge, ts] : edge_triangles) {
    if (ts.size() == 2) {
      joined[edge].emplace_back(ts[0], ts[1]);
      continue;
    }
    joined[edge] = wedge_pairs(vertices, before, edge, ts);
  }
  std::vector<std::vector<int>> around(vertices.size());
  for (std::size_t t = 0; t < before.size(); ++t)
    for (int i = 0; i < 3; ++i) around[static_cast<std::size_t>(before[t](i))].push_back(static_cast<int>(t));
  const std::size_t original = vertices.size();
  std::vector<int> split;  // every vertex that got copies, and its copies
  for (std::size_t v = 0; v < original; ++v) {
    const auto& ts = around[v];
    if (ts.size() < 2) continue;
    std::map<int, int> slot;  // triangle → its index in ts
    for (std::size_t i = 0; i < ts.size(); ++i) slot[ts[i]] = static_cast<int>(i);
    detail::UnionFind sheets(ts.size());
    for (int t : ts)
      for (int i = 0; i < 3; ++i) {
        const int x = before[static_cast<std::size_t>(t)](i);
        if (x == static_cast<int>(v)) continue;
        for (const auto& [p, q] : joined[{std::min<int>(static_cast<int>(v), x), std::max<int>(static_cast<int>(v), x)}])
          sheets.unite(slot[p], slot[q]);
      }
    std::map<int, int> copy_of_sheet;  // root → vertex index
    const std::size_t copies_before = vertices.size();
    for (std::size_t i = 0; i < ts.size(); ++i) {
      const int root = sheets.find(static_cast<int>(i));
      auto [it, inserted] = copy_of_sheet.try_emplace(root, -1);
      if (inserted) {
        it->second = copy_of_sheet.size() == 1 ? static_cast<int>(v) : static_cast<int>(vertices.size());
        if (it->second != static_cast<int>(v)) vertices.push_back(vertices[v]);
      }
      auto& t = triangles[static_cast<std::size_t>(ts[i])];
      for (int p = 0; p < 3; ++p)
        if (before[static_cast<std::size_t>(ts[i])](p) == static_cast<int>(v)) t(p) = it->second;
    }
    if (vertices.size() > copies_before) {
      split.push_back(static_cast<int>(v));
      for (std::size_t c = copies_before; c < vertices.size(); ++c) split.push_back(static_cast<int>(c));
    }
  }
  // Edges still pinched: their sheets join round both ends, so no copy of an end parts them.
  // Each sheet's pair of triangles round the edge gets its own vertex at the edge's midpoint,
  // both triangles split there, and the midpoints move into their sheets' sides like the copies.
  std::map<std::pair<int, int>, std::vector<int>> now;
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int i = 0; i < 3; ++i) {
      const int a = triangles[t](i), b = triangles[t]((i + 1) % 3);
      now[{std::min(a, b), std::max(a, b)}].push_back(static_cast<int>(t));
    }
  for (const auto& [edge, ts] : now) {
    // A short pinched edge is left to collapse_short_edges, which removes it with its fins.
    if (ts.size() <= 2 || (vertices[static_cast<std::size_t>(edge.first)] - vertices[static_cast<std::size_t>(edge.second)]).norm() < 10.0 * separation)
      continue;
    const auto pairs = wedge_pairs(vertices, triangles, edge, ts);
    const auto side_of = [&](int t) {  // the triangle's corner where the edge starts, or −1
      for (int i = 0; i < 3; ++i) {
        const int x = triangles[static_cast<std::size_t>(t)](i), y = triangles[static_cast<std::size_t>(t)]((i + 1) % 3);
        if (std::min(x, y) == edge.first && std::max(x, y) == edge.second) return i;
      }
      return -1;
    };
    // A triangle split for another pinched edge no longer has this one: the edge is left as it
    // is rather than split on one side only, which would open it.
    if (std::any_of(pairs.begin(), pairs.end(), [&](const auto& pq) { return side_of(pq.first) < 0 || side_of(pq.second) < 0; }))
      continue;
    for (const auto& [p, q] : pairs) {
      const int m = static_cast<int>(vertices.size());
      vertices.push_back(0.5 * (vertices[static_cast<std::size_t>(edge.first)] + vertices[static_cast<std::size_t>(edge.second)]));
      for (int t : {p, q}) {
        // (x, y, c) → (x, m, c) and (m, y, c): the same winding.
        const int i = side_of(t);
        Eigen::Vector3i& tri = triangles[static_cast<std::size_t>(t)];
        const int y = tri((i + 1) % 3), c = tri((i + 2) % 3);
        tri((i + 1) % 3) = m;
        triangles.emplace_back(m, y, c);
        triangle_crack.push_back(triangle_crack[static_cast<std::size_t>(t)]);
      }
      split.push_back(m);
    }
  }
  // Each copy's sheet: the area-weighted outward normal of its triangles; moved against it.
  std::vector<Eigen::Vector3d> normal(vertices.size(), Eigen::Vector3d::Zero());
  for (const auto& t : triangles) {
    const Eigen::Vector3d n = (vertices[static_cast<std::size_t>(t(1))] - vertices[static_cast<std::size_t>(t(0))])
                                  .cross(vertices[static_cast<std::size_t>(t(2))] - vertices[static_cast<std::size_t>(t(0))]);
    for (int i = 0; i < 3; ++i) normal[static_cast<std::size_t>(t(i))] += n;
  }
  for (int c : split) {
    const Eigen::Vector3d& n = normal[static_cast<std::size_t>(c)];
    if (n.norm() > 0.0) vertices[static_cast<std::size_t>(c)] -= separation * n.normalized();
  }
  return {separation, split};
}

// Whether an edge has other than two triangles: most fragments have none, and skip unpinch().
bool has_pinched_edge(const std::vector<Eigen::Vector3i>& triangles) {
  std::vector<std::uint64_t> edges;
  edges.reserve(3 * triangles.size());
  for (const auto& t : triangles)
    for (int i = 0; i < 3; ++i) {
      const auto a = static_cast<std::uint32_t>(t(i)), b = static_cast<std::uint32_t>(t((i + 1) % 3));
      edges.push_back(static_cast<std::uint64_t>(std::min(a, b)) << 32 | std::max(a, b));
    }
  std::sort(edges.begin(), edges.end());
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    if (j - i != 2) return true;
    i = j;
  }
  return false;
}

// Whether every directed edge is used as often as its reverse: closed and consistently wound.
bool balanced(const std::vector<Eigen::Vector3i>& triangles) {
  std::map<std::pair<int, int>, int> directed;
  for (const auto& t : triangles)
    for (int i = 0; i < 3; ++i) ++directed[{t(i), t((i + 1) % 3)}];
  for (const auto& [e, count] : directed) {
    const auto it = directed.find({e.second, e.first});
    if (it == directed.end() || it->second != count) return false;
  }
  return true;
}

// Edges shorter than 3e-7 of the fragment's size are collapsed into their lower-numbered end,
// with their two triangles. Such edges come from cracks crossing within round-off of a tet edge;
// float32, which glTF, PLY and Blender store, resolves 1.2e-7 of the size at best, so readers
// would merge their ends and drop the triangles, opening the surface. An edge is collapsed only
// when its ends share no neighbour but its two opposite vertices (the link condition), which
// keeps a closed 2-manifold one. The volume changes by at most the edge's length times the area
// round the end that moves. Unused vertices are removed. Returns the new index of every vertex
// (−1: removed), and adds each surviving end of a collapsed edge to `moved`.
std::vector<int> collapse_short_edges(std::vector<Eigen::Vector3d>& vertices, std::vector<Eigen::Vector3i>& triangles,
                                      std::vector<int>& triangle_crack, std::vector<int>& moved, double& max_move) {
  std::vector<int> index(vertices.size());
  std::iota(index.begin(), index.end(), 0);
  if (vertices.empty()) return index;
  Eigen::Vector3d low = vertices[0], high = vertices[0];
  for (const auto& x : vertices) {
    low = low.cwiseMin(x);
    high = high.cwiseMax(x);
  }
  // Files without a node origin (OBJ, PLY) store world coordinates: their float32 steps grow
  // with the distance from the world's origin.
  const double shortest = 3e-7 * std::max((high - low).norm(), high.cwiseAbs().cwiseMax(low.cwiseAbs()).maxCoeff());
  std::vector<std::tuple<double, int, int>> short_edges;
  const auto find_short_edges = [&](const std::vector<bool>& alive) {
    short_edges.clear();
    for (std::size_t k = 0; k < triangles.size(); ++k) {
      if (!alive[k]) continue;
      const auto& t = triangles[k];
      for (int i = 0; i < 3; ++i) {
        const int a = t(i), b = t((i + 1) % 3);
        const double length = (vertices[static_cast<std::size_t>(a)] - vertices[static_cast<std::size_t>(b)]).norm();
        if (a < b && length < shortest) short_edges.emplace_back(length, a, b);
      }
    }
    std::sort(short_edges.begin(), short_edges.end());
    return !short_edges.empty();
  };
  std::vector<bool> alive(triangles.size(), true);
  find_short_edges(alive);
  // The triangles round each vertex, built only when there is an edge to collapse (most
  // fragments have none, and a list per vertex is the allocator's work).
  std::vector<std::vector<int>> around;
  if (!short_edges.empty()) {
    around.resize(vertices.size());
    for (std::size_t t = 0; t < triangles.size(); ++t)
      for (int i = 0; i < 3; ++i) around[static_cast<std::size_t>(triangles[t](i))].push_back(static_cast<int>(t));
  }
  const auto neighbours = [&](int v) {
    std::vector<int> out;
    for (int t : around[static_cast<std::size_t>(v)])
      if (alive[static_cast<std::size_t>(t)])
        for (int i = 0; i < 3; ++i)
          if (triangles[static_cast<std::size_t>(t)](i) != v) out.push_back(triangles[static_cast<std::size_t>(t)](i));
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  };
  // A collapse can leave a new short edge where three or more ends lay together: passes until
  // none is left or none can go.
  for (bool collapsed = true; collapsed && !short_edges.empty(); collapsed = collapsed && find_short_edges(alive)) {
    collapsed = false;
    for (const auto& [length, a, b] : short_edges) {
      // Still an edge (earlier collapses may have removed or lengthened it), with two triangles.
      std::vector<int> shared, opposite;
      for (int t : around[static_cast<std::size_t>(a)]) {
        if (!alive[static_cast<std::size_t>(t)]) continue;
        const auto& tri = triangles[static_cast<std::size_t>(t)];
        if (tri(0) != b && tri(1) != b && tri(2) != b) continue;
        shared.push_back(t);
        for (int i = 0; i < 3; ++i)
          if (tri(i) != a && tri(i) != b) opposite.push_back(tri(i));
      }
      if (shared.size() != 2 || opposite[0] == opposite[1]) continue;
      const double now = (vertices[static_cast<std::size_t>(a)] - vertices[static_cast<std::size_t>(b)]).norm();
      if (!(now < shortest)) continue;
      std::vector<int> common;
      const auto na = neighbours(a), nb = neighbours(b);
      std::set_intersection(na.begin(), na.end(), nb.begin(), nb.end(), std::back_inserter(common));
      std::sort(opposite.begin(), opposite.end());
      if (common != opposite) continue;
      for (int t : shared) alive[static_cast<std::size_t>(t)] = false;
      moved.push_back(a);
      max_move = std::max(max_move, now);
      collapsed = true;
      for (int t : around[static_cast<std::size_t>(b)]) {
        if (!alive[static_cast<std::size_t>(t)]) continue;
        auto& tri = triangles[static_cast<std::size_t>(t)];
        for (int i = 0; i < 3; ++i)
          if (tri(i) == b) tri(i) = a;
        around[static_cast<std::size_t>(a)].push_back(t);
      }
      around[static_cast<std::size_t>(b)].clear();
    }
  }
  // Two triangles on the same three vertices, wound opposite ways, enclose nothing: a fin left
  // where a short edge could not go (its two triangles shared their third vertex). Readers drop
  // one of a duplicate pair, which would open the surface; both go, which keeps every edge's
  // uses balanced.
  std::vector<std::pair<std::array<int, 3>, int>> keyed;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    if (!alive[t]) continue;
    std::array<int, 3> key = {triangles[t](0), triangles[t](1), triangles[t](2)};
    std::sort(key.begin(), key.end());
    keyed.emplace_back(key, static_cast<int>(t));
  }
  std::sort(keyed.begin(), keyed.end());
  const auto winding = [&](int t) {  // +1 or −1: whether the triangle lists its sorted key cyclically
    const auto& tri = triangles[static_cast<std::size_t>(t)];
    const int lowest = static_cast<int>(std::min_element(tri.data(), tri.data() + 3) - tri.data());
    return tri((lowest + 1) % 3) < tri((lowest + 2) % 3) ? 1 : -1;
  };
  for (std::size_t i = 0; i + 1 < keyed.size(); ++i)
    if (keyed[i].first == keyed[i + 1].first && winding(keyed[i].second) != winding(keyed[i + 1].second)) {
      alive[static_cast<std::size_t>(keyed[i].second)] = false;
      alive[static_cast<std::size_t>(keyed[i + 1].second)] = false;
      ++i;
    }
  std::fill(index.begin(), index.end(), -1);
  std::vector<Eigen::Vector3d> kept_vertices;
  std::vector<Eigen::Vector3i> kept_triangles;
  std::vector<int> kept_cracks;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    if (!alive[t]) continue;
    Eigen::Vector3i tri = triangles[t];
    for (int i = 0; i < 3; ++i) {
      int& k = index[static_cast<std::size_t>(tri(i))];
      if (k < 0) {
        k = static_cast<int>(kept_vertices.size());
        kept_vertices.push_back(vertices[static_cast<std::size_t>(tri(i))]);
      }
      tri(i) = k;
    }
    kept_triangles.push_back(tri);
    kept_cracks.push_back(triangle_crack[t]);
  }
  vertices = std::move(kept_vertices);
  triangles = std::move(kept_triangles);
  triangle_crack = std::move(kept_cracks);
  return index;
}

// One fragment's polygons → a closed triangle mesh: vertices welded, every vertex lying on
// another polygon's edge inserted into that edge (a crack that ends at a tet face splits the
// faces on one side of it and not on the other), convex polygons fanned.
FragmentMesh triangulate(const std::vector<Emitted>& polygons, double tolerance) {
  std::size_t corners = 0;
  for (const Emitted& e : polygons) corners += e.polygon.size();
  VertexWelder welder(tolerance, corners / 2);
  std::vector<std::vector<int>> loops;
  std::vector<int> cracks;
  for (const Emitted& e : polygons) {
    std::vector<int> loop;
    for (const auto& x : e.polygon) {
      const int v = welder.index(x);
      if (loop.empty() || loop.back() != v) loop.push_back(v);
    }
    while (loop.size() > 1 && loop.front() == loop.back()) loop.pop_back();
    if (loop.size() < 3) continue;
    loops.push_back(std::move(loop));
    cracks.push_back(e.crack);
  }
  const auto& points = welder.points();
  // Vertices by grid cell of twice the mean edge length, to find those on an edge (cells of the
  // longest edge's size held most of a fragment's vertices: fragments are a few tets across).
  // The test is exact on the cells' superset, so the cell size changes only the time.
  double edge_sum = 0.0;
  std::size_t edge_count = 0;
  for (const auto& loop : loops)
    for (std::size_t i = 0; i < loop.size(); ++i, ++edge_count)
      edge_sum += (points[static_cast<std::size_t>(loop[i])] - points[static_cast<std::size_t>(loop[(i + 1) % loop.size()])]).norm();
  const double cell = std::max(4.0 * tolerance, 2.0 * edge_sum / static_cast<double>(std::max<std::size_t>(edge_count, 1)));
  detail::PointGrid grid(cell, points.size());
  for (std::size_t v = 0; v < points.size(); ++v) grid.add(static_cast<int>(v), points[v]);

  FragmentMesh out;
  std::vector<Eigen::Vector3d> vertices = points;
  std::vector<Eigen::Vector3i> triangles;
  std::vector<std::pair<double, int>> on_edge;
  for (std::size_t l = 0; l < loops.size(); ++l) {
    const auto& loop = loops[l];
    std::vector<int> ring;
    bool inserted = false;
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const int a = loop[i], b = loop[(i + 1) % loop.size()];
      ring.push_back(a);
      const Eigen::Vector3d pa = points[static_cast<std::size_t>(a)], pb = points[static_cast<std::size_t>(b)];
      const Eigen::Vector3d ab = pb - pa;
      const double len2 = ab.squaredNorm();
      on_edge.clear();
      const auto visit = [&](int c) {
        if (c == a || c == b) return;
        const Eigen::Vector3d pc = points[static_cast<std::size_t>(c)];
        const double s = (pc - pa).dot(ab) / len2;
        if (s > 0.0 && s < 1.0 && (pa + s * ab - pc).norm() <= tolerance) on_edge.emplace_back(s, c);
      };
      grid.visit_box(pa.cwiseMin(pb) - Eigen::Vector3d::Constant(tolerance),
                     pa.cwiseMax(pb) + Eigen::Vector3d::Constant(tolerance), visit);
      std::sort(on_edge.begin(), on_edge.end());
      for (const auto& [s, c] : on_edge) ring.push_back(c);
      inserted = inserted || !on_edge.empty();
    }
    const int crack = cracks[l];
    if (!inserted && ring.size() == 3) {
      triangles.emplace_back(ring[0], ring[1], ring[2]);
      out.triangle_crack.push_back(crack);
      continue;
    }
    // A fan from the polygon's centre: no triangle degenerates on points inserted along an edge.
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (int v : ring) centre += vertices[static_cast<std::size_t>(v)];
    centre /= static_cast<double>(ring.size());
    const int c = static_cast<int>(vertices.size());
    vertices.push_back(centre);
    for (std::size_t i = 0; i < ring.size(); ++i) {
      triangles.emplace_back(c, ring[i], ring[(i + 1) % ring.size()]);
      out.triangle_crack.push_back(crack);
    }
  }
  std::vector<int> moved;
  double max_move = 0.0;
  if (has_pinched_edge(triangles)) {
    // Kept only where it leaves every edge with as many triangles each way (the input has that
    // by construction): a fan of coplanar faces round one edge can defeat the angular pairing.
    std::vector<Eigen::Vector3d> v = vertices;
    std::vector<Eigen::Vector3i> t = triangles;
    std::vector<int> crack_of = out.triangle_crack;
    auto [separation, separated] = unpinch(v, t, crack_of);
    if (balanced(t)) {
      vertices = std::move(v);
      triangles = std::move(t);
      out.triangle_crack = std::move(crack_of);
      moved = std::move(separated);
      max_move = separation;
    }
  }
  // After unpinch: the sheets' copies are then apart, and the short edges round them manifold.
  const std::vector<int> index = collapse_short_edges(vertices, triangles, out.triangle_crack, moved, max_move);
  for (int v : moved)
    if (index[static_cast<std::size_t>(v)] >= 0) out.moved_vertices.push_back(index[static_cast<std::size_t>(v)]);
  std::sort(out.moved_vertices.begin(), out.moved_vertices.end());
  out.moved_vertices.erase(std::unique(out.moved_vertices.begin(), out.moved_vertices.end()), out.moved_vertices.end());
  out.max_move = max_move;
  out.vertices.resize(static_cast<Eigen::Index>(vertices.size()), 3);
  for (std::size_t i = 0; i < vertices.size(); ++i) out.vertices.row(static_cast<Eigen::Index>(i)) = vertices[i].transpose();
  out.triangles.resize(static_cast<Eigen::Index>(triangles.size()), 3);
  double six_v = 0.0;
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  const Eigen::Vector3d r = vertices.empty() ? Eigen::Vector3d::Zero() : vertices[0];
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    out.triangles.row(static_cast<Eigen::Index>(i)) = triangles[i].transpose();
    const Eigen::Vector3d a = vertices[static_cast<std::size_t>(triangles[i](0))] - r,
                          b = vertices[static_cast<std::size_t>(triangles[i](1))] - r,
                          c = vertices[static_cast<std::size_t>(triangles[i](2))] - r;
    const double v = a.dot(b.cross(c));
    six_v += v;
    moment += v * (a + b + c) / 4.0;
  }
  out.volume = six_v / 6.0;
  out.centre = six_v != 0.0 ? Eigen::Vector3d(r + moment / six_v) : r;
  return out;
}

}  // namespace

std::vector<FragmentMesh> mesh_fragments(const TetMesh& mesh, const std::vector<CrackSurface>& cracks,
                                         int crack_count, int threads) {
  crack_count = std::clamp(crack_count, 0, static_cast<int>(cracks.size()));
  const int n = mesh.tet_count();
  const auto box = mesh.bounding_box();
  const double diagonal = (box.row(1) - box.row(0)).norm();
  detail::TetPieceOptions options;
  // Crack values are lengths (signed distances plus noise), snapped ≥ 1e-6 h away from zero at
  // nodes: a plane within 1e-12 of the body's size of a point passes through it.
  options.on_plane = 1e-12 * diagonal;
  const double weld = 1e-10 * diagonal;
  // The simulation keeps every node at least 1e-6 h off every crack (paper-gaps §3), so where a
  // crack passes that close to a node the pieces around it are 1e-6 h thin, and their faces'
  // overlaps are decided by round-off (an open seam of 1e-8 m edges on a 30 cm tile). For the
  // meshes those crack values are moved out to 1e-5 of the body's size: the crack moves by at
  // most that near such a node, every node stays on its side, so the pieces, labels and volumes
  // are unchanged but for that shift.
  const detail::TetCutIndex index(n, cracks, crack_count, 1e-5 * diagonal);

  const auto tet_nodes = [&](int t) {
    Eigen::Matrix<double, 4, 3> p;
    for (int i = 0; i < 4; ++i) p.row(i) = mesh.nodes().row(mesh.tets()(t, i));
    return p;
  };
  // Pieces of cut tets (uncut tets are one piece, the tet); piece ids run tet by tet.
  std::vector<std::vector<TetPiece>> pieces(static_cast<std::size_t>(n));
  parallel_for(static_cast<std::size_t>(n), threads, [&](std::size_t t) {
    const auto cuts = index.of(static_cast<int>(t));
    if (cuts.empty()) return;
    detail::TetPieceOptions mine_options = options;
    std::iota(mine_options.node_order.begin(), mine_options.node_order.end(), 0);
    std::sort(mine_options.node_order.begin(), mine_options.node_order.end(),
              [&](int a, int b) { return mesh.tets()(static_cast<Eigen::Index>(t), a) < mesh.tets()(static_cast<Eigen::Index>(t), b); });
    auto& mine = pieces[t];
    mine = detail::tet_pieces(tet_nodes(static_cast<int>(t)), cuts, mine_options);
    for (TetPiece& p : mine)
      for (PieceFace& f : p.faces) f.weights = {};  // only the construction needs them
  });
  std::vector<int> first_piece(static_cast<std::size_t>(n) + 1, 0);
  for (int t = 0; t < n; ++t) {
    // An uncut tet, or one whose cuts are too thin to part anything, is one piece.
    const int count = std::max<int>(1, static_cast<int>(pieces[static_cast<std::size_t>(t)].size()));
    first_piece[static_cast<std::size_t>(t) + 1] = first_piece[static_cast<std::size_t>(t)] + count;
  }
  const auto cut = [&](int t) { return !pieces[static_cast<std::size_t>(t)].empty(); };
  const auto piece_id = [&](int t, std::size_t i) { return first_piece[static_cast<std::size_t>(t)] + static_cast<int>(i); };
  // Each piece's part of the tet's four faces (null where it has none), looked up in the joins
  // below instead of scanning its faces, which are large.
  std::vector<std::array<const PieceFace*, 4>> piece_tet_faces(static_cast<std::size_t>(first_piece.back()),
                                                               {nullptr, nullptr, nullptr, nullptr});
  for (int t = 0; t < n; ++t) {
    const auto& mine = pieces[static_cast<std::size_t>(t)];
    for (std::size_t i = 0; i < mine.size(); ++i)
      for (const PieceFace& f : mine[i].faces)
        if (f.kind == PieceFaceKind::TetFace) piece_tet_faces[static_cast<std::size_t>(piece_id(t, i))][static_cast<std::size_t>(f.index)] = &f;
  }
  const auto tet_face_of = [&](int t, std::size_t i, int f) {
    return piece_tet_faces[static_cast<std::size_t>(piece_id(t, i))][static_cast<std::size_t>(f)];
  };
  // Polygons overlap with positive area, not a touch along an edge: more than round-off of the
  // smaller one's area, and more than the faces tet_pieces keeps (1e-20 of an element's size²).
  const double element = std::cbrt(8.5 * mesh.total_volume() / std::max(1, n));  // a regular tet's edge
  const double area_floor = 1e-20 * element * element;
  // Round-off of a coordinate on a shared plane (~1e-16 of the body's size) and far below any
  // real gap between faces.
  const double box_slack = 1e-12 * diagonal;
  const auto shared_area = [&](const Polygon& a, const Polygon& b, double common) {
    return common > std::max(area_floor, 1e-9 * std::min(polygon_area(a), polygon_area(b)));
  };
  const auto overlaps = [&](const Polygon& a, const Polygon& b) {
    return !boxes_apart(a, b, box_slack) && shared_area(a, b, polygon_area(intersect(a, b)));
  };

  detail::UnionFind sets(static_cast<std::size_t>(first_piece.back()));
  for (int t = 0; t < n; ++t) {
    const auto& mine = pieces[static_cast<std::size_t>(t)];
    // Pieces on either side of an open face are one.
    for (std::size_t i = 0; i < mine.size(); ++i)
      for (const PieceFace& f : mine[i].faces) {
        if (f.kind != PieceFaceKind::Open) continue;
        for (std::size_t j = i + 1; j < mine.size(); ++j) {
          const PieceFace* g = face_on(mine[j], PieceFaceKind::Open, f.index);
          if (g && overlaps(f.points, g->points)) sets.unite(piece_id(t, i), piece_id(t, j));
        }
      }
    for (int f = 0; f < 4; ++f) {
      const int u = mesh.neighbours()(t, f);
      if (u < t) continue;
      const int g = mesh.neighbour_faces()(t, f);
      if (!cut(t) && !cut(u)) {
        sets.unite(piece_id(t, 0), piece_id(u, 0));
        continue;
      }
      if (!cut(t) || !cut(u)) {
        // The uncut side's face is whole: every piece of the other side touching it joins it.
        const int whole = cut(t) ? u : t, split = cut(t) ? t : u, face = cut(t) ? f : g;
        const auto& theirs = pieces[static_cast<std::size_t>(split)];
        for (std::size_t j = 0; j < theirs.size(); ++j)
          if (tet_face_of(split, j, face)) sets.unite(piece_id(whole, 0), piece_id(split, j));
        continue;
      }
      const auto& theirs = pieces[static_cast<std::size_t>(u)];
      for (std::size_t i = 0; i < mine.size(); ++i) {
        const PieceFace* a = tet_face_of(t, i, f);
        if (!a) continue;
        for (std::size_t j = 0; j < theirs.size(); ++j) {
          const PieceFace* b = tet_face_of(u, j, g);
          if (b && overlaps(a->points, b->points)) sets.unite(piece_id(t, i), piece_id(u, j));
        }
      }
    }
  }

  // An uncut tet's faces, wound outward.
  const auto tet_face = [&](int t, int f) {
    const auto p = tet_nodes(t);
    Polygon face;
    for (int i : TetMesh::kLocalFaces[static_cast<std::size_t>(f)]) face.push_back(p.row(i).transpose());
    const Eigen::Vector3d inner = p.colwise().mean().transpose();
    if (polygon_area_vector(face).dot(face[0] - inner) < 0.0) std::reverse(face.begin(), face.end());
    return face;
  };
  // Debris: where three cracks meet within round-off of each other (at a corner, say) the
  // construction can leave a fragment a few 1e-8 of the body across. Its edges are below what
  // float32 files resolve (collapse_short_edges' 3e-7 of the coordinates), so its mesh and its
  // neighbours' faces on it would be collapsed open; it joins the neighbour it shares the most
  // crack area with, and the fragments are assigned again (a pass only when there is debris).
  const double debris_size = 3e-6 * std::max(diagonal, box.cwiseAbs().maxCoeff());
  // Dust: a fragment of less than kDustPerElement of a mean element's volume is below what the
  // mesh resolves (a crack clipping a tet's corner cuts it off), not a shard the simulation
  // predicts; it joins its neighbour as debris does. Left alone, 50 of the 299 fragments of the
  // README's street run were under 1 mm³, down to 3e-15 m³.
  const double dust_volume = kDustPerElement * mesh.total_volume() / std::max(1, n);
  std::vector<double> piece_volumes(sets.size(), 0.0);
  for (int t = 0; t < n; ++t) {
    if (!cut(t)) {
      piece_volumes[static_cast<std::size_t>(piece_id(t, 0))] = mesh.volumes()(t);
      continue;
    }
    const auto& mine = pieces[static_cast<std::size_t>(t)];
    for (std::size_t i = 0; i < mine.size(); ++i) piece_volumes[static_cast<std::size_t>(piece_id(t, i))] = detail::piece_volume(mine[i]);
  }
  std::vector<int> fragment_of_piece(sets.size()), first_tet, representative;
  std::vector<double> fragment_volume;
  std::vector<std::vector<Emitted>> emitted;
  std::vector<std::map<int, double>> contact_area;
  for (bool again = true; again;) {
    // Fragments in order of their lowest piece (the union-find root), hence of their lowest tet.
    std::vector<int> fragment_of_root(sets.size(), -1);
    first_tet.clear();
    representative.clear();
    for (int t = 0; t < n; ++t) {
      for (int id = first_piece[static_cast<std::size_t>(t)]; id < first_piece[static_cast<std::size_t>(t) + 1]; ++id) {
        const int root = sets.find(id);
        if (fragment_of_root[static_cast<std::size_t>(root)] < 0) {
          fragment_of_root[static_cast<std::size_t>(root)] = static_cast<int>(first_tet.size());
          first_tet.push_back(t);
          representative.push_back(id);
        }
        fragment_of_piece[static_cast<std::size_t>(id)] = fragment_of_root[static_cast<std::size_t>(root)];
      }
    }
    fragment_volume.assign(first_tet.size(), 0.0);
    for (std::size_t id = 0; id < piece_volumes.size(); ++id)
      fragment_volume[static_cast<std::size_t>(fragment_of_piece[id])] += piece_volumes[id];

    emitted.assign(first_tet.size(), {});
    contact_area.assign(first_tet.size(), {});
    for (int t = 0; t < n; ++t) {
      if (!cut(t)) {
        for (int f = 0; f < 4; ++f)
          if (mesh.neighbours()(t, f) < 0) emitted[static_cast<std::size_t>(fragment_of_piece[static_cast<std::size_t>(piece_id(t, 0))])].push_back({tet_face(t, f), -1});
        continue;
      }
      const auto& mine = pieces[static_cast<std::size_t>(t)];
      for (std::size_t i = 0; i < mine.size(); ++i) {
        const int fragment = fragment_of_piece[static_cast<std::size_t>(piece_id(t, i))];
        auto& out = emitted[static_cast<std::size_t>(fragment)];
        for (const PieceFace& face : mine[i].faces) {
          if (face.kind == PieceFaceKind::TetFace) {
            if (mesh.neighbours()(t, face.index) < 0) out.push_back({face.points, -1});
          } else if (face.kind == PieceFaceKind::Crack) {
            // The crack between this piece and each piece across it of another fragment.
            for (std::size_t j = 0; j < mine.size(); ++j) {
              if (j == i || fragment_of_piece[static_cast<std::size_t>(piece_id(t, j))] == fragment) continue;
              const PieceFace* across = face_on(mine[j], PieceFaceKind::Crack, face.index);
              if (!across || boxes_apart(face.points, across->points, box_slack)) continue;
              Polygon common = intersect(face.points, across->points);
              // Against the smaller polygon: a sliver across a large face is real.
              const double common_area = polygon_area(common);
              if (shared_area(face.points, across->points, common_area)) {
                contact_area[static_cast<std::size_t>(fragment)][fragment_of_piece[static_cast<std::size_t>(piece_id(t, j))]] += common_area;
                out.push_back({std::move(common), face.index});
              }
            }
          }
        }
      }
    }

    again = false;
    for (std::size_t k = 0; k < emitted.size(); ++k) {
      if (contact_area[k].empty() || emitted[k].empty()) continue;
      Eigen::Vector3d low = emitted[k][0].polygon[0], high = low;
      for (const Emitted& e : emitted[k])
        for (const auto& x : e.polygon) {
          low = low.cwiseMin(x);
          high = high.cwiseMax(x);
        }
      if ((high - low).norm() >= debris_size && fragment_volume[k] >= dust_volume) continue;
      const auto largest = std::max_element(contact_area[k].begin(), contact_area[k].end(),
                                            [](const auto& x, const auto& y) { return x.second < y.second; });
      sets.unite(representative[k], representative[static_cast<std::size_t>(largest->first)]);
      again = true;
    }
  }

  std::vector<FragmentMesh> fragments(emitted.size());
  parallel_for(emitted.size(), threads, [&](std::size_t k) { fragments[k] = triangulate(emitted[k], weld); });
  for (std::size_t k = 0; k < emitted.size(); ++k) {
    FragmentMesh& f = fragments[k];
    f.first_tet = first_tet[k];
    for (const Emitted& e : emitted[k])
      if (e.crack >= 0) {
        const double time = cracks[static_cast<std::size_t>(e.crack)].time;
        if (f.crack_onset_time < 0.0 || time < f.crack_onset_time) f.crack_onset_time = time;
      }
    for (const auto& [other, area] : contact_area[k]) f.contacts.push_back({other, area});
  }
  return fragments;
}

}  // namespace fissure
