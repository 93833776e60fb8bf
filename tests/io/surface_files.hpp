#pragma once
// Test-only writers of the simple surface formats, from a polygon list, so the readers are
// tested against files written independently of them (and of assimp).

#include "fissure/mesh/surface_mesh.hpp"

#include <bit>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

namespace fissure::test {

struct Polygons {
  Eigen::MatrixX3d vertices;
  std::vector<std::vector<int>> faces;  // 0-based, counter-clockwise from outside
};

inline Polygons polygons_of(const SurfaceMesh& s) {
  Polygons p{s.vertices, {}};
  for (Eigen::Index f = 0; f < s.face_count(); ++f) p.faces.push_back({s.faces(f, 0), s.faces(f, 1), s.faces(f, 2)});
  return p;
}

/// The L prism of test_shapes.hpp with its two L-shaped caps as single non-convex hexagons and
/// its six sides as quads: 12 vertices, 8 faces, volume 1.5 m³.
inline Polygons l_prism_polygons() {
  Polygons p;
  const double xy[6][2] = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  p.vertices.resize(12, 3);
  for (int i = 0; i < 6; ++i) {
    p.vertices.row(i) << xy[i][0], xy[i][1], 0.0;
    p.vertices.row(6 + i) << xy[i][0], xy[i][1], 0.5;
  }
  p.faces.push_back({0, 5, 4, 3, 2, 1});   // bottom, facing −z
  p.faces.push_back({6, 7, 8, 9, 10, 11});  // top, facing +z
  for (int i = 0; i < 6; ++i) {
    const int j = (i + 1) % 6;
    p.faces.push_back({i, j, 6 + j, 6 + i});
  }
  return p;
}

/// A 1 × 2 × 3 m box with a corner at the origin as six quads: 8 vertices, volume 6 m³.
inline Polygons box_polygons() {
  Polygons box;
  box.vertices.resize(8, 3);
  for (int v = 0; v < 8; ++v) box.vertices.row(v) << (v & 1) * 1.0, (v >> 1 & 1) * 2.0, (v >> 2 & 1) * 3.0;
  box.faces = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  return box;
}

inline std::string to_obj(const Polygons& p) {
  std::ostringstream out;
  out.precision(17);
  out << "# written by the Fissure tests\no solid\n";
  for (Eigen::Index v = 0; v < p.vertices.rows(); ++v) out << "v " << p.vertices(v, 0) << ' ' << p.vertices(v, 1) << ' ' << p.vertices(v, 2) << '\n';
  for (const auto& f : p.faces) {
    out << 'f';
    for (int v : f) out << ' ' << v + 1 << "//" << v + 1;  // with a normal index, as exporters write
    out << '\n';
  }
  return out.str();
}

// An OBJ as a modeller writes a textured, multi-material one: a `vt` per vertex (its x and y),
// faces "v/vt/vn", and `usemtl` switching between two materials face by face.
inline std::string to_obj_textured(const Polygons& p) {
  std::ostringstream out;
  out.precision(17);
  out << "# written by the Fissure tests\nmtllib solid.mtl\no solid\n";
  for (Eigen::Index v = 0; v < p.vertices.rows(); ++v) out << "v " << p.vertices(v, 0) << ' ' << p.vertices(v, 1) << ' ' << p.vertices(v, 2) << '\n';
  for (Eigen::Index v = 0; v < p.vertices.rows(); ++v) out << "vt " << p.vertices(v, 0) << ' ' << p.vertices(v, 1) << '\n';
  for (std::size_t k = 0; k < p.faces.size(); ++k) {
    out << "usemtl " << (k % 2 ? "stone" : "grout") << "\nf";
    for (int v : p.faces[k]) out << ' ' << v + 1 << '/' << v + 1 << '/' << v + 1;
    out << '\n';
  }
  return out.str();
}

// The vertex and face lines OFF and ASCII PLY share: "x y z" rows, then "n v0 v1 …" rows.
inline void write_vertex_and_face_lines(std::ostream& out, const Polygons& p) {
  for (Eigen::Index v = 0; v < p.vertices.rows(); ++v) out << p.vertices(v, 0) << ' ' << p.vertices(v, 1) << ' ' << p.vertices(v, 2) << '\n';
  for (const auto& f : p.faces) {
    out << f.size();
    for (int v : f) out << ' ' << v;
    out << '\n';
  }
}

inline std::string to_off(const Polygons& p) {
  std::ostringstream out;
  out.precision(17);
  out << "OFF\n# comment\n" << p.vertices.rows() << ' ' << p.faces.size() << " 0\n";
  write_vertex_and_face_lines(out, p);
  return out.str();
}

inline std::string ply_header(const Polygons& p, const char* format, const char* coordinate) {
  return std::string("ply\nformat ") + format + " 1.0\ncomment written by the Fissure tests\nelement vertex " +
         std::to_string(p.vertices.rows()) + "\nproperty " + coordinate + " x\nproperty " + coordinate + " y\nproperty " +
         coordinate + " z\nelement face " + std::to_string(p.faces.size()) +
         "\nproperty list uchar int vertex_indices\nend_header\n";
}

inline std::string to_ply(const Polygons& p) {
  std::ostringstream out;
  out.precision(17);
  out << ply_header(p, "ascii", "double");
  write_vertex_and_face_lines(out, p);
  return out.str();
}

template <class T>
void put(std::string& out, T value, bool big_endian) {
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  if (big_endian != (std::endian::native == std::endian::big)) {
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(raw[i], raw[sizeof(T) - 1 - i]);
  }
  out.append(raw, sizeof(T));
}

/// Binary PLY with float32 coordinates (exact for the test shapes' coordinates).
inline std::string to_ply_binary(const Polygons& p, bool big_endian) {
  std::string out = ply_header(p, big_endian ? "binary_big_endian" : "binary_little_endian", "float");
  for (Eigen::Index v = 0; v < p.vertices.rows(); ++v)
    for (int k = 0; k < 3; ++k) put(out, static_cast<float>(p.vertices(v, k)), big_endian);
  for (const auto& f : p.faces) {
    put(out, static_cast<std::uint8_t>(f.size()), big_endian);
    for (int v : f) put(out, static_cast<std::int32_t>(v), big_endian);
  }
  return out;
}

// STL holds triangles only: polygons are fanned (fine for convex ones; the tests pass triangles).
inline std::vector<std::vector<int>> triangles_of(const Polygons& p) {
  std::vector<std::vector<int>> t;
  for (const auto& f : p.faces)
    for (std::size_t k = 1; k + 1 < f.size(); ++k) t.push_back({f[0], f[k], f[k + 1]});
  return t;
}

inline std::string to_stl(const Polygons& p) {
  std::ostringstream out;
  out.precision(17);
  out << "solid test\n";
  for (const auto& t : triangles_of(p)) {
    out << "  facet normal 0 0 0\n    outer loop\n";
    for (int v : t) out << "      vertex " << p.vertices(v, 0) << ' ' << p.vertices(v, 1) << ' ' << p.vertices(v, 2) << '\n';
    out << "    endloop\n  endfacet\n";
  }
  out << "endsolid test\n";
  return out.str();
}

inline std::string to_stl_binary(const Polygons& p) {
  std::string out = "solid binary STL whose header starts like an ASCII one";
  out.resize(80, ' ');
  const auto triangles = triangles_of(p);
  put(out, static_cast<std::uint32_t>(triangles.size()), false);
  for (const auto& t : triangles) {
    for (int k = 0; k < 3; ++k) put(out, 0.0f, false);
    for (int v : t)
      for (int k = 0; k < 3; ++k) put(out, static_cast<float>(p.vertices(v, k)), false);
    put(out, std::uint16_t{0}, false);
  }
  return out;
}

/// A plain, fast write for test files (the product's writes go through write_file_atomically;
/// thousands of fuzz files need no fsync).
inline void write_test_file(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

}  // namespace fissure::test
