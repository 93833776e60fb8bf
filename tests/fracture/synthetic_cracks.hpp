#pragma once
// Cracks with known geometry for the fracture tests: planes evaluated at the mesh's nodes, laid
// out as the simulation lays out its cracks (CrackSurface: cuts with S_k's node values, T-junction
// clipping by an earlier crack), so the stages after the simulation can be tested against exact
// answers without running it.

#include "fissure/base/rng.hpp"
#include "fissure/fracture/crack_surface.hpp"
#include "fissure/mesh/tet_mesh.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

namespace fissure::test {

/// A planar crack S(x) = n̂·(x − point), n̂ = normal / |normal|.
struct PlaneCrack {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  /// Earlier cracks (indices) it ends on, T-junction style: it exists only on the side of each
  /// that `point` is on. In a tet that such a crack cuts, the cut is clipped by it when its
  /// polygon reaches the far side (CrackCut::clipped_by; at most one: see make_cut); elsewhere a
  /// tet is kept when its polygon reaches that side.
  std::vector<int> stop_on;
  /// When set, only tets whose centroid satisfies it (a partial crack: it ends where the region
  /// does).
  std::function<bool(const Eigen::Vector3d&)> region;
  /// When set, added to S (metres): a curved crack, like the simulation's noisy planes. The
  /// stop_on sides of later cracks are still judged by this crack's plane, so give an offset only
  /// to cracks nothing stops on.
  std::function<double(const Eigen::Vector3d&)> offset;

  // A constructor, not aggregate initialisation, so that a brace list may stop after any member.
  PlaneCrack(const Eigen::Vector3d& normal_ = Eigen::Vector3d::UnitX(),
             const Eigen::Vector3d& point_ = Eigen::Vector3d::Zero(), std::vector<int> stop_on_ = {},
             std::function<bool(const Eigen::Vector3d&)> region_ = {},
             std::function<double(const Eigen::Vector3d&)> offset_ = {})
      : normal(normal_), point(point_), stop_on(std::move(stop_on_)), region(std::move(region_)),
        offset(std::move(offset_)) {}
};

/// Mesh scale for the snapping rule of CrackCut (values within 1e-6·h of zero move off it): the
/// edge of a cube holding one tet's volume, times 6^(1/3) (the structured box's cube edge).
inline double crack_snap_length(const TetMesh& mesh) {
  return std::cbrt(6.0 * mesh.total_volume() / std::max(1, mesh.tet_count()));
}

/// S(x) = n̂·(x − point) (+ offset(x)) at the nodes of tet `t`, snapped off zero as the
/// simulation does.
inline std::array<double, 4> plane_node_values(const TetMesh& mesh, int t, const Eigen::Vector3d& unit_normal,
                                               const Eigen::Vector3d& point,
                                               const std::function<double(const Eigen::Vector3d&)>& offset = {}) {
  const double snap = 1e-6 * crack_snap_length(mesh);
  std::array<double, 4> v{};
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector3d x = mesh.nodes().row(mesh.tets()(t, i)).transpose();
    double s = unit_normal.dot(x - point) + (offset ? offset(x) : 0.0);
    if (std::abs(s) < snap) s = s < 0.0 ? -snap : snap;
    v[static_cast<std::size_t>(i)] = s;
  }
  return v;
}

/// Appends `spec` to `cracks` as crack number cracks.size() (id, time = id, origin = point,
/// normal = n̂) and returns that number. Its cuts are the tets the plane crosses (a sign change at
/// their nodes) that the region and the stop_on sides allow, flooded breadth-first over face
/// neighbours from the allowed tet whose centroid is nearest `point` (so cuts[0] is the origin and
/// a region split in two keeps the part around the point); a clipped cut whose clipped polygon is
/// empty is dropped. stopped_on and area are filled in. O(#tets).
inline int add_plane_crack(const TetMesh& mesh, std::vector<CrackSurface>& cracks, const PlaneCrack& spec) {
  const Eigen::Vector3d n = spec.normal.normalized();
  CrackSurface crack;
  crack.id = static_cast<int>(cracks.size());
  crack.time = crack.id;
  crack.origin = spec.point;
  crack.normal = n;
  // Each earlier crack's cut of each tet, and the side of it the point is on.
  std::vector<std::vector<int>> cut_index(spec.stop_on.size(), std::vector<int>(static_cast<std::size_t>(mesh.tet_count()), -1));
  std::vector<double> side(spec.stop_on.size());
  for (std::size_t s = 0; s < spec.stop_on.size(); ++s) {
    const CrackSurface& j = cracks[static_cast<std::size_t>(spec.stop_on[s])];
    for (std::size_t c = 0; c < j.cuts.size(); ++c) cut_index[s][static_cast<std::size_t>(j.cuts[c].tet)] = static_cast<int>(c);
    side[s] = j.normal.dot(spec.point - j.origin) >= 0.0 ? 1.0 : -1.0;
  }
  auto nodes_of = [&](int t) {
    Eigen::Matrix<double, 4, 3> x;
    for (int i = 0; i < 4; ++i) x.row(i) = mesh.nodes().row(mesh.tets()(t, i));
    return x;
  };
  // The cut of tet t, or a cut with tet = −1 when the crack may not be there.
  auto make_cut = [&](int t) {
    CrackCut cut;
    cut.node_values = plane_node_values(mesh, t, n, spec.point, spec.offset);
    const auto [lo, hi] = std::minmax_element(cut.node_values.begin(), cut.node_values.end());
    const Eigen::Vector3d centroid = mesh.centroid(t);
    if (!(*lo < 0.0 && *hi > 0.0) || (spec.region && !spec.region(centroid))) return cut;
    // Stop cracks that cut this tet: the cut is clipped by the one the polygon runs into (at a
    // cell corner two may cut the tet, and the polygon usually crosses only one of them; when it
    // crosses several, by the one whose clipped polygon respects the others, else the first).
    // Stop cracks that do not cut it: the polygon must reach the arrival side.
    const std::vector<Eigen::Vector3d> polygon = crack_polygon(nodes_of(t), cut);
    auto outside = [&](const std::vector<Eigen::Vector3d>& poly, std::size_t s) {
      const CrackSurface& j = cracks[static_cast<std::size_t>(spec.stop_on[s])];
      const double tolerance = 1e-9 * crack_snap_length(mesh);
      return std::any_of(poly.begin(), poly.end(), [&](const Eigen::Vector3d& x) { return side[s] * j.normal.dot(x - j.origin) < -tolerance; });
    };
    std::vector<std::size_t> crossed;
    for (std::size_t s = 0; s < spec.stop_on.size(); ++s) {
      const CrackSurface& j = cracks[static_cast<std::size_t>(spec.stop_on[s])];
      if (cut_index[s][static_cast<std::size_t>(t)] < 0) {
        // Not cut by j: beyond the cell when the whole polygon is past j's plane. A polygon
        // straddling the plane is where j does not reach (its own end, at a cell corner), and
        // the centroid's side would open a gap there.
        const bool past = std::all_of(polygon.begin(), polygon.end(), [&](const Eigen::Vector3d& x) { return side[s] * j.normal.dot(x - j.origin) < 0.0; });
        if (past) return cut;
      } else if (outside(polygon, s)) {
        crossed.push_back(s);
      }
    }
    if (!crossed.empty()) {
      std::size_t chosen = crossed.front();
      for (const std::size_t s : crossed) {
        CrackCut trial = cut;
        trial.clipped_by = spec.stop_on[s];
        trial.clip_side = side[s] > 0.0 ? 1 : -1;
        const auto clipped = crack_polygon(nodes_of(t), trial, &cracks[static_cast<std::size_t>(spec.stop_on[s])].cuts[static_cast<std::size_t>(cut_index[s][static_cast<std::size_t>(t)])]);
        if (std::none_of(crossed.begin(), crossed.end(), [&](std::size_t o) { return o != s && outside(clipped, o); })) {
          chosen = s;
          break;
        }
      }
      cut.clipped_by = spec.stop_on[chosen];
      cut.clip_side = side[chosen] > 0.0 ? 1 : -1;
      const CrackSurface& j = cracks[static_cast<std::size_t>(cut.clipped_by)];
      if (crack_polygon(nodes_of(t), cut, &j.cuts[static_cast<std::size_t>(cut_index[chosen][static_cast<std::size_t>(t)])]).size() < 3) return cut;
    }
    cut.tet = t;
    return cut;
  };
  // Flood from the allowed tet nearest the point.
  std::vector<CrackCut> allowed(static_cast<std::size_t>(mesh.tet_count()));
  int start = -1;
  double best = INFINITY;
  for (int t = 0; t < mesh.tet_count(); ++t) {
    allowed[static_cast<std::size_t>(t)] = make_cut(t);
    const double d = (mesh.centroid(t) - spec.point).squaredNorm();
    if (allowed[static_cast<std::size_t>(t)].tet >= 0 && d < best) {
      best = d;
      start = t;
    }
  }
  if (start >= 0) {
    std::vector<char> seen(static_cast<std::size_t>(mesh.tet_count()), 0);
    std::vector<int> queue{start};
    seen[static_cast<std::size_t>(start)] = 1;
    for (std::size_t head = 0; head < queue.size(); ++head) {
      const int t = queue[head];
      crack.cuts.push_back(allowed[static_cast<std::size_t>(t)]);
      for (int f = 0; f < 4; ++f) {
        const int u = mesh.neighbours()(t, f);
        if (u < 0 || seen[static_cast<std::size_t>(u)] || allowed[static_cast<std::size_t>(u)].tet < 0) continue;
        seen[static_cast<std::size_t>(u)] = 1;
        queue.push_back(u);
      }
    }
  }
  crack.origin_tet = start;
  for (const CrackCut& cut : crack.cuts) {
    const CrackCut* clipping = nullptr;
    if (cut.clipped_by >= 0) {
      crack.stopped_on.push_back(cut.clipped_by);
      for (const CrackCut& c : cracks[static_cast<std::size_t>(cut.clipped_by)].cuts) {
        if (c.tet == cut.tet) clipping = &c;
      }
    }
    const std::vector<Eigen::Vector3d> polygon = crack_polygon(nodes_of(cut.tet), cut, clipping);
    Eigen::Vector3d twice = Eigen::Vector3d::Zero();
    for (std::size_t i = 1; i + 1 < polygon.size(); ++i) twice += (polygon[i] - polygon[0]).cross(polygon[i + 1] - polygon[0]);
    crack.area += 0.5 * twice.norm();
  }
  std::sort(crack.stopped_on.begin(), crack.stopped_on.end());
  crack.stopped_on.erase(std::unique(crack.stopped_on.begin(), crack.stopped_on.end()), crack.stopped_on.end());
  cracks.push_back(std::move(crack));
  return static_cast<int>(cracks.size()) - 1;
}

/// A hierarchical, T-dominated pattern like a drying or cracked tile (Shin et al.: fragments split
/// in two, nearly orthogonally to their long side): `count` vertical plane cracks over the
/// rectangle [lo, hi] of the xy-plane. Each splits the currently largest cell (ties: the oldest)
/// through a point near its centroid, across its longest extent turned by up to ±25°, and stops on
/// the cracks bounding that cell. On a face normal to z it leaves count + 1 fragments, all convex,
/// and T-junctions only (crossings and free ends only where a cell corner falls within a tet of
/// another crack's end). Seeded: the same cracks for the same seed. Appends to `cracks`.
inline void add_hierarchical_cracks(const TetMesh& mesh, std::vector<CrackSurface>& cracks, int count, std::uint64_t seed,
                                    const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) {
  struct Cell {
    std::vector<Eigen::Vector2d> corners;  // counter-clockwise
    std::vector<int> edge_crack;           // crack along corners[i] → corners[i+1], −1 on the border
  };
  auto area_of = [](const Cell& c) {
    double twice = 0.0;
    for (std::size_t i = 0; i < c.corners.size(); ++i) {
      const Eigen::Vector2d& a = c.corners[i];
      const Eigen::Vector2d& b = c.corners[(i + 1) % c.corners.size()];
      twice += a.x() * b.y() - a.y() * b.x();
    }
    return 0.5 * twice;
  };
  std::vector<Cell> cells{{{lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}}, {-1, -1, -1, -1}}};
  Rng rng = Rng::derive(seed, "hierarchical cracks");
  for (int n = 0; n < count; ++n) {
    std::size_t largest = 0;
    for (std::size_t c = 1; c < cells.size(); ++c) {
      if (area_of(cells[c]) > area_of(cells[largest])) largest = c;
    }
    const Cell cell = cells[largest];
    // Centroid and second moments of the corners: the long axis is the principal direction.
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();
    for (const Eigen::Vector2d& p : cell.corners) centre += p;
    centre /= static_cast<double>(cell.corners.size());
    Eigen::Matrix2d moment = Eigen::Matrix2d::Zero();
    for (const Eigen::Vector2d& p : cell.corners) moment += (p - centre) * (p - centre).transpose();
    const double long_angle = 0.5 * std::atan2(2.0 * moment(0, 1), moment(0, 0) - moment(1, 1));
    // The crack runs across the long axis, so its normal is along it (turned by up to ±25°).
    const double angle = long_angle + rng.uniform(-25.0, 25.0) * std::numbers::pi / 180.0;
    const Eigen::Vector2d normal(std::cos(angle), std::sin(angle));
    double reach = 0.0;
    for (const Eigen::Vector2d& p : cell.corners) reach = std::max(reach, std::abs(normal.dot(p - centre)));
    const Eigen::Vector2d point = centre + rng.uniform(-0.15, 0.15) * reach * normal;
    std::vector<int> stop;
    for (const int c : cell.edge_crack) {
      if (c >= 0 && std::find(stop.begin(), stop.end(), c) == stop.end()) stop.push_back(c);
    }
    const int id = add_plane_crack(mesh, cracks, {Eigen::Vector3d(normal.x(), normal.y(), 0.0),
                                                  Eigen::Vector3d(point.x(), point.y(), 0.0), stop});
    // The two halves of the cell.
    Cell halves[2];
    for (int side = 0; side < 2; ++side) {
      const double sign = side == 0 ? 1.0 : -1.0;
      Cell& h = halves[side];
      for (std::size_t i = 0; i < cell.corners.size(); ++i) {
        const Eigen::Vector2d& a = cell.corners[i];
        const Eigen::Vector2d& b = cell.corners[(i + 1) % cell.corners.size()];
        const double va = sign * normal.dot(a - point), vb = sign * normal.dot(b - point);
        if (va >= 0.0) {
          h.corners.push_back(a);
          h.edge_crack.push_back(cell.edge_crack[i]);
        }
        if ((va >= 0.0) != (vb >= 0.0)) {
          h.corners.push_back(a + va / (va - vb) * (b - a));
          // Entering the kept side continues the old edge; leaving it starts the new crack edge.
          h.edge_crack.push_back(va >= 0.0 ? id : cell.edge_crack[i]);
        }
      }
    }
    cells[largest] = halves[0];
    cells.push_back(halves[1]);
  }
}

}  // namespace fissure::test
