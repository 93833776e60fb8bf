#include "tet_pieces.hpp"

#include "polygon_geometry.hpp"

#include "fissure/mesh/tet_mesh.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <optional>

namespace fissure::detail {
namespace {

// Sums over the tet's nodes in one fixed order (TetPieceOptions::node_order).
class TetFrame {
public:
  TetFrame(const Eigen::Matrix<double, 4, 3>& nodes, const std::array<int, 4>& order) : m_nodes(nodes), m_order(order) {}

  double value(const std::array<double, 4>& node_values, const Eigen::Vector4d& w) const {
    double s = 0.0;
    for (int i : m_order) s += w(i) * node_values[static_cast<std::size_t>(i)];
    return s;
  }

  Eigen::Vector3d position(const Eigen::Vector4d& w) const {
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for (int i : m_order) x += w(i) * m_nodes.row(i).transpose();
    return x;
  }

private:
  const Eigen::Matrix<double, 4, 3>& m_nodes;
  std::array<int, 4> m_order;
};

// One linear function to split by: a cut's node values, times ±1.
struct SplitPlane {
  const std::array<double, 4>* node_values;
  double sign;
  Eigen::Vector3d gradient;  // of sign·S in space, for the section's orientation
  PieceFaceKind kind;
  int index;
};

struct Split {
  std::optional<TetPiece> positive, negative;  // f > 0 and f < 0; empty when nothing is there
};

// The two sides of convex `piece` across f = 0. Points with |f| ≤ on_plane are on the plane:
// they go to both sides and no crossing is computed next to them. A crossing is computed from
// its segment's lexicographically first end, so the faces sharing the segment (in this tet or
// the next) get the same bits.
Split split(TetPiece&& piece, const TetFrame& frame, const SplitPlane& plane, double on_plane, double min_area2) {
  // Most pieces a crack's tets hold lie on one side of it: found first, they move through whole.
  {
    bool pos_side = false, neg_side = false;
    for (const PieceFace& face : piece.faces)
      for (const Eigen::Vector4d& w : face.weights) {
        const double v = plane.sign * frame.value(*plane.node_values, w);
        pos_side = pos_side || v > on_plane;
        neg_side = neg_side || v < -on_plane;
      }
    Split out;
    if (!neg_side) {
      out.positive = std::move(piece);
      return out;
    }
    if (!pos_side) {
      out.negative = std::move(piece);
      return out;
    }
  }
  TetPiece pos{piece.key, {}}, neg{piece.key, {}};
  pos.faces.reserve(piece.faces.size() + 1);
  neg.faces.reserve(piece.faces.size() + 1);
  SmallVector<std::pair<Eigen::Vector3d, Eigen::Vector4d>, 16> cap;  // the section's points, unordered
  for (const PieceFace& face : piece.faces) {
    const std::size_t n = face.points.size();
    SmallVector<double, 16> value;
    SmallVector<int, 16> side;
    for (std::size_t i = 0; i < n; ++i) {
      value.push_back(plane.sign * frame.value(*plane.node_values, face.weights[i]));
      side.push_back(value[i] > on_plane ? 1 : (value[i] < -on_plane ? -1 : 0));
    }
    PieceFace fp{face.kind, face.index, {}, {}}, fn{face.kind, face.index, {}, {}};
    const auto add = [](PieceFace& f, const Eigen::Vector3d& x, const Eigen::Vector4d& w) {
      f.points.push_back(x);
      f.weights.push_back(w);
    };
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t j = (i + 1) % n;
      if (side[i] >= 0) add(fp, face.points[i], face.weights[i]);
      if (side[i] <= 0) add(fn, face.points[i], face.weights[i]);
      if (side[i] == 0) cap.emplace_back(face.points[i], face.weights[i]);
      if (side[i] * side[j] < 0) {
        std::size_t a = i, b = j;
        if (position_before(face.points[j], face.points[i])) std::swap(a, b);
        const double t = value[a] / (value[a] - value[b]);
        const Eigen::Vector4d w = face.weights[a] + t * (face.weights[b] - face.weights[a]);
        const Eigen::Vector3d x = frame.position(w);
        add(fp, x, w);
        add(fn, x, w);
        cap.emplace_back(x, w);
      }
    }
    if (fp.points.size() >= 3 && polygon_area_vector(fp.points).squaredNorm() > min_area2) pos.faces.push_back(std::move(fp));
    if (fn.points.size() >= 3 && polygon_area_vector(fn.points).squaredNorm() > min_area2) neg.faces.push_back(std::move(fn));
  }
  Split out;
  // The section: the cap points without repeats (each crossing is found by both faces of its
  // segment, with the same bits), in order round their mean in the plane.
  const auto before = [](const auto& a, const auto& b) { return position_before(a.first, b.first); };
  std::sort(cap.begin(), cap.end(), before);
  cap.truncate(static_cast<std::size_t>(
      std::unique(cap.begin(), cap.end(), [](const auto& a, const auto& b) { return a.first == b.first; }) - cap.begin()));
  if (cap.size() >= 3) {
    const Eigen::Vector3d normal = plane.gradient.normalized();  // out of the negative side
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (const auto& p : cap) centre += p.first;
    centre /= static_cast<double>(cap.size());
    const Eigen::Vector3d u = (cap[0].first - centre).normalized();
    const Eigen::Vector3d w = normal.cross(u);
    const auto angle = [&](const Eigen::Vector3d& x) { return std::atan2((x - centre).dot(w), (x - centre).dot(u)); };
    std::sort(cap.begin(), cap.end(), [&](const auto& a, const auto& b) { return angle(a.first) < angle(b.first); });
    // Counter-clockwise about `normal`: outward for the negative side, inward for the positive.
    PieceFace section{plane.kind, plane.index, {}, {}};
    for (const auto& [x, wt] : cap) {
      section.points.push_back(x);
      section.weights.push_back(wt);
    }
    if (polygon_area_vector(section.points).squaredNorm() > min_area2) {
      neg.faces.push_back(section);
      std::reverse(section.points.begin(), section.points.end());
      std::reverse(section.weights.begin(), section.weights.end());
      pos.faces.push_back(std::move(section));
    }
  }
  if (pos.faces.size() >= 4) out.positive = std::move(pos);
  if (neg.faces.size() >= 4) out.negative = std::move(neg);
  return out;
}

// The gradient in space of the P1 interpolant of `v` over the tet.
Eigen::Vector3d gradient(const Eigen::Matrix<double, 4, 3>& nodes, const std::array<double, 4>& v) {
  Eigen::Matrix3d a;
  for (int i = 0; i < 3; ++i) a.row(i) = nodes.row(i + 1) - nodes.row(0);
  // Cramer's rule by cross products: no LU needed for one 3 × 3 system.
  const Eigen::Vector3d b(v[1] - v[0], v[2] - v[0], v[3] - v[0]);
  const Eigen::Vector3d c0 = a.row(1).cross(a.row(2)), c1 = a.row(2).cross(a.row(0)), c2 = a.row(0).cross(a.row(1));
  const double det = a.row(0).dot(c0);
  return (b(0) * c0 + b(1) * c1 + b(2) * c2) / det;
}

}  // namespace

double piece_volume(const TetPiece& piece) {
  // Σ over faces of the fan triangles' signed volumes against one reference point.
  if (piece.faces.empty() || piece.faces[0].points.empty()) return 0.0;
  const Eigen::Vector3d r = piece.faces[0].points[0];
  double six_v = 0.0;
  for (const PieceFace& face : piece.faces) {
    const auto& p = face.points;
    for (std::size_t i = 1; i + 1 < p.size(); ++i) six_v += (p[0] - r).dot((p[i] - r).cross(p[i + 1] - r));
  }
  return six_v / 6.0;
}

std::vector<TetPiece> tet_pieces(const Eigen::Matrix<double, 4, 3>& nodes, std::span<const TetCutPlane> cuts,
                                 const TetPieceOptions& options) {
  const TetFrame frame(nodes, options.node_order);
  // The tet, its faces wound outward whichever way its nodes are ordered.
  TetPiece whole;
  for (int f = 0; f < 4; ++f) {
    PieceFace face{PieceFaceKind::TetFace, f, {}, {}};
    for (int i : TetMesh::kLocalFaces[static_cast<std::size_t>(f)]) {
      face.points.push_back(nodes.row(i).transpose());
      face.weights.push_back(Eigen::Vector4d::Unit(i));
    }
    whole.faces.push_back(std::move(face));
  }
  if (piece_volume(whole) < 0.0) {  // kLocalFaces winds outward for positively oriented tets
    for (PieceFace& face : whole.faces) {
      std::reverse(face.points.begin(), face.points.end());
      std::reverse(face.weights.begin(), face.weights.end());
    }
  }
  std::vector<TetPiece> pieces{std::move(whole)};
  if (cuts.empty()) return pieces;

  const double size = (nodes.colwise().maxCoeff() - nodes.colwise().minCoeff()).maxCoeff();
  // Faces below 1e-20 size² (1e-10 of the size across, where fragment meshing welds points) are
  // dropped. A face 3e-8 across is real: where four cracks meet within round-off they bound a
  // cell that small, and dropping its faces (at 1e-12 size²) left holes in its neighbours.
  const double min_area2 = std::pow(1e-20 * size * size, 2);
  double on_plane = options.on_plane;
  if (!(on_plane > 0.0)) {
    for (const TetCutPlane& c : cuts)
      for (double v : c.node_values) on_plane = std::max(on_plane, 1e-12 * std::abs(v));
  }

  for (std::size_t j = 0; j < cuts.size(); ++j) {
    const TetCutPlane& c = cuts[j];
    std::ptrdiff_t clip = -1;
    for (std::size_t i = 0; i < j && c.clipped_by >= 0; ++i)
      if (cuts[i].crack == c.clipped_by) clip = static_cast<std::ptrdiff_t>(i);
    const SplitPlane crack{&c.node_values, 1.0, gradient(nodes, c.node_values), PieceFaceKind::Crack, c.crack};
    std::vector<TetPiece> next;
    next.reserve(2 * pieces.size());
    for (TetPiece& piece : pieces) {
      SmallVector<TetPiece, 2> arrival;  // the parts crack c divides
      if (clip < 0) {
        arrival.push_back(std::move(piece));
      } else {
        // Crack c exists on the side clip_side·S_i > 0 of the clipping crack's plane. Where
        // that crack does not exist across the piece (its own code 0), the piece is divided
        // along its plane here without a crack: open faces.
        const TetCutPlane& ci = cuts[static_cast<std::size_t>(clip)];
        const double sign = c.clip_side < 0 ? -1.0 : 1.0;
        const SplitPlane clipping{&ci.node_values, sign, sign * gradient(nodes, ci.node_values), PieceFaceKind::Open,
                                  ci.crack};
        Split s = split(std::move(piece), frame, clipping, on_plane, min_area2);
        if (s.positive) arrival.push_back(std::move(*s.positive));
        if (s.negative) {
          s.negative->key.push_back('\0');
          next.push_back(std::move(*s.negative));
        }
      }
      for (TetPiece& part : arrival) {
        Split s = split(std::move(part), frame, crack, on_plane, min_area2);
        if (s.positive) {
          s.positive->key.push_back('\1');
          next.push_back(std::move(*s.positive));
        }
        if (s.negative) {
          s.negative->key.push_back('\2');
          next.push_back(std::move(*s.negative));
        }
      }
    }
    pieces.clear();
    for (TetPiece& p : next)
      if (piece_volume(p) > 0.0) pieces.push_back(std::move(p));
  }
  return pieces;
}

}  // namespace fissure::detail
