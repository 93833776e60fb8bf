#include "tet_pieces.hpp"

#include "fissure/mesh/tet_mesh.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <optional>

namespace fissure::detail {
namespace {

// A linear function of position: the P1 interpolant of one cut's node values in the tet.
struct Linear {
  Eigen::Vector3d gradient;
  Eigen::Vector3d origin;  // node 0
  double value0 = 0.0;
  double operator()(const Eigen::Vector3d& x) const { return value0 + gradient.dot(x - origin); }
};

Linear interpolant(const Eigen::Matrix<double, 4, 3>& nodes, const std::array<double, 4>& v) {
  Eigen::Matrix3d a;
  for (int i = 0; i < 3; ++i) a.row(i) = nodes.row(i + 1) - nodes.row(0);
  const Eigen::Vector3d g = a.partialPivLu().solve(Eigen::Vector3d(v[1] - v[0], v[2] - v[0], v[3] - v[0]));
  return {g, nodes.row(0).transpose(), v[0]};
}

bool lexicographically_before(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  if (a.x() != b.x()) return a.x() < b.x();
  if (a.y() != b.y()) return a.y() < b.y();
  return a.z() < b.z();
}

// Where the segment (a, b) with values (la, lb) of opposite signs crosses zero, computed from the
// lexicographically first end so the two faces that share the segment get the same bits.
Eigen::Vector3d crossing(const Eigen::Vector3d& a, double la, const Eigen::Vector3d& b, double lb) {
  if (lexicographically_before(b, a)) return crossing(b, lb, a, la);
  const double t = la / (la - lb);
  return a + t * (b - a);
}

Eigen::Vector3d area_vector(const std::vector<Eigen::Vector3d>& p) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (std::size_t i = 1; i + 1 < p.size(); ++i) sum += (p[i] - p[0]).cross(p[i + 1] - p[0]);
  return sum;
}

struct Split {
  std::optional<TetPiece> positive, negative;  // f > 0 and f < 0; empty when nothing is there
};

// The two sides of convex `piece` across f = 0; the new faces on f = 0 are of `kind`/`index`.
// Points within `tolerance` of the plane (in f's units) are on it: they go to both sides and
// no crossing is computed next to them.
Split split(const TetPiece& piece, const Linear& f, double tolerance, PieceFaceKind kind, int index,
            double min_area2) {
  TetPiece pos{piece.key, {}}, neg{piece.key, {}};
  std::vector<Eigen::Vector3d> cap;  // the section's points, unordered
  bool any_pos = false, any_neg = false;
  for (const PieceFace& face : piece.faces) {
    const std::size_t n = face.points.size();
    std::vector<double> value(n);
    std::vector<int> side(n);
    for (std::size_t i = 0; i < n; ++i) {
      value[i] = f(face.points[i]);
      side[i] = value[i] > tolerance ? 1 : (value[i] < -tolerance ? -1 : 0);
      any_pos = any_pos || side[i] > 0;
      any_neg = any_neg || side[i] < 0;
    }
    PieceFace fp{face.kind, face.index, {}}, fn{face.kind, face.index, {}};
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t j = (i + 1) % n;
      if (side[i] >= 0) fp.points.push_back(face.points[i]);
      if (side[i] <= 0) fn.points.push_back(face.points[i]);
      if (side[i] == 0) cap.push_back(face.points[i]);
      if (side[i] * side[j] < 0) {
        const Eigen::Vector3d q = crossing(face.points[i], value[i], face.points[j], value[j]);
        fp.points.push_back(q);
        fn.points.push_back(q);
        cap.push_back(q);
      }
    }
    if (fp.points.size() >= 3 && area_vector(fp.points).squaredNorm() > min_area2) pos.faces.push_back(std::move(fp));
    if (fn.points.size() >= 3 && area_vector(fn.points).squaredNorm() > min_area2) neg.faces.push_back(std::move(fn));
  }
  Split out;
  if (!any_neg) {
    out.positive = piece;
    return out;
  }
  if (!any_pos) {
    out.negative = piece;
    return out;
  }
  // The section: the cap points without repeats (each crossing is found by both faces of its
  // edge, with the same bits), in order round their mean in the plane.
  std::sort(cap.begin(), cap.end(), lexicographically_before);
  cap.erase(std::unique(cap.begin(), cap.end()), cap.end());
  if (cap.size() >= 3) {
    const Eigen::Vector3d normal = f.gradient.normalized();  // out of the negative side
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (const auto& p : cap) centre += p;
    centre /= static_cast<double>(cap.size());
    const Eigen::Vector3d u = (cap[0] - centre).normalized();
    const Eigen::Vector3d w = normal.cross(u);
    std::sort(cap.begin(), cap.end(), [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
      return std::atan2((a - centre).dot(w), (a - centre).dot(u)) < std::atan2((b - centre).dot(w), (b - centre).dot(u));
    });
    // Counter-clockwise about `normal`: outward for the negative side, inward for the positive.
    if (area_vector(cap).squaredNorm() > min_area2) {
      neg.faces.push_back({kind, index, cap});
      std::reverse(cap.begin(), cap.end());
      pos.faces.push_back({kind, index, std::move(cap)});
    }
  }
  if (pos.faces.size() >= 4) out.positive = std::move(pos);
  if (neg.faces.size() >= 4) out.negative = std::move(neg);
  return out;
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

std::vector<TetPiece> tet_pieces(const Eigen::Matrix<double, 4, 3>& nodes, std::span<const TetCutPlane> cuts) {
  // The tet, its faces wound outward whichever way its nodes are ordered.
  TetPiece whole;
  const Eigen::Vector3d p0 = nodes.row(0).transpose();
  const double signed_six_v =
      (nodes.row(1).transpose() - p0).dot((nodes.row(2).transpose() - p0).cross(nodes.row(3).transpose() - p0));
  for (int f = 0; f < 4; ++f) {
    PieceFace face{PieceFaceKind::TetFace, f, {}};
    for (int i : TetMesh::kLocalFaces[static_cast<std::size_t>(f)]) face.points.push_back(nodes.row(i).transpose());
    whole.faces.push_back(std::move(face));
  }
  if (piece_volume(whole) < 0.0)  // kLocalFaces winds outward for positively oriented tets
    for (PieceFace& face : whole.faces) std::reverse(face.points.begin(), face.points.end());
  std::vector<TetPiece> pieces{std::move(whole)};
  if (cuts.empty()) return pieces;

  const double size = (nodes.colwise().maxCoeff() - nodes.colwise().minCoeff()).maxCoeff();
  const double min_volume = 1e-12 * std::abs(signed_six_v) / 6.0;
  const double min_area2 = std::pow(1e-12 * size * size, 2);
  std::vector<Linear> planes;
  for (const TetCutPlane& c : cuts) planes.push_back(interpolant(nodes, c.node_values));
  // Values within this of zero are on the plane: round-off of a value of size |∇f|·size.
  const auto tolerance = [&](const Linear& f) { return 1e-12 * f.gradient.norm() * size; };

  for (std::size_t j = 0; j < cuts.size(); ++j) {
    const TetCutPlane& c = cuts[j];
    std::ptrdiff_t clip = -1;
    for (std::size_t i = 0; i < j && c.clipped_by >= 0; ++i)
      if (cuts[i].crack == c.clipped_by) clip = static_cast<std::ptrdiff_t>(i);
    std::vector<TetPiece> next;
    for (const TetPiece& piece : pieces) {
      std::vector<TetPiece> arrival;  // the parts crack c divides
      if (clip < 0) {
        arrival.push_back(piece);
      } else {
        // Crack c exists on the side clip_side·f_i > 0 of the clipping crack's plane. Where
        // that crack does not exist across the piece (its own code 0), the piece is divided
        // along its plane here without a crack: open faces.
        const Linear& fi = planes[static_cast<std::size_t>(clip)];
        const Linear oriented{c.clip_side * fi.gradient, fi.origin, c.clip_side * fi.value0};
        Split s = split(piece, oriented, tolerance(fi), PieceFaceKind::Open, cuts[static_cast<std::size_t>(clip)].crack,
                        min_area2);
        if (s.positive) arrival.push_back(std::move(*s.positive));
        if (s.negative) {
          s.negative->key.push_back('\0');
          next.push_back(std::move(*s.negative));
        }
      }
      for (const TetPiece& part : arrival) {
        Split s = split(part, planes[j], tolerance(planes[j]), PieceFaceKind::Crack, c.crack, min_area2);
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
      if (piece_volume(p) > min_volume) pieces.push_back(std::move(p));
  }
  return pieces;
}

}  // namespace fissure::detail
