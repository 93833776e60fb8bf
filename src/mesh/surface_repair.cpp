#include "fissure/mesh/surface_repair.hpp"

#include "fissure/base/error.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <unordered_map>

namespace fissure {
namespace {

struct CellKey {
  std::int64_t x, y, z;
  bool operator==(const CellKey&) const = default;
};
struct CellHash {
  std::size_t operator()(const CellKey& k) const {
    // Unsigned: the products of far-out cells wrap (in int64 that overflow is undefined, and
    // UBSan stopped the assimp import fuzz test on a vertex in cell 2.1e16).
    const auto u = [](std::int64_t c) { return static_cast<std::uint64_t>(c); };
    return static_cast<std::size_t>(u(k.x) * 73856093u ^ u(k.y) * 19349663u ^ u(k.z) * 83492791u);
  }
};

// Union of vertices within `tolerance` of an earlier one (grid of cell size `tolerance`, 27
// neighbouring cells). Returns the representative (lowest index) of every vertex.
std::vector<int> merge_close_vertices(const Eigen::MatrixX3d& v, double tolerance) {
  std::vector<int> representative(static_cast<std::size_t>(v.rows()));
  std::unordered_map<CellKey, std::vector<int>, CellHash> grid;
  for (int i = 0; i < v.rows(); ++i) {
    // Cells clamped to ±2^62 so that the conversion and the ±1 neighbours stay inside int64; far
    // vertices sharing a clamped cell are still told apart by their distance.
    const auto cell = [&](int k) {
      return static_cast<std::int64_t>(std::clamp(std::floor(v(i, k) / tolerance), -0x1p62, 0x1p62));
    };
    const CellKey key{cell(0), cell(1), cell(2)};
    int found = i;
    for (int dx = -1; dx <= 1 && found == i; ++dx)
      for (int dy = -1; dy <= 1 && found == i; ++dy)
        for (int dz = -1; dz <= 1 && found == i; ++dz) {
          const auto it = grid.find({key.x + dx, key.y + dy, key.z + dz});
          if (it == grid.end()) continue;
          for (int j : it->second) {
            if ((v.row(i) - v.row(j)).norm() <= tolerance) {
              found = j;
              break;
            }
          }
        }
    representative[static_cast<std::size_t>(i)] = found;
    if (found == i) grid[key].push_back(i);
  }
  return representative;
}

// Möller–Trumbore ray/triangle test (ray from p along d, t > 0).
bool ray_hits(const Eigen::Vector3d& p, const Eigen::Vector3d& d, const Eigen::Vector3d& a,
              const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d e1 = b - a, e2 = c - a, h = d.cross(e2);
  const double det = e1.dot(h);
  if (std::abs(det) < 1e-300) return false;
  const Eigen::Vector3d s = p - a;
  const double u = s.dot(h) / det;
  if (u < 0.0 || u > 1.0) return false;
  const Eigen::Vector3d q = s.cross(e1);
  const double w = d.dot(q) / det;
  if (w < 0.0 || u + w > 1.0) return false;
  return e2.dot(q) / det > 0.0;
}

}  // namespace

SurfaceMesh repair_surface(const SurfaceMesh& input, SurfaceRepairReport& report, const SurfaceRepairOptions& options) {
  const std::string name = input.source_name.empty() ? std::string("surface") : input.source_name;
  if (input.face_count() == 0 || input.vertex_count() == 0) throw InvalidInput(name + ": the surface has no triangles");
  if (!input.vertices.allFinite()) throw InvalidInput(name + ": a vertex has a non-finite coordinate");
  if (input.faces.minCoeff() < 0 || input.faces.maxCoeff() >= input.vertex_count()) {
    throw InvalidInput(name + ": a face references a vertex that does not exist");
  }
  const Eigen::RowVector3d lo = input.vertices.colwise().minCoeff(), hi = input.vertices.colwise().maxCoeff();
  const double diagonal = (hi - lo).norm();
  if (!(diagonal > 0.0)) throw InvalidInput(name + ": all vertices coincide");

  // 1. Merge duplicate vertices.
  const std::vector<int> representative = merge_close_vertices(input.vertices, options.merge_tolerance * diagonal);
  int merged = 0;
  for (std::size_t i = 0; i < representative.size(); ++i) merged += representative[i] != static_cast<int>(i);
  if (merged > 0) report.actions.push_back("merged " + std::to_string(merged) + " duplicate vertices");

  // 2. Drop degenerate and duplicate faces.
  std::vector<std::array<int, 3>> faces;
  std::vector<int> face_origin;  // input face index of every kept face, for messages
  std::map<std::array<int, 3>, int> seen;
  int degenerate = 0, duplicate = 0;
  const double min_twice_area = std::pow(options.merge_tolerance * diagonal, 2);
  for (Eigen::Index f = 0; f < input.face_count(); ++f) {
    std::array<int, 3> face{representative[input.faces(f, 0)], representative[input.faces(f, 1)],
                            representative[input.faces(f, 2)]};
    const Eigen::Vector3d a = input.vertices.row(face[0]), b = input.vertices.row(face[1]), c = input.vertices.row(face[2]);
    if (face[0] == face[1] || face[1] == face[2] || face[0] == face[2] || (b - a).cross(c - a).norm() <= min_twice_area) {
      ++degenerate;
      continue;
    }
    auto key = face;
    std::sort(key.begin(), key.end());
    if (!seen.emplace(key, static_cast<int>(faces.size())).second) {
      ++duplicate;
      continue;
    }
    faces.push_back(face);
    face_origin.push_back(static_cast<int>(f));
  }
  if (degenerate) report.actions.push_back("removed " + std::to_string(degenerate) + " degenerate faces");
  if (duplicate) report.actions.push_back("removed " + std::to_string(duplicate) + " duplicate faces");
  if (faces.size() < 4) throw InvalidInput(name + ": fewer than 4 usable faces");

  // Compact the vertices still in use, in index order.
  std::vector<int> new_index(static_cast<std::size_t>(input.vertex_count()), -1);
  for (const auto& face : faces)
    for (int v : face) new_index[static_cast<std::size_t>(v)] = 0;
  int used = 0;
  for (auto& slot : new_index)
    if (slot == 0) slot = used++;
  SurfaceMesh out;
  out.source_name = input.source_name;
  out.appearance = input.appearance;
  out.vertices.resize(used, 3);
  for (Eigen::Index i = 0; i < input.vertex_count(); ++i) {
    if (new_index[static_cast<std::size_t>(i)] >= 0) out.vertices.row(new_index[static_cast<std::size_t>(i)]) = input.vertices.row(i);
  }
  for (auto& face : faces)
    for (int& v : face) v = new_index[static_cast<std::size_t>(v)];
  // Messages name vertices and faces by the user's 1-based input numbers (what OBJ and PLY
  // tools show), not by the indices after merging and compaction. A merged vertex is named by
  // its lowest input number (its representative) and the others it absorbed.
  std::vector<int> input_vertex(static_cast<std::size_t>(used));
  for (Eigen::Index i = 0; i < input.vertex_count(); ++i) {
    const int slot = new_index[static_cast<std::size_t>(i)];
    if (slot >= 0) input_vertex[static_cast<std::size_t>(slot)] = static_cast<int>(i);
  }
  auto vertex_name = [&](int v) {
    const int original = input_vertex[static_cast<std::size_t>(v)];
    std::string text = "vertex " + std::to_string(original + 1);
    std::vector<int> absorbed;
    for (std::size_t i = 0; i < representative.size(); ++i) {
      if (representative[i] == original && static_cast<int>(i) != original) absorbed.push_back(static_cast<int>(i) + 1);
    }
    if (!absorbed.empty()) {
      text += " (merged with " + std::to_string(absorbed.front());
      if (absorbed.size() > 1) text += " and " + std::to_string(absorbed.size() - 1) + " more";
      text += ")";
    }
    return text;
  };
  auto face_list = [&](const std::vector<int>& kept) {
    std::string text = kept.size() == 1 ? "face " : "faces ";
    for (std::size_t i = 0; i < kept.size(); ++i) {
      if (i > 0) text += i + 1 == kept.size() ? " and " : ", ";
      text += std::to_string(face_origin[static_cast<std::size_t>(kept[i])] + 1);
    }
    return text;
  };

  // 3. Edges: every undirected edge must have exactly two faces.
  std::map<std::pair<int, int>, std::vector<int>> edge_faces;
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = faces[f][k], b = faces[f][(k + 1) % 3];
      edge_faces[{std::min(a, b), std::max(a, b)}].push_back(static_cast<int>(f));
    }
  int border = 0, overfull = 0;
  std::pair<int, int> first_border{-1, -1}, first_overfull{-1, -1};
  for (const auto& [edge, list] : edge_faces) {
    if (list.size() == 1 && border++ == 0) first_border = edge;
    if (list.size() > 2 && overfull++ == 0) first_overfull = edge;
  }
  if (border > 0) {
    throw InvalidInput(name + ": open: " + std::to_string(border) + " border edges (e.g. the edge between " +
                       vertex_name(first_border.first) + " and " + vertex_name(first_border.second) +
                       ", which only " + face_list(edge_faces[first_border]) + " has); Fissure needs a closed surface");
  }
  if (overfull > 0) {
    throw InvalidInput(name + ": non-manifold: " + std::to_string(overfull) +
                       " edges shared by more than two faces (e.g. the edge between " + vertex_name(first_overfull.first) +
                       " and " + vertex_name(first_overfull.second) + ", shared by " +
                       face_list(edge_faces[first_overfull]) + ")");
  }

  // 4. Non-manifold vertices: the faces around a vertex must form one fan.
  {
    std::vector<std::vector<int>> vertex_faces(static_cast<std::size_t>(used));
    for (std::size_t f = 0; f < faces.size(); ++f)
      for (int v : faces[f]) vertex_faces[static_cast<std::size_t>(v)].push_back(static_cast<int>(f));
    for (int v = 0; v < used; ++v) {
      const auto& around = vertex_faces[static_cast<std::size_t>(v)];
      std::vector<char> reached(around.size(), 0);
      std::vector<std::size_t> stack{0};
      reached[0] = 1;
      std::size_t count = 1;
      while (!stack.empty()) {
        const std::size_t i = stack.back();
        stack.pop_back();
        for (std::size_t j = 0; j < around.size(); ++j) {
          if (reached[j]) continue;
          // Faces i and j are fan neighbours when they share an edge through v.
          int shared = 0;
          for (int a : faces[static_cast<std::size_t>(around[i])])
            for (int b : faces[static_cast<std::size_t>(around[j])]) shared += (a == b);
          if (shared >= 2) {
            reached[j] = 1;
            ++count;
            stack.push_back(j);
          }
        }
      }
      if (count != around.size()) {
        // One face of the fan that was reached and one that was not: two sheets, one of each.
        std::size_t other = 0;
        while (reached[other]) ++other;
        throw InvalidInput(name + ": non-manifold " + vertex_name(v) + ": two surface sheets touch only there (" +
                           face_list({around[0]}) + " on one, " + face_list({around[other]}) + " on the other)");
      }
    }
  }

  // 5. Consistent orientation per connected component (flood fill across edges).
  std::vector<int> component(faces.size(), -1);
  int components = 0, flipped = 0;
  for (std::size_t seed = 0; seed < faces.size(); ++seed) {
    if (component[seed] >= 0) continue;
    component[seed] = components;
    std::vector<std::size_t> stack{seed};
    while (!stack.empty()) {
      const std::size_t f = stack.back();
      stack.pop_back();
      for (int k = 0; k < 3; ++k) {
        const int a = faces[f][k], b = faces[f][(k + 1) % 3];
        for (int g_index : edge_faces[{std::min(a, b), std::max(a, b)}]) {
          const auto g = static_cast<std::size_t>(g_index);
          if (g == f) continue;
          // Consistent neighbours traverse the shared edge in opposite directions.
          bool same_direction = false;
          for (int m = 0; m < 3; ++m) same_direction = same_direction || (faces[g][m] == a && faces[g][(m + 1) % 3] == b);
          if (component[g] < 0) {
            component[g] = components;
            if (same_direction) {
              std::swap(faces[g][1], faces[g][2]);
              ++flipped;
            }
            stack.push_back(g);
          } else if (same_direction) {
            throw InvalidInput(name + ": non-orientable surface (a Moebius-like shell: " +
                               face_list({static_cast<int>(f), g_index}) + " cannot both face outward)");
          }
        }
      }
    }
    ++components;
  }
  if (flipped) report.actions.push_back("flipped " + std::to_string(flipped) + " faces to a consistent orientation");

  // 6. Outward orientation: each shell's signed volume must be positive, except for shells
  // nested inside an odd number of others (cavities), which must be negative.
  auto vertex = [&](int v) -> Eigen::Vector3d { return out.vertices.row(v).transpose(); };
  std::vector<double> shell_volume(static_cast<std::size_t>(components), 0.0);
  for (std::size_t f = 0; f < faces.size(); ++f) {
    shell_volume[static_cast<std::size_t>(component[f])] += vertex(faces[f][0]).dot(vertex(faces[f][1]).cross(vertex(faces[f][2]))) / 6.0;
  }
  // A direction with no special alignment, so rays graze no edge of axis-aligned models.
  const Eigen::Vector3d direction = Eigen::Vector3d(0.5773, 0.5774, 0.5775).normalized();
  int reversed = 0;
  for (int c = 0; c < components; ++c) {
    std::size_t probe = 0;
    while (component[probe] != c) ++probe;
    const Eigen::Vector3d start = (vertex(faces[probe][0]) + vertex(faces[probe][1]) + vertex(faces[probe][2])) / 3.0;
    int crossings = 0;
    for (std::size_t f = 0; f < faces.size(); ++f) {
      if (component[f] != c && ray_hits(start, direction, vertex(faces[f][0]), vertex(faces[f][1]), vertex(faces[f][2]))) {
        ++crossings;
      }
    }
    const bool cavity = crossings % 2 == 1;
    const double volume = shell_volume[static_cast<std::size_t>(c)];
    if ((volume < 0.0) != cavity) {
      for (std::size_t f = 0; f < faces.size(); ++f)
        if (component[f] == c) std::swap(faces[f][1], faces[f][2]);
      ++reversed;
    }
  }
  if (reversed) report.actions.push_back("reversed " + std::to_string(reversed) + " shell(s) to face outward");

  out.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (int k = 0; k < 3; ++k) out.faces(static_cast<Eigen::Index>(f), k) = faces[f][k];

  if (options.check_self_intersections) {
    const long pairs = count_self_intersections(out);
    if (pairs > 0) throw InvalidInput(name + ": self-intersecting: " + std::to_string(pairs) + " pairs of faces cross");
  }
  if (!(signed_volume(out) > 0.0)) throw InvalidInput(name + ": the surface encloses no volume");
  return out;
}

}  // namespace fissure
