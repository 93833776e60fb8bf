#pragma once
// Closed test surfaces shared by the mesh, io, fracture and CLI tests.

#include "fissure/mesh/surface_mesh.hpp"

#include <Eigen/Core>

#include <cmath>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

namespace fissure::test {

/// A surface from vertex and triangle lists (as given: no orientation fix).
inline SurfaceMesh surface_from(const std::vector<Eigen::Vector3d>& v, const std::vector<Eigen::Vector3i>& f,
                                const std::string& name) {
  SurfaceMesh s;
  s.source_name = name;
  s.vertices.resize(static_cast<Eigen::Index>(v.size()), 3);
  for (std::size_t i = 0; i < v.size(); ++i) s.vertices.row(static_cast<Eigen::Index>(i)) = v[i].transpose();
  s.faces.resize(static_cast<Eigen::Index>(f.size()), 3);
  for (std::size_t i = 0; i < f.size(); ++i) s.faces.row(static_cast<Eigen::Index>(i)) = f[i].transpose();
  return s;
}

/// An L-shaped prism, outward-oriented: the L (0,0)-(2,0)-(2,1)-(1,1)-(1,2)-(0,2) extruded from
/// z = 0 to 0.5; volume 1.5 m³; non-convex.
inline SurfaceMesh l_prism() {
  SurfaceMesh s;
  s.source_name = "L prism";
  const double xy[6][2] = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  s.vertices.resize(12, 3);
  for (int i = 0; i < 6; ++i) {
    s.vertices.row(i) << xy[i][0], xy[i][1], 0.0;
    s.vertices.row(6 + i) << xy[i][0], xy[i][1], 0.5;
  }
  std::vector<Eigen::Vector3i> faces;
  const int cap[4][3] = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}};  // fan from corner 0
  for (const auto& t : cap) {
    faces.emplace_back(t[0], t[2], t[1]);              // bottom, facing −z
    faces.emplace_back(6 + t[0], 6 + t[1], 6 + t[2]);  // top, facing +z
  }
  for (int i = 0; i < 6; ++i) {
    const int j = (i + 1) % 6;
    faces.emplace_back(i, j, 6 + j);
    faces.emplace_back(i, 6 + j, 6 + i);
  }
  s.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f) s.faces.row(static_cast<Eigen::Index>(f)) = faces[f].transpose();
  return s;
}

/// The closed surface swept by revolving a closed profile loop of (r, z) points (r ≥ 0; points
/// with r = 0 lie on the axis, which is z) about z in `segments` steps, outward-oriented
/// whichever way the loop runs. Consecutive axis points are the axis itself and make no face.
inline SurfaceMesh revolve_profile(const std::vector<std::pair<double, double>>& profile, int segments,
                                   const std::string& name) {
  constexpr double kTwoPi = 6.28318530717958647692;
  std::vector<Eigen::Vector3d> vertices;
  std::vector<int> first(profile.size());  // first vertex of each profile point's ring
  for (std::size_t i = 0; i < profile.size(); ++i) {
    first[i] = static_cast<int>(vertices.size());
    const auto [r, z] = profile[i];
    if (r == 0.0) {
      vertices.emplace_back(0.0, 0.0, z);
      continue;
    }
    for (int j = 0; j < segments; ++j) {
      const double a = kTwoPi * j / segments;
      vertices.emplace_back(r * std::cos(a), r * std::sin(a), z);
    }
  }
  auto at = [&](std::size_t i, int j) { return profile[i].first == 0.0 ? first[i] : first[i] + j % segments; };
  std::vector<Eigen::Vector3i> faces;
  for (std::size_t i = 0; i < profile.size(); ++i) {
    const std::size_t k = (i + 1) % profile.size();
    const bool a_axis = profile[i].first == 0.0, b_axis = profile[k].first == 0.0;
    if (a_axis && b_axis) continue;
    for (int j = 0; j < segments; ++j) {
      // One rule for every edge of the loop: neighbouring edges then use each ring edge in
      // opposite directions, so the orientation is consistent.
      if (!a_axis) faces.emplace_back(at(i, j), at(i, j + 1), at(k, j + 1));
      if (!b_axis) faces.emplace_back(at(i, j), at(k, j + 1), at(k, j));
    }
  }
  SurfaceMesh s = surface_from(vertices, faces, name);
  if (signed_volume(s) < 0.0) s.faces.col(1).swap(s.faces.col(2));
  return s;
}

/// A bowl: a hemispherical shell (outer radius `outer`, wall `wall`, rim flat at the equator)
/// standing on a foot ring (radii 0.44·outer and 0.35·outer, its sole `foot` below the bottom of
/// the shell), axis z, resting on z = 0. Default: a 16 cm ceramic bowl with a 6 mm wall.
/// A curved body for the default fracture scenario: it rests on its foot ring's sole, its
/// up-facing face nearest the centre is the inside floor.
inline SurfaceMesh bowl(double outer = 0.08, double wall = 0.006, double foot = 0.005, int segments = 64) {
  const double centre = outer + foot, inner = outer - wall;
  const double foot_out = 0.44 * outer, foot_in = 0.35 * outer;
  auto outer_z = [&](double r) { return centre - std::sqrt(outer * outer - r * r); };
  std::vector<std::pair<double, double>> p;
  p.emplace_back(0.0, centre - inner);  // inside floor, on the axis
  const int arc = 16;
  for (int i = 1; i <= arc; ++i) {  // inner sphere, up to the rim
    const double a = 1.5707963267948966 * i / arc;
    p.emplace_back(inner * std::sin(a), centre - inner * std::cos(a));
  }
  for (int i = arc; i >= 0; --i) {  // outer sphere, down to the foot ring
    const double a = 1.5707963267948966 * i / arc;
    const double r = outer * std::sin(a);
    if (r <= foot_out) break;
    p.emplace_back(r, centre - outer * std::cos(a));
  }
  p.emplace_back(foot_out, outer_z(foot_out));
  p.emplace_back(foot_out, 0.0);  // the foot ring's sole
  p.emplace_back(foot_in, 0.0);
  p.emplace_back(foot_in, outer_z(foot_in));
  for (double r : {0.66 * foot_in, 0.33 * foot_in}) p.emplace_back(r, outer_z(r));  // the ceiling inside the ring
  p.emplace_back(0.0, centre - outer);
  return revolve_profile(p, segments, "bowl");
}

/// A basin: an open box `length` × `width` × `depth` (x, y, z) with walls and floor `wall`
/// thick, centred on the axis in x and y, resting on z = 0. Default: a 50 × 40 × 20 cm ceramic
/// sink with 2 cm walls. Outward-oriented, 16 vertices.
inline SurfaceMesh basin(double length = 0.5, double width = 0.4, double depth = 0.2, double wall = 0.02) {
  SurfaceMesh s;
  s.source_name = "basin";
  const double x = 0.5 * length, y = 0.5 * width, xi = x - wall, yi = y - wall;
  // Rings of 4 corners, counter-clockwise seen from +z: outer bottom, outer top, inner top, floor.
  const double ring[4][3] = {{x, y, 0.0}, {x, y, depth}, {xi, yi, depth}, {xi, yi, wall}};
  const double sx[4] = {-1, 1, 1, -1}, sy[4] = {-1, -1, 1, 1};
  s.vertices.resize(16, 3);
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) s.vertices.row(4 * r + c) << sx[c] * ring[r][0], sy[c] * ring[r][1], ring[r][2];
  }
  std::vector<Eigen::Vector3i> faces = {{0, 2, 1}, {0, 3, 2}, {12, 13, 14}, {12, 14, 15}};  // bottom, floor
  for (int r = 0; r < 3; ++r) {  // outer walls, rim, inner walls: bands between consecutive rings
    for (int c = 0; c < 4; ++c) {
      const int d = (c + 1) % 4;
      faces.emplace_back(4 * r + c, 4 * r + d, 4 * (r + 1) + d);
      faces.emplace_back(4 * r + c, 4 * (r + 1) + d, 4 * (r + 1) + c);
    }
  }
  s.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f) s.faces.row(static_cast<Eigen::Index>(f)) = faces[f].transpose();
  if (signed_volume(s) < 0.0) s.faces.col(1).swap(s.faces.col(2));
  return s;
}

/// Writes `surface` as a Wavefront OBJ (what a user exports from a modeller), as Blender writes
/// its Z-up models to OBJ, which is Y up: (x, y, z) → (x, z, −y), a rotation.
inline void write_obj(const SurfaceMesh& surface, const std::string& path) {
  std::ofstream out(path);
  out.precision(17);
  for (Eigen::Index v = 0; v < surface.vertex_count(); ++v) {
    out << "v " << surface.vertices(v, 0) << ' ' << surface.vertices(v, 2) << ' ' << -surface.vertices(v, 1) << '\n';
  }
  for (Eigen::Index f = 0; f < surface.face_count(); ++f) {
    out << "f " << surface.faces(f, 0) + 1 << ' ' << surface.faces(f, 1) + 1 << ' ' << surface.faces(f, 2) + 1 << '\n';
  }
}

}  // namespace fissure::test
