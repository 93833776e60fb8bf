#pragma once
// Curved closed surfaces made procedurally, shared by the mesh tests and the preparation
// benchmark (tests/bench/bench_prepare_body.cpp): a sphere, bulky and without sharp features,
// and a curved shell, as thin as the tile and with a sharp rim.

#include "fissure/mesh/surface_mesh.hpp"

#include "../support/test_shapes.hpp"  // surface_from

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

namespace fissure::test {

/// An icosphere of radius 1 (20 · 4^levels faces), outward-oriented: a curved surface whose
/// edges (dihedral deviation ≈ 10° at 3 levels) are below the feature angle, so the tet boundary
/// cuts across them.
inline SurfaceMesh icosphere(int levels) {
  const double g = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Eigen::Vector3d> v = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                                    {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  for (auto& p : v) p.normalize();
  std::vector<Eigen::Vector3i> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                                    {11, 10, 2}, {10, 7, 6}, {7, 1, 8},   {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                                    {3, 8, 9},  {4, 9, 5},  {2, 4, 11},  {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<int, int>, int> middle;
    auto mid = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      const auto [it, inserted] = middle.try_emplace(key, static_cast<int>(v.size()));
      if (inserted) v.push_back((v[a] + v[b]).normalized());
      return it->second;
    };
    std::vector<Eigen::Vector3i> next;
    for (const auto& t : f) {
      const int ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
      next.insert(next.end(), {{t[0], ab, ca}, {t[1], bc, ab}, {t[2], ca, bc}, {ab, bc, ca}});
    }
    f = std::move(next);
  }
  return surface_from(v, f, "icosphere");
}

/// A curved shell: the 1 × 1 × 0.05 m tile bent about the y axis to a mid-surface radius of 1 m
/// (a 1 rad arc, `segments` flat strips along it), outward-oriented. Its crown is at z = 0, its
/// straight ends at x = ±sin(0.5)·r; volume 0.05 m³ for the arc, less (a/n)²/6 ≈ 4e-5 of it
/// for the chords of n = 64 strips. The rim edges are sharp features, the strips' edges (≈ 0.9°) not.
inline SurfaceMesh curved_shell(int segments = 64) {
  constexpr double kRadius = 1.0, kThickness = 0.05, kArc = 1.0, kWidth = 1.0;
  std::vector<Eigen::Vector3d> v;
  std::vector<Eigen::Vector3i> f;
  // Vertex of strip edge i on side s (0 inner, 1 outer) at end e (0: y = −W/2, 1: y = +W/2).
  const auto id = [](int i, int s, int e) { return (i * 2 + s) * 2 + e; };
  for (int i = 0; i <= segments; ++i) {
    const double angle = kArc * (static_cast<double>(i) / segments - 0.5);
    for (int s = 0; s < 2; ++s) {
      for (int e = 0; e < 2; ++e) {
        const double r = kRadius + (s ? 0.5 : -0.5) * kThickness;
        v.emplace_back(r * std::sin(angle), (e ? 0.5 : -0.5) * kWidth, r * std::cos(angle) - kRadius);
      }
    }
  }
  // Quad a-b-c-d listed clockwise seen from outside; its triangles are wound the other way.
  const auto quad = [&](int a, int b, int c, int d) {
    f.emplace_back(a, c, b);
    f.emplace_back(a, d, c);
  };
  for (int i = 0; i < segments; ++i) {
    quad(id(i, 1, 0), id(i, 1, 1), id(i + 1, 1, 1), id(i + 1, 1, 0));  // outer (convex) side
    quad(id(i, 0, 0), id(i + 1, 0, 0), id(i + 1, 0, 1), id(i, 0, 1));  // inner side
    quad(id(i, 0, 0), id(i, 1, 0), id(i + 1, 1, 0), id(i + 1, 0, 0));  // y = −W/2
    quad(id(i, 0, 1), id(i + 1, 0, 1), id(i + 1, 1, 1), id(i, 1, 1));  // y = +W/2
  }
  quad(id(0, 0, 0), id(0, 0, 1), id(0, 1, 1), id(0, 1, 0));
  quad(id(segments, 0, 0), id(segments, 1, 0), id(segments, 1, 1), id(segments, 0, 1));
  return surface_from(v, f, "curved shell");
}

}  // namespace fissure::test
