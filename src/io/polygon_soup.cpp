#include "polygon_soup.hpp"

#include "polygon_triangulation.hpp"

#include "fissure/base/memory.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fissure::io_detail {
namespace {

// Vertex indices are int in SurfaceMesh.
constexpr std::uint64_t kMaxVertices = static_cast<std::uint64_t>(std::numeric_limits<int>::max());

}  // namespace

void PolygonSoup::declare(std::uint64_t vertices, std::uint64_t faces) {
  if (vertices > kMaxVertices) {
    throw IoError(m_name + ": " + std::to_string(vertices) + " vertices are more than Fissure can index (" +
                  std::to_string(kMaxVertices) + ")");
  }
  // Each vertex is 3 doubles and each face at least one triangle of 3 ints, held twice while
  // finish() copies them into the SurfaceMesh.
  const double bytes = 2.0 * (24.0 * static_cast<double>(vertices) + 12.0 * static_cast<double>(faces));
  require_memory(bytes, 0, m_name + ": reading " + std::to_string(vertices) + " vertices and " + std::to_string(faces) + " faces");
  m_declared_vertices = vertices;
  m_xyz.reserve(3 * vertices);
  m_triangles.reserve(3 * faces);
}

void PolygonSoup::add_vertex(const ByteCursor& at, double x, double y, double z) {
  const std::uint64_t number = vertex_count() + 1;
  if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) {
    throw IoError(at.where() + "vertex " + std::to_string(number) + " has a non-finite coordinate");
  }
  if (number > kMaxVertices) throw IoError(m_name + ": more than " + std::to_string(kMaxVertices) + " vertices");
  m_xyz.insert(m_xyz.end(), {x, y, z});
}

void PolygonSoup::add_uv(const ByteCursor& at, double u, double v) {
  if (!std::isfinite(u) || !std::isfinite(v)) {
    throw IoError(at.where() + "texture coordinate " + std::to_string(uv_count() + 1) + " is not finite");
  }
  m_uv.insert(m_uv.end(), {u, v});
}

void PolygonSoup::use_material(std::string_view name) {
  const auto it = std::find(m_materials.begin(), m_materials.end(), name);
  m_material = static_cast<int>(it - m_materials.begin());
  if (it == m_materials.end()) m_materials.emplace_back(name);
  m_has_appearance = true;
}

void PolygonSoup::use_object(std::string_view name) {
  const auto it = std::find(m_objects.begin(), m_objects.end(), name);
  m_object = static_cast<int>(it - m_objects.begin());
  if (it == m_objects.end()) m_objects.emplace_back(name);
}

void PolygonSoup::add_face(const ByteCursor& at, std::span<const std::int64_t> indices, std::span<const std::int64_t> uv_indices) {
  const std::uint64_t number = ++m_faces_read;
  if (indices.size() < 3) {
    throw IoError(at.where() + "face " + std::to_string(number) + " has " + std::to_string(indices.size()) +
                  " vertices; a face needs at least 3");
  }
  const bool declared = m_declared_vertices != UINT64_MAX;
  const std::uint64_t limit = declared ? m_declared_vertices : vertex_count();
  m_scratch.clear();
  bool known = true;
  for (const std::int64_t written : indices) {
    const std::int64_t index = written - m_index_base;
    if (index < 0 || static_cast<std::uint64_t>(index) >= limit) {
      std::string range = declared ? "the file has " + std::to_string(limit) + " vertices"
                                   : "only " + std::to_string(limit) + " vertices come before it";
      if (m_index_base == 0 && limit > 0) range += " (indices 0 to " + std::to_string(limit - 1) + ")";
      throw IoError(at.where() + "face " + std::to_string(number) + " references vertex " +
                    std::string(m_index_base == 0 ? "index " : "") + std::to_string(written) + ", but " + range);
    }
    m_scratch.push_back(static_cast<int>(index));
    known = known && static_cast<std::uint64_t>(index) < vertex_count();
  }
  if (known) {
    const std::size_t first = m_triangles.size();
    triangulate(m_scratch, number);
    if (!uv_indices.empty() || m_has_appearance) record_appearance(first, uv_indices);
    m_triangle_object.resize(m_triangles.size() / 3, m_object);
  } else {
    m_pending.insert(m_pending.end(), m_scratch.begin(), m_scratch.end());
    m_pending_end.push_back(m_pending.size());
    m_pending_number.push_back(number);
  }
}

void PolygonSoup::record_appearance(std::size_t first, std::span<const std::int64_t> uv_indices) {
  const std::size_t before = first / 3, after = m_triangles.size() / 3;
  // Triangles of earlier faces had no uvs and material 0.
  if (!uv_indices.empty() && !m_has_uvs) {
    m_triangle_uv.assign(3 * before, -1);
    m_has_uvs = true;
  }
  if (m_has_uvs) {
    for (std::size_t k = first; k < m_triangles.size(); ++k) {
      // The triangle's corner is one of the face's vertices: its uv is that vertex's.
      const auto at = std::find(m_scratch.begin(), m_scratch.end(), m_triangles[k]) - m_scratch.begin();
      m_triangle_uv.push_back(uv_indices.empty() ? -1 : static_cast<int>(uv_indices[static_cast<std::size_t>(at)]));
    }
  }
  m_triangle_material.resize(before, 0);
  m_triangle_material.resize(after, m_material);
  m_has_appearance = true;
}

void PolygonSoup::triangulate(std::span<const int> face, std::uint64_t number) {
  if (!triangulate_polygon(m_xyz, face, m_triangles)) {
    throw IoError(m_name + ": face " + std::to_string(number) + " has " + std::to_string(face.size()) +
                  " vertices and is not convex; Fissure triangulates non-convex faces of up to " +
                  std::to_string(kMaxConcaveFaceVertices) + " vertices");
  }
}

SurfaceMesh PolygonSoup::finish(const char* format) {
  if (m_declared_vertices != UINT64_MAX && vertex_count() != m_declared_vertices) {
    throw IoError(m_name + ": the header declares " + std::to_string(m_declared_vertices) + " vertices, the file holds " +
                  std::to_string(vertex_count()));
  }
  std::size_t begin = 0;
  for (std::size_t k = 0; k < m_pending_end.size(); ++k) {
    const std::span<const int> face(m_pending.data() + begin, m_pending_end[k] - begin);
    for (const int v : face) {
      if (static_cast<std::uint64_t>(v) >= vertex_count()) {
        throw IoError(m_name + ": face " + std::to_string(m_pending_number[k]) + " references vertex " +
                      std::string(m_index_base == 0 ? "index " : "") + std::to_string(v + m_index_base) +
                      ", which the file does not define");
      }
    }
    triangulate(face, m_pending_number[k]);
    begin = m_pending_end[k];
  }
  if (m_triangles.empty()) throw InvalidInput(m_name + ": holds no faces (is it really " + std::string(format) + "?)");
  m_triangle_object.resize(m_triangles.size() / 3, 0);  // pending faces (PLY) have no object

  SurfaceMesh surface;
  surface.source_name = m_name;
  surface.vertices.resize(static_cast<Eigen::Index>(vertex_count()), 3);
  for (Eigen::Index v = 0; v < surface.vertices.rows(); ++v) {
    for (int axis = 0; axis < 3; ++axis) surface.vertices(v, axis) = m_xyz[3 * static_cast<std::size_t>(v) + static_cast<std::size_t>(axis)];
  }
  std::vector<double>().swap(m_xyz);
  surface.faces.resize(static_cast<Eigen::Index>(m_triangles.size() / 3), 3);
  for (Eigen::Index f = 0; f < surface.faces.rows(); ++f) {
    for (int k = 0; k < 3; ++k) surface.faces(f, k) = m_triangles[3 * static_cast<std::size_t>(f) + static_cast<std::size_t>(k)];
  }
  if (m_has_appearance) {
    SurfaceAppearance& a = surface.appearance;
    const Eigen::Index n = surface.faces.rows();
    for (const std::string& name : m_materials) a.materials.push_back({name});
    a.corners.resize(n, 9);
    for (Eigen::Index f = 0; f < n; ++f)
      for (int k = 0; k < 3; ++k) a.corners.row(f).segment<3>(3 * k) = surface.vertices.row(surface.faces(f, k));
    if (m_has_uvs) {
      m_triangle_uv.resize(3 * static_cast<std::size_t>(n), -1);
      a.uvs.setZero(n, 6);
      for (Eigen::Index f = 0; f < n; ++f)
        for (int k = 0; k < 3; ++k) {
          const int uv = m_triangle_uv[3 * static_cast<std::size_t>(f) + static_cast<std::size_t>(k)];
          if (uv >= 0) a.uvs.row(f).segment<2>(2 * k) << m_uv[2 * static_cast<std::size_t>(uv)], m_uv[2 * static_cast<std::size_t>(uv) + 1];
        }
    }
    m_triangle_material.resize(static_cast<std::size_t>(n), 0);
    a.material = std::move(m_triangle_material);
    a.drop_unused_materials();
  }
  return surface;
}

}  // namespace fissure::io_detail
