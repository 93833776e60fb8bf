#include "fissure/fracture/visible_pattern.hpp"

#include "fissure/base/error.hpp"
#include "fissure/base/number_text.hpp"
#include "fissure/exemplar/crack_graph.hpp"
#include "fissure/exemplar/crack_image.hpp"
#include "union_find.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <span>

namespace fissure {
namespace {

// Pieces thinner than this fraction of a triangle's value range are not cut off: a vertex whose
// crack value is within it of zero lies on the crack. 1e-12 relative is far above the round-off of
// the blends (≈1e-16) and far below any geometric scale (a crack 1e-12 of an element from a
// vertex), so no sliver piece of round-off size can become a fragment of its own.
constexpr double kOnLine = 1e-12;
// Two pieces across a shared edge touch when their footprints on it overlap by more than this
// fraction of the edge. Both footprints end at the same crack points, computed from the same node
// values (≈1e-16 apart); 1e-9 merges nothing real (two cracks 1e-9 of an edge apart).
constexpr double kOverlap = 1e-9;

using Bary = Eigen::Vector3d;  // barycentric coordinates on a visible triangle

std::uint64_t edge_key(int a, int b) {
  const auto lo = static_cast<std::uint64_t>(std::min(a, b)), hi = static_cast<std::uint64_t>(std::max(a, b));
  return (lo << 32) | hi;
}

// Dense indices for 64-bit keys (never 0): open addressing with linear probing in a table at least
// twice the expected count, so a lookup is one or two probes and nothing is allocated per key.
// A std::unordered_map allocated a node per edge, and sorting the keys instead took a third of
// the extraction (bench_visible_pattern).
class KeyIndex {
public:
  explicit KeyIndex(std::size_t expected) {
    std::size_t size = 16;
    while (size < 2 * expected) size *= 2;
    m_keys.assign(size, 0);
    m_values.assign(size, -1);
    m_mask = size - 1;
  }
  /// The index of `key`, giving it the next one (count()) when it is new.
  int insert(std::uint64_t key) {
    std::size_t slot = probe(key);
    if (m_keys[slot] == key) return m_values[slot];
    if (2 * static_cast<std::size_t>(m_count + 1) > m_keys.size()) {
      grow();
      slot = probe(key);
    }
    m_keys[slot] = key;
    m_values[slot] = m_count;
    return m_count++;
  }
  /// The index of `key`, or −1.
  int find(std::uint64_t key) const {
    const std::size_t slot = probe(key);
    return m_keys[slot] == key ? m_values[slot] : -1;
  }
  int count() const { return m_count; }

private:
  std::size_t probe(std::uint64_t key) const {
    std::size_t slot = static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> 20) & m_mask;
    while (m_keys[slot] != 0 && m_keys[slot] != key) slot = (slot + 1) & m_mask;
    return slot;
  }
  void grow() {
    std::vector<std::uint64_t> keys = std::move(m_keys);
    std::vector<int> values = std::move(m_values);
    m_keys.assign(2 * keys.size(), 0);
    m_values.assign(2 * keys.size(), -1);
    m_mask = m_keys.size() - 1;
    for (std::size_t i = 0; i < keys.size(); ++i) {
      if (keys[i] == 0) continue;
      const std::size_t slot = probe(keys[i]);
      m_keys[slot] = keys[i];
      m_values[slot] = values[i];
    }
  }
  std::vector<std::uint64_t> m_keys;
  std::vector<int> m_values;
  std::size_t m_mask = 0;
  int m_count = 0;
};

// A crack's trace on one visible triangle (before junction splits).
struct FaceSegment {
  int crack = -1;
  std::array<int, 2> point{};           // indices into the point table
  std::array<Bary, 2> bary;             // the end points on the triangle
  Eigen::Vector3d line = Eigen::Vector3d::Zero();  // S_k at the triangle's nodes
  bool clipped = false;                 // restricted to clip ≥ 0 (a T-junction's arrival side)
  int clipped_by = -1;
  Eigen::Vector3d clip = Eigen::Vector3d::Zero();  // side · S_j at the triangle's nodes
  bool ends_on_clip = false;            // point[1] is where it stops on crack clipped_by
  std::vector<std::pair<double, int>> splits;  // (parameter along point[0] → point[1], point)
};

struct Point {
  Eigen::Vector2d position;
  bool on_border = false;
};

// A convex piece of a triangle, its vertices held inline: a triangle cut by m lines has pieces of
// at most 3 + m vertices, and pieces are made and dropped by the thousand, so no heap allocation.
// 29 makes a piece 32 vertices (768 bytes); at 7K–54K tets a triangle is 1–3 cm wide, and 29
// cracks through one would be cracks a millimetre apart.
constexpr int kMaxCracksPerTriangle = 29;
struct Piece {
  std::array<Bary, 3 + kMaxCracksPerTriangle> vertices;
  int size = 0;
  void push_back(const Bary& b) { vertices[static_cast<std::size_t>(size++)] = b; }
};

// Splits a convex piece by the line where `values` (at the triangle's nodes) vanish. Vertices within
// `tolerance` of the line belong to both sides. Returns false (and leaves the outputs empty) when
// the line does not pass through the piece's interior.
bool split_piece(const Piece& piece, const Eigen::Vector3d& values, double tolerance, Piece& positive, Piece& negative) {
  const auto n = static_cast<std::size_t>(piece.size);
  std::array<double, 3 + kMaxCracksPerTriangle> v{};
  bool any_positive = false, any_negative = false;
  for (std::size_t i = 0; i < n; ++i) {
    v[i] = piece.vertices[i].dot(values);
    if (std::abs(v[i]) <= tolerance) v[i] = 0.0;
    any_positive |= v[i] > 0.0;
    any_negative |= v[i] < 0.0;
  }
  if (!any_positive || !any_negative) return false;
  positive.size = 0;
  negative.size = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    if (v[i] >= 0.0) positive.push_back(piece.vertices[i]);
    if (v[i] <= 0.0) negative.push_back(piece.vertices[i]);
    if ((v[i] > 0.0 && v[j] < 0.0) || (v[i] < 0.0 && v[j] > 0.0)) {
      const double s = v[i] / (v[i] - v[j]);
      // A coordinate that is exactly 0 at both ends stays exactly 0: the point stays on that edge.
      const Bary p = piece.vertices[i] + s * (piece.vertices[j] - piece.vertices[i]);
      positive.push_back(p);
      negative.push_back(p);
    }
  }
  return true;
}

std::string vector_text(const Eigen::Vector3d& v) {
  return "(" + format_number(v.x()) + ", " + format_number(v.y()) + ", " + format_number(v.z()) + ")";
}

}  // namespace

std::vector<std::string> VisiblePatternOptions::problems() const {
  std::vector<std::string> out;
  if (!(max_angle_deg >= 0.0 && max_angle_deg < 90.0)) out.push_back("max_angle_deg " + format_number(max_angle_deg) + " is outside [0, 90)");
  if (reference_long_side_px < kMinImageSide) {
    out.push_back("reference_long_side_px " + std::to_string(reference_long_side_px) + " is below " + std::to_string(kMinImageSide));
  }
  if (!(std::isfinite(line_width_px) && line_width_px > 0.0)) {
    out.push_back("line_width_px " + format_number(line_width_px) + " is not positive and finite");
  }
  return out;
}

void VisiblePatternOptions::validate() const { throw_if_problems("visible pattern options", problems()); }

PatternProjection pattern_projection(const Eigen::Vector3d& up) {
  PatternProjection p;
  p.up = up;
  int axis = 0;
  for (int i = 1; i < 3; ++i) {
    if (std::abs(up[i]) < std::abs(up[axis])) axis = i;
  }
  const Eigen::Vector3d a = Eigen::Vector3d::Unit(axis);
  p.axis_u = (a - a.dot(up) * up).normalized();
  p.axis_v = up.cross(p.axis_u);
  return p;
}

VisiblePattern extract_visible_pattern(const TetMesh& mesh, const std::vector<CrackSurface>& cracks, int crack_count,
                                       const Eigen::Vector3d& up_in, const VisiblePatternOptions& options) {
  options.validate();
  const std::string name = mesh.source_name().empty() ? std::string("mesh") : mesh.source_name();
  if (!up_in.allFinite() || !(up_in.norm() > 0.0)) {
    throw InvalidInput(name + ": the view direction " + vector_text(up_in) + " is not a finite non-zero vector");
  }
  if (crack_count < 0 || static_cast<std::size_t>(crack_count) > cracks.size()) {
    throw InvalidInput(name + ": crack count " + std::to_string(crack_count) + " is outside [0, " +
                       std::to_string(cracks.size()) + "]");
  }
  VisiblePattern result;
  result.projection = pattern_projection(up_in.normalized());
  const PatternProjection& proj = result.projection;

  // Visible triangles: outward normal within max_angle_deg of up.
  const double cos_max = std::cos(options.max_angle_deg * std::numbers::pi / 180.0);
  const std::vector<BoundaryFace>& boundary = mesh.boundary_faces();
  std::vector<int> visible;
  for (std::size_t f = 0; f < boundary.size(); ++f) {
    if (boundary[f].normal.dot(proj.up) >= cos_max) visible.push_back(static_cast<int>(f));
  }
  result.visible_triangles = static_cast<int>(visible.size());
  if (visible.empty()) {
    result.empty_reason = name + ": no boundary face has its outward normal within " +
                          format_number(options.max_angle_deg) + " degrees of " + vector_text(proj.up) +
                          ": the visible pattern is empty";
    return result;
  }
  result.has_visible_face = true;

  // The cuts of the tets that own a visible triangle, per tet (each cut's values checked).
  std::vector<int> slot_of_tet(static_cast<std::size_t>(mesh.tet_count()), -1);
  int slots = 0;
  for (const int f : visible) {
    int& slot = slot_of_tet[static_cast<std::size_t>(boundary[static_cast<std::size_t>(f)].tet)];
    if (slot < 0) slot = slots++;
  }
  // Compressed rows: slot r's cuts are cut_refs[cut_start[r] .. cut_start[r + 1]), in crack order
  // (the fragment split below relies on it: a T's clipping crack cuts first).
  std::vector<int> cut_start(static_cast<std::size_t>(slots) + 1, 0);
  for (int k = 0; k < crack_count; ++k) {
    for (const CrackCut& cut : cracks[static_cast<std::size_t>(k)].cuts) {
      if (cut.tet < 0 || cut.tet >= mesh.tet_count()) {
        throw InvalidInput(name + ": crack " + std::to_string(k) + " cuts tet index " + std::to_string(cut.tet) +
                           ", outside the mesh's " + std::to_string(mesh.tet_count()) + " tets");
      }
      for (const double v : cut.node_values) {
        if (!std::isfinite(v)) {
          throw InvalidInput(name + ": crack " + std::to_string(k) + " has a non-finite value in " + mesh.tet_label(cut.tet));
        }
      }
      const int slot = slot_of_tet[static_cast<std::size_t>(cut.tet)];
      if (slot >= 0) ++cut_start[static_cast<std::size_t>(slot) + 1];
    }
  }
  for (std::size_t r = 1; r < cut_start.size(); ++r) cut_start[r] += cut_start[r - 1];
  std::vector<std::pair<int, const CrackCut*>> cut_refs(static_cast<std::size_t>(cut_start.back()));
  {
    std::vector<int> fill(cut_start.begin(), cut_start.end() - 1);
    for (int k = 0; k < crack_count; ++k) {
      for (const CrackCut& cut : cracks[static_cast<std::size_t>(k)].cuts) {
        const int slot = slot_of_tet[static_cast<std::size_t>(cut.tet)];
        if (slot >= 0) cut_refs[static_cast<std::size_t>(fill[static_cast<std::size_t>(slot)]++)] = {k, &cut};
      }
    }
  }

  // Edges of the visible region: how many visible triangles use each mesh edge (2 inside, 1 on the
  // border of the region).
  KeyIndex edges(visible.size() * 2);  // a closed triangulation has 1.5 edges a triangle
  std::vector<int> edge_use;
  for (const int f : visible) {
    const auto& n = boundary[static_cast<std::size_t>(f)].nodes;
    for (int i = 0; i < 3; ++i) {
      const int e = edges.insert(edge_key(n[static_cast<std::size_t>(i)], n[static_cast<std::size_t>((i + 1) % 3)]));
      if (e == static_cast<int>(edge_use.size())) edge_use.push_back(0);
      ++edge_use[static_cast<std::size_t>(e)];
    }
  }

  std::vector<Point> points;
  KeyIndex edge_point(visible.size());  // (edge, crack) → index; point_of_edge_point maps it to a point
  std::vector<int> point_of_edge_point;
  struct Segment {
    int a, b, crack;
  };
  std::vector<Segment> segments;
  int piece_count = 0;
  std::vector<double> piece_area;
  std::vector<Eigen::Vector2d> piece_centroid;
  struct Footprint {
    int edge, triangle, piece;
    double t0, t1;
  };
  std::vector<Footprint> footprints;
  std::vector<char> piece_on_border;
  double total_area = 0.0;
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(INFINITY), hi = Eigen::Vector2d::Constant(-INFINITY);
  result.visible_triangle_corners.reserve(visible.size());
  // Most triangles are uncut: one piece and three footprints each.
  footprints.reserve(3 * visible.size() + 16);
  piece_area.reserve(visible.size() + 16);
  piece_centroid.reserve(visible.size() + 16);
  piece_on_border.reserve(visible.size() + 16);

  std::vector<FaceSegment> face_segments;
  std::vector<Piece> face_pieces, next;
  Piece positive, negative;
  Piece whole;
  for (int i = 0; i < 3; ++i) whole.push_back(Bary::Unit(i));
  for (std::size_t vi = 0; vi < visible.size(); ++vi) {
    const BoundaryFace& face = boundary[static_cast<std::size_t>(visible[vi])];
    const auto tet_nodes = mesh.tets().row(face.tet);
    std::array<int, 3> local{};
    std::array<Eigen::Vector2d, 3> corner;
    for (int i = 0; i < 3; ++i) {
      const int node = face.nodes[static_cast<std::size_t>(i)];
      for (int l = 0; l < 4; ++l) {
        if (tet_nodes(l) == node) local[static_cast<std::size_t>(i)] = l;
      }
      corner[static_cast<std::size_t>(i)] = proj.project(mesh.nodes().row(node).transpose());
      lo = lo.cwiseMin(corner[static_cast<std::size_t>(i)]);
      hi = hi.cwiseMax(corner[static_cast<std::size_t>(i)]);
    }
    result.visible_triangle_corners.push_back(corner);
    // The mesh edge opposite each corner, and its parameter's origin (the lower-numbered node).
    std::array<int, 3> edge_opposite{};
    for (int i = 0; i < 3; ++i) {
      edge_opposite[static_cast<std::size_t>(i)] =
          edges.find(edge_key(face.nodes[static_cast<std::size_t>((i + 1) % 3)], face.nodes[static_cast<std::size_t>((i + 2) % 3)]));
    }
    const double triangle_area = 0.5 * ((corner[1] - corner[0]).x() * (corner[2] - corner[0]).y() -
                                        (corner[1] - corner[0]).y() * (corner[2] - corner[0]).x());
    total_area += triangle_area;
    auto position = [&](const Bary& b) { return Eigen::Vector2d(b[0] * corner[0] + b[1] * corner[1] + b[2] * corner[2]); };
    auto values_of = [&](const CrackCut& cut) {
      return Eigen::Vector3d(cut.node_values[static_cast<std::size_t>(local[0])], cut.node_values[static_cast<std::size_t>(local[1])],
                             cut.node_values[static_cast<std::size_t>(local[2])]);
    };
    const auto slot = static_cast<std::size_t>(slot_of_tet[static_cast<std::size_t>(face.tet)]);
    const std::span<const std::pair<int, const CrackCut*>> tet_cuts(cut_refs.data() + cut_start[slot],
                                                                    cut_refs.data() + cut_start[slot + 1]);

    // Crack traces: the zero segment of each cut's values on this triangle, clipped for a T.
    face_segments.clear();
    for (const auto& [k, cut] : tet_cuts) {
      FaceSegment s;
      s.crack = k;
      s.line = values_of(*cut);
      int found = 0;
      for (int i = 0; i < 3 && found < 2; ++i) {
        const int a = i, b = (i + 1) % 3;
        if ((s.line[a] > 0.0) == (s.line[b] > 0.0)) continue;
        // The point is computed from the edge's lower-numbered node, so both triangles on the edge
        // (and their tets' cuts, which hold the same node values) get the very same point.
        const int node_a = face.nodes[static_cast<std::size_t>(a)], node_b = face.nodes[static_cast<std::size_t>(b)];
        const bool a_low = node_a < node_b;
        const int p = a_low ? a : b, q = a_low ? b : a;
        const double t = s.line[p] / (s.line[p] - s.line[q]);
        Bary bary = Bary::Zero();
        bary[p] = 1.0 - t;
        bary[q] = t;
        const int edge = edge_opposite[static_cast<std::size_t>(3 - a - b)];
        const int id = edge_point.insert((static_cast<std::uint64_t>(edge) + 1) << 32 | static_cast<std::uint32_t>(k));
        if (id == static_cast<int>(point_of_edge_point.size())) {
          point_of_edge_point.push_back(static_cast<int>(points.size()));
          points.push_back({corner[static_cast<std::size_t>(p)] + t * (corner[static_cast<std::size_t>(q)] - corner[static_cast<std::size_t>(p)]),
                            edge_use[static_cast<std::size_t>(edge)] == 1});
        }
        s.point[static_cast<std::size_t>(found)] = point_of_edge_point[static_cast<std::size_t>(id)];
        s.bary[static_cast<std::size_t>(found)] = bary;
        ++found;
      }
      if (found < 2) continue;
      if (cut->clipped_by >= 0) {
        const CrackCut* by = nullptr;
        for (const auto& [j, other] : tet_cuts) {
          if (j == cut->clipped_by) by = other;
        }
        if (!by) {
          throw InvalidInput(name + ": crack " + std::to_string(k) + " is clipped by crack " + std::to_string(cut->clipped_by) +
                             " in " + mesh.tet_label(face.tet) + ", which that crack does not cut");
        }
        s.clipped = true;
        s.clipped_by = cut->clipped_by;
        s.clip = (cut->clip_side >= 0 ? 1.0 : -1.0) * values_of(*by);
        const double h0 = s.bary[0].dot(s.clip), h1 = s.bary[1].dot(s.clip);
        const bool in0 = h0 >= 0.0, in1 = h1 >= 0.0;  // crack_polygon's rule: ≥ 0 is kept
        if (!in0 && !in1) continue;
        if (in0 != in1) {
          if (!in0) {
            std::swap(s.point[0], s.point[1]);
            std::swap(s.bary[0], s.bary[1]);
          }
          const double hk = in0 ? h0 : h1, hd = in0 ? h1 : h0;
          const double u = hk / (hk - hd);
          s.bary[1] = s.bary[0] + u * (s.bary[1] - s.bary[0]);
          s.point[1] = static_cast<int>(points.size());
          points.push_back({position(s.bary[1]), false});
          s.ends_on_clip = true;
        }
      }
      face_segments.push_back(std::move(s));
    }
    // The crack value of `line` along a segment: opposite strict signs at its ends = it crosses.
    auto crossing = [](const FaceSegment& s, const Eigen::Vector3d& line, double& param) {
      const double g0 = s.bary[0].dot(line), g1 = s.bary[1].dot(line);
      if (!((g0 > 0.0 && g1 < 0.0) || (g0 < 0.0 && g1 > 0.0))) return false;
      param = g0 / (g0 - g1);
      return true;
    };
    // T-junctions: a clipped segment ends on the clipping crack's segment, which is split there.
    for (FaceSegment& s : face_segments) {
      if (!s.ends_on_clip) continue;
      for (FaceSegment& other : face_segments) {
        double param = 0.0;
        if (other.crack == s.clipped_by && crossing(other, s.line, param)) other.splits.emplace_back(param, s.point[1]);
      }
    }
    // X-junctions: two segments crossing inside the triangle (not a T's own pair).
    for (std::size_t i = 0; i < face_segments.size(); ++i) {
      for (std::size_t j = i + 1; j < face_segments.size(); ++j) {
        FaceSegment& a = face_segments[i];
        FaceSegment& b = face_segments[j];
        if (a.crack == b.crack || a.clipped_by == b.crack || b.clipped_by == a.crack) continue;
        double pa = 0.0, pb = 0.0;
        if (!crossing(a, b.line, pa) || !crossing(b, a.line, pb)) continue;
        const int p = static_cast<int>(points.size());
        points.push_back({position(a.bary[0] + pa * (a.bary[1] - a.bary[0])), false});
        a.splits.emplace_back(pa, p);
        b.splits.emplace_back(pb, p);
      }
    }
    for (FaceSegment& s : face_segments) {
      std::sort(s.splits.begin(), s.splits.end());
      int from = s.point[0];
      for (const auto& [param, p] : s.splits) {
        segments.push_back({from, p, s.crack});
        from = p;
      }
      segments.push_back({from, s.point[1], s.crack});
    }

    // Fragments: the triangle cut into convex pieces, cracks in order of opening so that a T's
    // clipping crack has cut before the T's own segment, which then splits only the pieces on its
    // arrival side. A piece straddling the clipping line (possible only where the clipping crack is
    // itself clipped away in this tet) is left whole: the T ends inside it like a free end.
    if (face_segments.empty()) {
      // Uncut (most triangles): one piece, the triangle, on its three edges from end to end.
      for (int i = 0; i < 3; ++i) footprints.push_back({edge_opposite[static_cast<std::size_t>(i)], static_cast<int>(vi), piece_count, 0.0, 1.0});
      ++piece_count;
      piece_area.push_back(triangle_area);
      piece_centroid.push_back((corner[0] + corner[1] + corner[2]) / 3.0);
      piece_on_border.push_back(0);
      continue;
    }
    if (face_segments.size() > static_cast<std::size_t>(kMaxCracksPerTriangle)) {
      throw NumericalFailure(name + ": " + std::to_string(face_segments.size()) + " cracks cross one visible face of " +
                             mesh.tet_label(face.tet) + ", more than the " + std::to_string(kMaxCracksPerTriangle) +
                             " the visible pattern handles in one triangle");
    }
    face_pieces.assign(1, whole);
    for (const FaceSegment& s : face_segments) {
      const double line_tolerance = kOnLine * s.line.cwiseAbs().maxCoeff();
      const double clip_tolerance = kOnLine * s.clip.cwiseAbs().maxCoeff();
      next.clear();
      for (const Piece& piece : face_pieces) {
        bool split_here = true;
        if (s.clipped) {
          for (int v = 0; v < piece.size; ++v) split_here &= piece.vertices[static_cast<std::size_t>(v)].dot(s.clip) >= -clip_tolerance;
        }
        if (split_here && split_piece(piece, s.line, line_tolerance, positive, negative)) {
          next.push_back(positive);
          next.push_back(negative);
        } else {
          next.push_back(piece);
        }
      }
      std::swap(face_pieces, next);
    }
    for (Piece& piece : face_pieces) {
      // Area and centroid (fan from the first vertex; pieces are convex).
      double area = 0.0;
      Eigen::Vector2d moment = Eigen::Vector2d::Zero();
      const Eigen::Vector2d p0 = position(piece.vertices[0]);
      for (std::size_t i = 1; i + 1 < static_cast<std::size_t>(piece.size); ++i) {
        const Eigen::Vector2d p1 = position(piece.vertices[i]), p2 = position(piece.vertices[i + 1]);
        const double a = 0.5 * ((p1 - p0).x() * (p2 - p0).y() - (p1 - p0).y() * (p2 - p0).x());
        area += a;
        moment += a * (p0 + p1 + p2) / 3.0;
      }
      if (!(area > 0.0)) continue;
      const int id = piece_count;
      // Footprints on the triangle's edges: a piece edge lies on the edge opposite corner i when
      // both its ends have coordinate i exactly 0 (splitting keeps such zeros exact).
      for (std::size_t e = 0; e < static_cast<std::size_t>(piece.size); ++e) {
        const Bary& u = piece.vertices[e];
        const Bary& w = piece.vertices[(e + 1) % static_cast<std::size_t>(piece.size)];
        for (int i = 0; i < 3; ++i) {
          if (u[i] != 0.0 || w[i] != 0.0) continue;
          const int a = (i + 1) % 3, b = (i + 2) % 3;
          const int node_a = face.nodes[static_cast<std::size_t>(a)], node_b = face.nodes[static_cast<std::size_t>(b)];
          const int high = node_a < node_b ? b : a;  // parameter measured from the lower-numbered node
          const double t0 = std::min(u[high], w[high]), t1 = std::max(u[high], w[high]);
          if (t1 - t0 > kOverlap) footprints.push_back({edge_opposite[static_cast<std::size_t>(i)], static_cast<int>(vi), id, t0, t1});
        }
      }
      ++piece_count;
      piece_area.push_back(area);
      piece_centroid.push_back(moment / area);
      piece_on_border.push_back(0);
    }
  }

  // Pieces across a shared edge whose footprints overlap are one fragment; a footprint on an edge
  // of the region makes its fragment touch the border.
  detail::UnionFind sets(static_cast<std::size_t>(piece_count));
  // Bucketed by edge (a counting sort: pieces stay in order within an edge).
  std::vector<int> first(static_cast<std::size_t>(edges.count()) + 1, 0);
  for (const Footprint& f : footprints) ++first[static_cast<std::size_t>(f.edge) + 1];
  for (std::size_t e = 1; e < first.size(); ++e) first[e] += first[e - 1];
  std::vector<int> order(footprints.size());
  {
    std::vector<int> fill(first.begin(), first.end() - 1);
    for (std::size_t i = 0; i < footprints.size(); ++i) order[static_cast<std::size_t>(fill[static_cast<std::size_t>(footprints[i].edge)]++)] = static_cast<int>(i);
  }
  for (std::size_t e = 0; e + 1 < first.size(); ++e) {
    const int begin = first[e], end = first[e + 1];
    if (edge_use[e] == 1) {
      for (int i = begin; i < end; ++i) piece_on_border[static_cast<std::size_t>(footprints[static_cast<std::size_t>(order[static_cast<std::size_t>(i)])].piece)] = 1;
      continue;
    }
    for (int i = begin; i < end; ++i) {
      for (int j = i + 1; j < end; ++j) {
        const Footprint& a = footprints[static_cast<std::size_t>(order[static_cast<std::size_t>(i)])];
        const Footprint& b = footprints[static_cast<std::size_t>(order[static_cast<std::size_t>(j)])];
        if (a.triangle != b.triangle && std::min(a.t1, b.t1) - std::max(a.t0, b.t0) > kOverlap) sets.unite(a.piece, b.piece);
      }
    }
  }

  // The graph, in metres. The frame is the region's bounding box.
  const double extent = std::max(hi.x() - lo.x(), hi.y() - lo.y());
  const double metres_per_pixel = extent / options.reference_long_side_px;
  PlanarCrackGraphBuilder builder(lo, hi, total_area, name + " (visible pattern)");
  builder.set_crack_width(options.line_width_px * metres_per_pixel);
  result.stats_options.probe_min = PatternStatsOptions{}.probe_min * metres_per_pixel;

  std::vector<int> fragment_of_root(static_cast<std::size_t>(piece_count), -1);
  std::vector<Fragment> fragments;
  std::vector<Eigen::Vector2d> moments;
  for (std::size_t p = 0; p < static_cast<std::size_t>(piece_count); ++p) {
    const auto root = static_cast<std::size_t>(sets.find(static_cast<int>(p)));
    if (fragment_of_root[root] < 0) {
      fragment_of_root[root] = static_cast<int>(fragments.size());
      fragments.emplace_back();
      moments.push_back(Eigen::Vector2d::Zero());
    }
    const auto f = static_cast<std::size_t>(fragment_of_root[root]);
    fragments[f].area += piece_area[p];
    moments[f] += piece_area[p] * piece_centroid[p];
    fragments[f].touches_border = fragments[f].touches_border || piece_on_border[p];
  }
  // Fragments under min_fragment_px pixels at the reference resolution are not fragments, the
  // exemplar module's rule (CrackGraphOptions), which no drawing resolves: slivers where two
  // cracks meet at a grazing angle or a T is closed twice, down to 1e-8 of the area, which put
  // mass four decades below every traced fragment in Eq. 5's area histogram.
  const double min_fragment_area = CrackGraphOptions{}.min_fragment_px * metres_per_pixel * metres_per_pixel;
  for (std::size_t f = 0; f < fragments.size(); ++f) {
    if (fragments[f].area < min_fragment_area) continue;
    fragments[f].centroid = moments[f] / fragments[f].area;
    builder.add_fragment(std::move(fragments[f]));
  }

  // Polylines: chains of segments through points of degree 2, from node to node (degree ≠ 2);
  // what is left are closed loops meeting nothing.
  std::vector<std::vector<int>> at(points.size());
  for (std::size_t s = 0; s < segments.size(); ++s) {
    at[static_cast<std::size_t>(segments[s].a)].push_back(static_cast<int>(s));
    at[static_cast<std::size_t>(segments[s].b)].push_back(static_cast<int>(s));
  }
  // Nodes: points of degree ≠ 2. Lines first, then nodes: junctions joined by a crack shorter
  // than the crack width are one junction, the exemplar module's rule (CrackGraphOptions::
  // merge_factor), which a drawing of the pattern shows as one: two cracks meeting a third from
  // either side a millimetre apart are an X to `fissure analyze`, and were two T junctions and a
  // millimetre crack to the geometry (measured on the bundled tile: 18 of 268 junctions).
  struct Line {
    std::vector<Eigen::Vector2d> points;
    int start, end;  // point indices, or −1 for a closed loop meeting nothing
    int crack;
  };
  std::vector<Line> lines;
  std::vector<char> is_node(points.size(), 0);
  for (std::size_t p = 0; p < points.size(); ++p) is_node[p] = at[p].size() != 0 && at[p].size() != 2;
  std::vector<char> used(segments.size(), 0);
  auto walk = [&](int start, int first, bool loop) {
    std::vector<Eigen::Vector2d> line{points[static_cast<std::size_t>(start)].position};
    int current = start, segment = first;
    while (true) {
      used[static_cast<std::size_t>(segment)] = 1;
      const Segment& s = segments[static_cast<std::size_t>(segment)];
      current = s.a == current ? s.b : s.a;
      line.push_back(points[static_cast<std::size_t>(current)].position);
      if (is_node[static_cast<std::size_t>(current)] || current == start) break;
      const auto& next = at[static_cast<std::size_t>(current)];
      segment = next[0] == segment ? next[1] : next[0];
      if (used[static_cast<std::size_t>(segment)]) break;
    }
    lines.push_back({std::move(line), loop ? -1 : start, loop ? -1 : current, segments[static_cast<std::size_t>(first)].crack});
  };
  for (std::size_t p = 0; p < points.size(); ++p) {
    if (!is_node[p]) continue;
    for (const int s : at[p]) {
      if (!used[static_cast<std::size_t>(s)]) walk(static_cast<int>(p), s, false);
    }
  }
  for (std::size_t s = 0; s < segments.size(); ++s) {
    if (!used[s]) walk(segments[s].a, static_cast<int>(s), true);
  }
  const double merge_length = CrackGraphOptions{}.merge_factor * options.line_width_px * metres_per_pixel;
  detail::UnionFind junctions(points.size());
  std::vector<char> contracted(lines.size(), 0);
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const Line& l = lines[i];
    if (l.start < 0 || l.start == l.end) continue;
    if (at[static_cast<std::size_t>(l.start)].size() < 3 || at[static_cast<std::size_t>(l.end)].size() < 3) continue;
    if (polyline_length(l.points) >= merge_length) continue;
    junctions.unite(l.start, l.end);
    contracted[i] = 1;
  }
  // One node per set, at the mean of its points.
  std::vector<int> node_of_root(points.size(), -1);
  std::vector<Eigen::Vector2d> position_sum(points.size(), Eigen::Vector2d::Zero());
  std::vector<int> members(points.size(), 0);
  for (std::size_t p = 0; p < points.size(); ++p) {
    if (!is_node[p]) continue;
    const auto root = static_cast<std::size_t>(junctions.find(static_cast<int>(p)));
    position_sum[root] += points[p].position;
    ++members[root];
  }
  for (std::size_t p = 0; p < points.size(); ++p) {
    if (!is_node[p]) continue;
    const auto root = static_cast<std::size_t>(junctions.find(static_cast<int>(p)));
    if (node_of_root[root] < 0) {
      node_of_root[root] = builder.add_node(position_sum[root] / members[root], at[p].size() == 1 && points[p].on_border);
    }
  }
  auto node_of = [&](int p) { return p < 0 ? -1 : node_of_root[static_cast<std::size_t>(junctions.find(p))]; };
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (contracted[i]) continue;
    builder.add_crack(std::move(lines[i].points), node_of(lines[i].start), node_of(lines[i].end));
    result.source_crack.push_back(lines[i].crack);
  }
  result.graph = std::move(builder).build();
  return result;
}

}  // namespace fissure
