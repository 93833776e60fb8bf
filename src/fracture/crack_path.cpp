#include "crack_path.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <limits>

namespace fissure::detail {
namespace {

// Barycentric coordinates of x in tet t (λ0..λ3, summing to 1).
Eigen::Vector4d barycentric(const TetMesh& mesh, int t, const Eigen::Vector3d& x) {
  const Eigen::Vector3d p0 = mesh.nodes().row(mesh.tets()(t, 0)).transpose();
  Eigen::Matrix3d a;
  for (int i = 0; i < 3; ++i) a.col(i) = mesh.nodes().row(mesh.tets()(t, i + 1)).transpose() - p0;
  const Eigen::Vector3d b = a.partialPivLu().solve(x - p0);
  return {1.0 - b.sum(), b(0), b(1), b(2)};
}

// The direction along the surface (normal `up`) orthogonal to the crack normal n, oriented like
// `previous`; zero when the crack lies parallel to the surface there.
Eigen::Vector3d along(const Eigen::Vector3d& n, const Eigen::Vector3d& up, const Eigen::Vector3d& previous) {
  Eigen::Vector3d t = n.cross(up);
  const double norm = t.norm();
  if (norm < 1e-6) return Eigen::Vector3d::Zero();
  t /= norm;
  return t.dot(previous) < 0.0 ? Eigen::Vector3d(-t) : t;
}

// cos 30°: the most the surface normal may turn in one step of the path.
constexpr double kSmoothTurn = 0.866;

// Steps an arm goes on past the first tet where it may end (Options::ends_at).
constexpr int kStepsPastEnd = 4;

// `to`, or the unit vector at most `max_angle` from `from` toward it.
Eigen::Vector3d limit_turn(const Eigen::Vector3d& from, const Eigen::Vector3d& to, double max_angle) {
  const double angle = std::acos(std::clamp(from.dot(to), -1.0, 1.0));
  if (angle <= max_angle) return to;
  const Eigen::Vector3d side = (to - from.dot(to) * from).normalized();
  return (std::cos(max_angle) * from + std::sin(max_angle) * side).normalized();
}

}  // namespace

// The tet holding x, walking from `start` across the face of the most negative barycentric
// coordinate (face f is opposite local node f); -1 when the walk leaves the body. Steps are an
// element or less, so the walk takes one or two moves; the cap only guards against cycling on
// degenerate input.
int locate_tet(const TetMesh& mesh, int start, const Eigen::Vector3d& x) {
  int t = start;
  for (int moves = 0; moves < 64; ++moves) {
    const Eigen::Vector4d l = barycentric(mesh, t, x);
    if (!l.allFinite()) return -1;
    Eigen::Index f = 0;
    if (l.minCoeff(&f) >= -1e-12) return t;
    t = mesh.neighbours()(t, static_cast<int>(f));
    if (t < 0) return -1;
  }
  return -1;
}

CrackPath::CrackPath(const TetMesh& mesh, const Eigen::MatrixX3d& surface_normals, int origin_tet,
                     const Eigen::Vector3d& origin, const Eigen::Vector3d& normal_minus,
                     const Eigen::Vector3d& normal_plus, const Options& options, const Turn& turn) {
  const Eigen::Vector3d up = surface_normals.row(origin_tet).transpose();
  std::vector<Eigen::Vector3d> points_minus{origin}, normals_minus{normal_minus}, up_minus{up};
  std::vector<Eigen::Vector3d> points_plus{origin}, normals_plus{normal_plus}, up_plus{up};
  trace_arm(mesh, surface_normals, origin_tet, -1.0, options, turn, points_minus, normals_minus, up_minus);
  trace_arm(mesh, surface_normals, origin_tet, 1.0, options, turn, points_plus, normals_plus, up_plus);
  // One polyline: the minus arm reversed, then the plus arm. The origin appears once, or, at a
  // kink, twice (once with each arm's normal): the zero-length segment between the two keeps each
  // arm's normal up to the kink instead of blending the two across its first segment.
  m_points.assign(points_minus.rbegin(), points_minus.rend());
  m_normals.assign(normals_minus.rbegin(), normals_minus.rend());
  m_up.assign(up_minus.rbegin(), up_minus.rend());
  const bool kink = normal_minus != normal_plus;
  const auto from = static_cast<std::ptrdiff_t>(kink ? 0 : 1);
  m_points.insert(m_points.end(), points_plus.begin() + from, points_plus.end());
  m_normals.insert(m_normals.end(), normals_plus.begin() + from, normals_plus.end());
  m_up.insert(m_up.end(), up_plus.begin() + from, up_plus.end());
  // Each segment along the surface, once: D is evaluated at every node a crack's flood reaches.
  for (std::size_t i = 0; i + 1 < m_points.size(); ++i) {
    const Eigen::Vector3d ab = m_points[i + 1] - m_points[i];
    const Eigen::Vector3d& up = m_up[i + 1];
    m_along.push_back(ab - ab.dot(up) * up);
    m_along_length2.push_back(m_along.back().squaredNorm());
  }
}

void CrackPath::trace_arm(const TetMesh& mesh, const Eigen::MatrixX3d& surface_normals, int origin_tet, double sign,
                          const Options& options, const Turn& turn, std::vector<Eigen::Vector3d>& points,
                          std::vector<Eigen::Vector3d>& normals, std::vector<Eigen::Vector3d>& up) const {
  // The arm's first direction: across the crack normal, along the surface; a crack parallel to
  // the surface (delamination) has no course along it and stays the paper's plane.
  Eigen::Vector3d n = normals.back();
  const Eigen::Vector3d seed = n.cross(up.back());
  if (seed.norm() < 1e-6) return;
  Eigen::Vector3d direction = sign * seed.normalized();
  int tet = origin_tet;
  const double step = options.step;
  if (!(step > 0.0)) return;  // no course to trace: the crack stays the plane through its origin
  const double max_turn = step / options.min_radius;  // radians per step
  // As a double first: a denormal step makes the count infinite, and converting that to int is
  // undefined.
  const double wanted = std::ceil(options.max_length / step);
  const int steps = wanted < 1e7 ? static_cast<int>(wanted) : 10'000'000;
  int after_end = -1;  // steps since the path first entered a tet where it may end
  for (int i = 0; i < steps && after_end < kStepsPastEnd; ++i) {
    const Eigen::Vector3d next = points.back() + step * direction;
    const int from = tet;
    tet = locate_tet(mesh, tet, next);
    if (tet < 0) return;  // left the body: the end segment's ray carries the crack out
    if (after_end >= 0) {
      ++after_end;
    } else if (options.ends_at && options.ends_at(tet)) {
      after_end = 0;
    }
    // The surface the path runs along: the nearest surface's normal, as long as it turns
    // smoothly (a bowl's wall); not where the nearest surface jumps to another face (a tile's
    // side wall beside its top), which would tip the crack over into the thickness.
    Eigen::Vector3d u = surface_normals.row(tet).transpose();
    const Eigen::Vector3d& previous = up.back();
    if (u.dot(previous) < 0.0) u = -u;  // a tile's bottom is the same plane as its top
    if (u.dot(previous) < kSmoothTurn) u = previous;
    n = limit_turn(n, turn(from, tet, n, u, step), max_turn);
    const Eigen::Vector3d d = along(n, u, direction);
    points.push_back(next);
    normals.push_back(n);
    up.push_back(u);
    if (d.squaredNorm() == 0.0) return;  // turned parallel to the surface: stop turning here
    direction = d;
  }
}

double CrackPath::operator()(const Eigen::Vector3d& x) const {
  if (m_points.size() == 1) return m_normals[0].dot(x - m_points[0]);
  // The nearest point along the surface: each segment's distance with its surface normal's
  // component removed. The first and last segments extend beyond their ends as rays.
  double best = std::numeric_limits<double>::infinity();
  std::size_t best_i = 0;
  double best_s = 0.0;
  const std::size_t last = m_points.size() - 2;
  for (std::size_t i = 0; i + 1 < m_points.size(); ++i) {
    const Eigen::Vector3d& a = m_points[i];
    const Eigen::Vector3d& up = m_up[i + 1];
    const Eigen::Vector3d& ab_t = m_along[i];
    Eigen::Vector3d ax = x - a;
    ax -= ax.dot(up) * up;
    const double len2 = m_along_length2[i];
    double s = len2 > 0.0 ? ax.dot(ab_t) / len2 : 0.0;
    const double lo = i == 0 ? -std::numeric_limits<double>::infinity() : 0.0;
    const double hi = i == last ? std::numeric_limits<double>::infinity() : 1.0;
    s = std::clamp(s, lo, hi);
    const double d2 = (ax - s * ab_t).squaredNorm();
    if (d2 < best) {
      best = d2;
      best_i = i;
      best_s = s;
    }
  }
  const double w = std::clamp(best_s, 0.0, 1.0);
  const Eigen::Vector3d q = m_points[best_i] + best_s * (m_points[best_i + 1] - m_points[best_i]);
  const Eigen::Vector3d n = ((1.0 - w) * m_normals[best_i] + w * m_normals[best_i + 1]).normalized();
  return n.dot(x - q);
}

}  // namespace fissure::detail
