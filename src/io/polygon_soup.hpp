#pragma once
// Private to io: the vertices and faces a strict surface reader collects, checked as they come
// in, and turned into a triangle SurfaceMesh.
//
// Every vertex is checked for finite coordinates and every face for its vertex count and index
// range when it is added, so each refusal names the vertex or face by its 1-based number in the
// file: "part.ply: vertex 17 has a non-finite coordinate", "part.obj:40: face 5 references vertex
// 12, but the file has 8 vertices". Faces are triangulated by triangulate_polygon().

#include "byte_cursor.hpp"

#include "fissure/mesh/surface_mesh.hpp"

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace fissure::io_detail {

class PolygonSoup {
public:
  /// `index_base`: 1 when the format counts vertices from 1 in its faces (OBJ), 0 otherwise
  /// (PLY, OFF); indices are reported as the file writes them.
  PolygonSoup(std::string name, int index_base) : m_name(std::move(name)), m_index_base(index_base) {}

  /// For formats whose header declares the counts (PLY, OFF): faces may be checked against the
  /// vertex count before the vertices are read, and storage is reserved once. Throws
  /// InvalidInput through require_memory when the counts need more memory than the machine has.
  /// Precondition: the counts were checked against the file's size (ByteCursor::check_count).
  void declare(std::uint64_t vertices, std::uint64_t faces);

  std::uint64_t vertex_count() const { return m_xyz.size() / 3; }
  std::uint64_t face_count() const { return m_faces_read; }

  /// Adds vertex number vertex_count() + 1. Throws IoError "<at>vertex N has a non-finite
  /// coordinate" naming it.
  void add_vertex(const ByteCursor& at, double x, double y, double z);

  /// Adds face number face_count() + 1 with vertex indices as the file writes them. Throws
  /// IoError naming the face when it has fewer than 3 vertices or an index that is not one of
  /// the file's vertices (the declared count, else the vertices added so far). `uv_indices`,
  /// empty or one per vertex: 0-based indices of texture coordinates added so far (−1: none).
  void add_face(const ByteCursor& at, std::span<const std::int64_t> indices, std::span<const std::int64_t> uv_indices = {});

  /// Texture coordinate number uv_count() + 1 (OBJ's `vt`). Throws IoError naming it when a
  /// value is not finite.
  void add_uv(const ByteCursor& at, double u, double v);
  std::uint64_t uv_count() const { return m_uv.size() / 2; }

  /// The faces added from now on use the material `name` (OBJ's `usemtl`).
  void use_material(std::string_view name);

  /// The faces added from now on belong to the object `name` (OBJ's `o`); faces before the first
  /// belong to object 0, named "".
  void use_object(std::string_view name);
  /// After finish(): the objects' names, and per triangle of the surface its object.
  const std::vector<std::string>& objects() const { return m_objects; }
  const std::vector<int>& triangle_objects() const { return m_triangle_object; }

  /// The triangle surface (not yet repaired); source_name is the file's name. Throws
  /// InvalidInput when no face was read (`format`, e.g. "an OBJ file", completes the message).
  SurfaceMesh finish(const char* format);

private:
  void triangulate(std::span<const int> face, std::uint64_t number);
  // The uvs and material of the triangles from m_triangles[first] on (the face in m_scratch).
  void record_appearance(std::size_t first, std::span<const std::int64_t> uv_indices);

  std::string m_name;
  int m_index_base;
  std::uint64_t m_declared_vertices = UINT64_MAX;
  std::vector<double> m_xyz;       // 3 per vertex
  std::vector<int> m_triangles;    // 3 per triangle
  std::uint64_t m_faces_read = 0;
  // Faces that name vertices not read yet (a PLY whose face element comes first): triangulated
  // at the end, when their vertices are known.
  std::vector<int> m_pending;              // indices of all pending faces, back to back
  std::vector<std::size_t> m_pending_end;  // end of each pending face in m_pending
  std::vector<std::uint64_t> m_pending_number;
  std::vector<int> m_scratch;
  // Appearance (OBJ): texture coordinates, and per triangle its corners' uv indices (−1: none)
  // and its material; faces before the first `usemtl` use material 0, named "surface".
  std::vector<double> m_uv;                 // 2 per texture coordinate
  std::vector<int> m_triangle_uv;           // 3 per triangle, once a face has uvs (m_has_uvs)
  std::vector<int> m_triangle_material;     // 1 per triangle, only once a material is used
  std::vector<std::string> m_materials{"surface"};
  int m_material = 0;
  std::vector<int> m_triangle_object;       // 1 per triangle
  std::vector<std::string> m_objects{""};
  int m_object = 0;
  bool m_has_appearance = false;
  bool m_has_uvs = false;
};

}  // namespace fissure::io_detail
