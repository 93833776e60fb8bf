#include "fissure/fracture/crack_surface.hpp"

namespace fissure {
namespace {

struct EdgePoint {
  Eigen::Vector3d position;
  int a, b;   // local nodes of the edge
  double t;   // position = node a + t (node b − node a)
};

// Where the P1 interpolant of `values` vanishes on edge (a, b), which must change sign.
EdgePoint edge_point(const Eigen::Matrix<double, 4, 3>& nodes, const std::array<double, 4>& values, int a, int b) {
  const double t = values[a] / (values[a] - values[b]);
  return {nodes.row(a).transpose() + t * (nodes.row(b) - nodes.row(a)).transpose(), a, b, t};
}

}  // namespace

std::vector<Eigen::Vector3d> crack_polygon(const Eigen::Matrix<double, 4, 3>& tet_nodes, const CrackCut& cut,
                                           const CrackCut* clipping_cut) {
  const auto& v = cut.node_values;
  std::array<int, 4> positive{}, negative{};
  int np = 0, nn = 0;
  for (int i = 0; i < 4; ++i) (v[i] > 0.0 ? positive[np++] : negative[nn++]) = i;
  std::vector<EdgePoint> points;
  if (np == 0 || nn == 0) return {};
  if (np == 1 || nn == 1) {
    // One node alone on its side: a triangle on its three edges.
    const int lone = np == 1 ? positive[0] : negative[0];
    for (int i = 0; i < 4; ++i) {
      if (i != lone) points.push_back(edge_point(tet_nodes, v, lone, i));
    }
  } else {
    // Two against two: a quad; (p0,n0) (p0,n1) (p1,n1) (p1,n0) go round it.
    const int p0 = positive[0], p1 = positive[1], n0 = negative[0], n1 = negative[1];
    points = {edge_point(tet_nodes, v, p0, n0), edge_point(tet_nodes, v, p0, n1), edge_point(tet_nodes, v, p1, n1),
              edge_point(tet_nodes, v, p1, n0)};
  }
  std::vector<Eigen::Vector3d> polygon;
  if (!clipping_cut) {
    for (const EdgePoint& p : points) polygon.push_back(p.position);
    return polygon;
  }
  // Sutherland–Hodgman against the clipping crack's P1 interpolant, which is linear in space, so
  // its value at an edge point is the linear blend of its node values, and along a polygon edge
  // the crossing is found by linear interpolation too.
  const auto& w = clipping_cut->node_values;
  const double side = cut.clip_side >= 0 ? 1.0 : -1.0;
  std::vector<double> value;
  for (const EdgePoint& p : points) value.push_back(side * ((1.0 - p.t) * w[p.a] + p.t * w[p.b]));
  const std::size_t n = points.size();
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    const bool in_i = value[i] >= 0.0, in_j = value[j] >= 0.0;
    if (in_i) polygon.push_back(points[i].position);
    if (in_i != in_j) {
      const double s = value[i] / (value[i] - value[j]);
      polygon.push_back(points[i].position + s * (points[j].position - points[i].position));
    }
  }
  return polygon;
}

}  // namespace fissure
